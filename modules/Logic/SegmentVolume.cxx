#include "SegmentVolume.h"

#include "BenderErrors.h"
#include "MeshIO.h"
#include "SegmentationSession.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace bender
{

bool IsEightBit(const Volume& volume)
{
  bool any = false;
  for (const float v : volume.voxels)
  {
    if (!std::isfinite(v))
    {
      continue;
    }
    if (v < 0.0f || v > 255.0f || v != std::floor(v))
    {
      return false;
    }
    any = true;
  }
  return any;
}

std::string SegmentationWarning(double threshold,
  bool eightBit,
  std::size_t maskVoxels,
  long long surfacePoints)
{
  if (surfacePoints >= MinimumSurfacePoints)
  {
    return {};
  }
  std::ostringstream text;
  text << "Segmentation: threshold " << std::setprecision(6) << threshold << " on "
       << (eightBit ? "an 8-bit volume" : "this volume") << " kept ";
  if (surfacePoints >= 0)
  {
    text << surfacePoints << " points";
  }
  else
  {
    text << maskVoxels << " voxels and no surface";
  }
  text << ": too little for a vessel.";
  return text.str();
}

SegmentVolumeResult SegmentLoadedVolume(const Volume& volume,
  const SegmentationParameters& segmentation,
  const SurfaceParameters& surface,
  const ProgressReporter& progress)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  auto mask = std::make_shared<const LabelMap>(SegmentVessels(volume, segmentation, progress));
  const Clock::time_point t1 = Clock::now();
  SegmentVolumeResult result;
  static_cast<SurfaceResult&>(result) = ExtractSurface(*mask, surface, progress);
  result.timings.insert(result.timings.begin(),
    StageTime{ "segmentation", std::chrono::duration<double>(t1 - t0).count() });
  result.mask = std::move(mask);
  const long long points = result.surface ? result.surface->GetNumberOfPoints() : -1;
  result.warning =
    SegmentationWarning(segmentation.lower, IsEightBit(volume), result.mask->CountInside(), points);
  return result;
}

SegmentVolumeResult SegmentVolume(const SegmentVolumeOptions& options)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  VolumeReadOptions read = options.read;
  std::string note;
  read.dicomSeriesUid = ChooseDicomSeries(options.input, options.read.dicomSeriesUid, note);
  if (!note.empty() && options.inform)
  {
    options.inform(note);
  }
  const Volume volume = ReadVolume(options.input, read, options.progress);
  const Clock::time_point t1 = Clock::now();
  SegmentVolumeResult result =
    SegmentLoadedVolume(volume, options.segmentation, options.surface, options.progress);
  result.timings.insert(
    result.timings.begin(), StageTime{ "read", std::chrono::duration<double>(t1 - t0).count() });
  return result;
}

Phantom MakePhantomVolume(const PhantomVolumeOptions& options)
{
  vtkSmartPointer<vtkPolyData> surface = ReadMesh(options.input); // MeshIOError: an InputError
  Phantom phantom = MakeVesselPhantom(surface, options.phantom, options.progress);
  if (!options.output.empty())
  {
    const std::filesystem::path parent = std::filesystem::path(options.output).parent_path();
    std::error_code error;
    if (!parent.empty())
    {
      std::filesystem::create_directories(parent, error);
    }
    // All-or-nothing (temporary beside the target, then renamed).
    WriteVolume(phantom.volume, options.output);
  }
  return phantom;
}

} // namespace bender
