#ifndef bender_Progress_h
#define bender_Progress_h

#include "SegmentationErrors.h"

#include <atomic>
#include <functional>
#include <string>

namespace bender
{

/// Progress reporting and cancellation for the long-running calls of this module. Both members
/// are optional. The callback is called on the thread that runs the work (a GUI marshals it to
/// its own thread); the cancel flag may be set from any thread and is polled between and inside
/// stages; a cancelled call throws SegmentationCancelled and returns nothing.
struct ProgressReporter
{
  /// stage: short name ("read", "threshold", "fill holes", "marching cubes", ...);
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
  void ThrowIfCancelled(const std::string& stage) const
  {
    if (this->Cancelled())
    {
      throw SegmentationCancelled("cancelled during " + stage);
    }
  }
};

} // namespace bender

#endif
