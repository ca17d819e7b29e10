#include "DemoPipeline.h"

#include "BenderErrors.h"
#include "DataDirectory.h"

#include "MeshIO.h"
#include "SurfaceExtraction.h"
#include "VesselPhantom.h"
#include "VesselSegmentation.h"

#include <vtkPolyData.h>

#include <cstdlib>
#include <exception>
#include <sstream>

namespace bender
{

std::string DemoDataDirectory()
{
  return DataDirectory();
}

std::string DemoVesselPath()
{
  return DemoDataDirectory() + "/external/aneurysm_data.stl";
}

std::string DemoPlanPath()
{
  return DemoDataDirectory() + "/demo/demo.bender.json";
}

DemoVessel SegmentDemoVessel(const std::string& vesselPath,
  const DemoOptions& options,
  const ProgressReporter& progress)
{
  progress.Report("read vessel", 0.0);
  vtkSmartPointer<vtkPolyData> truth = ReadMesh(vesselPath);
  progress.ThrowIfCancelled("read vessel");

  PhantomParameters phantomParameters;
  phantomParameters.spacing = options.spacing;
  Phantom phantom = MakeVesselPhantom(truth, phantomParameters, progress);

  SegmentationParameters segmentation;
  segmentation.method = SegmentationMethod::Threshold;
  segmentation.lower = phantom.midIntensity;
  segmentation.seeds = { phantom.seed };
  LabelMap mask = SegmentVessels(phantom.volume, segmentation, progress);

  SurfaceParameters surfaceParameters;
  surfaceParameters.smoothing = options.smoothing;
  surfaceParameters.seeds = { phantom.seed };
  SurfaceResult surface = ExtractSurface(mask, surfaceParameters, progress);

  DemoVessel demo;
  demo.volume = std::move(phantom.volume);
  demo.mask = std::move(mask);
  demo.surface = surface.surface;
  std::ostringstream summary;
  const auto& size = demo.volume.geometry.size;
  summary << "Demo: MRA-like volume " << size[0] << "x" << size[1] << "x" << size[2] << " at "
          << options.spacing << " mm, lumen segmented (" << demo.mask.CountInside()
          << " voxels), surface of " << demo.surface->GetNumberOfPolys() << " triangles (LPS mm)";
  demo.summary = summary.str();
  return demo;
}

DemoVessel SegmentDemoVesselOrFallBack(const std::string& vesselPath,
  const DemoOptions& options,
  const ProgressReporter& progress)
{
  try
  {
    return SegmentDemoVessel(vesselPath, options, progress);
  }
  catch (const Cancelled&)
  {
    throw;
  }
  catch (const std::exception& e) // the segmentation's errors and ITK's: the vessel itself
  {
    DemoVessel demo;
    demo.fallback = e.what();
    demo.surface = ReadMesh(vesselPath);
    return demo;
  }
}

} // namespace bender
