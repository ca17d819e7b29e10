#ifndef bender_SignalGuard_h
#define bender_SignalGuard_h

// Ctrl+C (SIGINT) and SIGTERM for the long commands (tracker, sweep): while a SignalGuard
// lives, either signal sets a flag instead of ending the process, so that the command stops
// its work cleanly and leaves its files consistent.

#include <atomic>

namespace bender
{

class SignalGuard
{
public:
  /// Clears the flag and installs the handlers; the destructor restores the previous ones.
  SignalGuard();
  ~SignalGuard();
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

  /// Set by SIGINT or SIGTERM (a lock-free atomic, safe to set from the handler); the cancel
  /// flag of a ProgressReporter.
  const std::atomic<bool>* Flag() const;
  bool Interrupted() const { return this->Flag()->load(); }

private:
  void (*OldInt)(int) = nullptr;
  void (*OldTerm)(int) = nullptr;
};

} // namespace bender

#endif
