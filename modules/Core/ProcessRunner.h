#ifndef bender_ProcessRunner_h
#define bender_ProcessRunner_h

// The one place that starts other programs (OpenFOAM's Allrun, a private Xvfb): POSIX fork and
// exec behind two small types, so that no workflow writes pipes, waitpid or signals itself.
// The programs run as separate processes (never linked): their exit status and output are
// all Bender sees of them.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace bender
{

/// A program to run to completion.
struct ProcessOptions
{
  /// The program and its arguments; argv[0] is a path, or a name looked up on PATH.
  std::vector<std::string> argv;
  /// The folder it runs in; empty: the caller's.
  std::string workingDirectory;
  /// Its output (stdout and stderr together) is also written here; empty: nowhere.
  std::string logPath;
  /// Append to logPath instead of replacing it.
  bool appendLog = false;
  /// Each line of its output (without the newline), as it comes, on the caller's thread.
  std::function<void(const std::string& line)> onLine;
  /// Seconds after which it is stopped (result.timedOut); 0: no limit.
  double timeoutSeconds = 0.0;
  /// When set (from any thread), it is stopped within about 0.1 s (result.cancelled).
  const std::atomic<bool>* cancel = nullptr;
};

/// How a program ended.
struct ProcessResult
{
  int exitCode = -1;      ///< its exit status; -1 when a signal ended it
  int signal = 0;         ///< the signal that ended it; 0 when it exited
  bool timedOut = false;  ///< stopped by ProcessOptions::timeoutSeconds
  bool cancelled = false; ///< stopped by ProcessOptions::cancel
  std::string lastLine;   ///< the last non-empty line of its output
  bool Succeeded() const { return this->exitCode == 0 && !this->timedOut && !this->cancelled; }
};

/// Runs options.argv with stdin from /dev/null and stdout and stderr read by the caller (to
/// onLine and the log), waits for it and says how it ended. A program that can be stopped
/// (a timeout or a cancel flag given) runs in its own process group, and stopping it stops
/// what it started too (SIGTERM, then SIGKILL after 2 s). Throws EnvironmentError (one line
/// naming the program) when it cannot be started: not found, not executable, no such working
/// folder, the log cannot be opened, no process left.
ProcessResult RunProcess(const ProcessOptions& options);

/// A program left running beside the caller (a private X server): its output goes where the
/// caller's goes. Stopped (SIGTERM, waited for) by Stop or the destructor.
class BackgroundProcess
{
public:
  BackgroundProcess() = default;
  ~BackgroundProcess();
  BackgroundProcess(const BackgroundProcess&) = delete;
  BackgroundProcess& operator=(const BackgroundProcess&) = delete;

  /// Starts argv (argv[0] a path or a name on PATH; stdin from /dev/null). Throws
  /// EnvironmentError like RunProcess; InputError when one is already running.
  void Start(const std::vector<std::string>& argv);
  /// True while the program runs (an exited one is reaped here).
  bool Running();
  /// Stops the program and waits for it; nothing when none runs.
  void Stop();

private:
  long Pid = -1;
};

/// The path of the executable `name` in PATH's folders (an empty folder is the current one);
/// empty when there is none. A name with a slash is returned when it is executable.
std::string FindExecutable(const std::string& name);

} // namespace bender

#endif
