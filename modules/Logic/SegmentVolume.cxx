#include "SegmentVolume.h"

#include "BenderErrors.h"
#include "MeshIO.h"
#include "SegmentationSession.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <exception>
#include <filesystem>

namespace bender
{

SurfaceResult SegmentVolume(const SegmentVolumeOptions& options)
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
  const LabelMap mask = SegmentVessels(volume, options.segmentation, options.progress);
  const Clock::time_point t2 = Clock::now();
  SurfaceResult result = ExtractSurface(mask, options.surface, options.progress);
  result.timings.insert(result.timings.begin(),
    { { "read", std::chrono::duration<double>(t1 - t0).count() },
      { "segmentation", std::chrono::duration<double>(t2 - t1).count() } });
  return result;
}

Phantom MakePhantomVolume(const PhantomVolumeOptions& options)
{
  vtkSmartPointer<vtkPolyData> surface;
  try
  {
    surface = ReadMesh(options.input);
  }
  catch (const std::exception& e)
  {
    throw InputError(e.what());
  }
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
