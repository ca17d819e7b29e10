#include "SegmentVolume.h"

#include <chrono>

namespace bender
{

SurfaceResult SegmentVolume(const SegmentVolumeOptions& options)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  const Volume volume = ReadVolume(options.input, options.read, options.progress);
  const Clock::time_point t1 = Clock::now();
  const LabelMap mask = SegmentVessels(volume, options.segmentation, options.progress);
  const Clock::time_point t2 = Clock::now();
  SurfaceResult result = ExtractSurface(mask, options.surface, options.progress);
  result.timings.insert(result.timings.begin(),
    { { "read", std::chrono::duration<double>(t1 - t0).count() },
      { "segmentation", std::chrono::duration<double>(t2 - t1).count() } });
  return result;
}

} // namespace bender
