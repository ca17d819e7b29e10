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
  /// Render demo.png (a private Xvfb is started without a display; skipped with a warning
  /// when rendering is impossible).
  bool screenshot = true;
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
};

/// The demo job: segment the demo vessel (or read it), apply the demo plan (ApplyPlan), check
/// (CheckForExport), export STL and VTP (ExportSurface, LPS mm), save the plan, render a
/// screenshot (RenderToPng), all into options.outputDirectory. Throws InputError when the
/// vessel or plan cannot be read or a file cannot be written, Cancelled.
RunDemoResult RunDemo(const RunDemoOptions& options);

} // namespace bender

#endif
