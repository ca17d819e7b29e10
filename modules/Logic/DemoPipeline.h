#ifndef bender_DemoPipeline_h
#define bender_DemoPipeline_h

#include "Progress.h"
#include "Volume.h"

#include <vtkSmartPointer.h>

#include <string>

class vtkPolyData;

namespace bender
{

/// Where the built-in demo's files are (external/ and demo/): bender::DataDirectory(), i.e.
/// BENDER_DATA_DIR or <executable folder>/../share/bender (install and build tree alike).
std::string DemoDataDirectory();
/// data/external/aneurysm_data.stl: the branching cerebral artery with an aneurysm.
std::string DemoVesselPath();
/// data/demo/demo.bender.json: the demo plan, bending one branch of that vessel.
std::string DemoPlanPath();

struct DemoOptions
{
  /// Voxel size of the MRA-like phantom, mm; range [0.3, 2]. Default 0.5: about 1.6 M voxels.
  double spacing = 0.5;
  /// Smoothing knob of the surface extraction, [0, 1].
  double smoothing = 0.5;
};

/// The demo's result: the MRA-like volume, its segmentation and the lumen surface (LPS mm).
struct DemoVessel
{
  Volume volume;
  LabelMap mask;
  vtkSmartPointer<vtkPolyData> surface;
  std::string summary; ///< one line for the user
  /// SegmentDemoVesselOrFallBack: why the segmentation failed and the vessel surface itself is
  /// the surface (volume and mask empty); empty when segmented.
  std::string fallback;
};

/// The built-in demo: makes the MRA-like phantom of the aneurysm vessel, segments its lumen
/// (threshold at mid-intensity from the phantom's seed) and extracts the surface. Runs on the
/// calling thread (a GUI calls it from a worker). Throws MeshIOError (missing vessel file),
/// the segmentation module's errors, SegmentationCancelled.
DemoVessel SegmentDemoVessel(const std::string& vesselPath,
  const DemoOptions& options = {},
  const ProgressReporter& progress = {});

/// The demo's "segment, else fall back" (the window's demo and bender --demo-headless): the
/// result of SegmentDemoVessel, or, when the segmentation fails (missing ITK data, a failure),
/// the vessel surface read from `vesselPath` with `fallback` saying why (the demo still bends
/// the vessel). Throws Cancelled, and the reader's errors when even the vessel cannot be read.
DemoVessel SegmentDemoVesselOrFallBack(const std::string& vesselPath,
  const DemoOptions& options = {},
  const ProgressReporter& progress = {});

} // namespace bender

#endif
