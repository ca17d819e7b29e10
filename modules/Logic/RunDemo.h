#ifndef bender_RunDemo_h
#define bender_RunDemo_h

#include "DemoPipeline.h"
#include "Progress.h"

#include <functional>
#include <string>
#include <vector>

namespace bender
{

/// Options of RunDemo, the headless demo job (bender --demo-headless).
struct RunDemoOptions
{
  std::string outputDirectory; ///< created when missing
  /// Segment the MRA-like phantom of the demo vessel; when off, or when segmentation fails,
  /// the vessel surface itself is bent.
  bool segment = true;
  DemoOptions demo;
  std::string vesselPath; ///< empty: DemoVesselPath()
  std::string planPath;   ///< empty: DemoPlanPath()
  /// Render demo.png (on DISPLAY; skipped with a warning when rendering is impossible: the
  /// application starts a private Xvfb where there is no display).
  bool screenshot = true;
  /// Also make the vessel CFD-ready (PrepareForCfd: ends clipped, flow extensions, labelled
  /// caps), bend it by the plan and write it in metres (demo-cfd.stl, named solids, with
  /// demo-cfd.patches.json; demo-cfd.vtp in mm with the labels) and an OpenFOAM case
  /// (demo-openfoam/, WriteOpenFoamCase). A failure of this step is a warning.
  bool cfd = true;
  /// Run the OpenFOAM case (RunOpenFoamCase; OpenFOAM must be installed: else a warning).
  bool runCfd = false;
  ProgressReporter progress;
  /// Lines for the user ("Segmenting...", the check report); warnings start with "warning: ".
  std::function<void(const std::string& line, bool warning)> onMessage;
};

/// What RunDemo did.
struct RunDemoResult
{
  bool segmented = false;           ///< the surface came from the segmentation
  bool checkClean = false;          ///< the check found no problem
  std::vector<std::string> written; ///< every file written, in order
  std::vector<std::string> warnings;
  std::string cfdCase; ///< the OpenFOAM case folder, empty when not written
};

/// The demo job: segment the demo vessel (or read it), apply the demo plan (ApplyPlan), check
/// (CheckForExport), export STL and VTP (ExportSurface, LPS mm), the CFD-ready bent vessel in
/// metres and its OpenFOAM case (options.cfd), save the plan, render a screenshot
/// (RenderToPng), all into options.outputDirectory. Throws InputError when the
/// vessel or plan cannot be read or a file cannot be written, Cancelled.
RunDemoResult RunDemo(const RunDemoOptions& options);

} // namespace bender

#endif
