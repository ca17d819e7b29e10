#ifndef bender_Progress_h
#define bender_Progress_h

#include "BenderErrors.h"

#include <atomic>
#include <functional>
#include <string>

namespace bender
{

/// Progress reporting and cancellation for Bender's long-running calls (segmentation, the
/// workflows of bender_logic). Both members are optional. The callback is called on the thread
/// that runs the work (a GUI marshals it to its own thread); the cancel flag may be set from any
/// thread and is polled between and inside stages; a cancelled call throws bender::Cancelled
/// (or a subclass) and returns nothing.
struct ProgressReporter
{
  /// stage: short name ("read", "threshold", "fill holes", "marching cubes", "warp 2", ...);
  /// fraction: progress of that stage in [0, 1].
  std::function<void(const std::string& stage, double fraction)> onProgress;
  const std::atomic<bool>* cancel = nullptr;

  void Report(const std::string& stage, double fraction) const
  {
    if (this->onProgress)
    {
      this->onProgress(stage, fraction);
    }
  }
  bool Cancelled() const { return this->cancel && this->cancel->load(); }
  /// Throws bender::Cancelled("cancelled during <stage>") when the flag is set.
  void ThrowIfCancelled(const std::string& stage) const;
};

} // namespace bender

#endif
