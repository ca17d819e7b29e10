#ifndef bender_FlowStudy_h
#define bender_FlowStudy_h

// "Run flow for the original and the current shape" (issue 23): what a bend does to the flow,
// the vessel as it is against the candidate, from the same case settings.
//  - the original: the surface before any step of the plan, with the plan's Prepare for CFD
//    steps applied and no warp (the same clip, names, extensions and caps as the candidate);
//  - the current shape: the committed surface, CFD-ready (a plan whose Prepare for CFD step
//    came before or after the warps).
// Each is written as an OpenFOAM case into the flow cache (FlowCaseCache.h: keyed by the case's
// content, so an unchanged shape is never solved twice), run (RunOpenFoamCase: the Allrun's
// steps and the solver's iterations reported as they come, Cancel stops it; the results mapped
// onto its surface: CASE/results) and read back. Surfaces are LPS millimetres.

#include "CfdCase.h"
#include "CfdFlowResults.h"
#include "CfdResidualMonitor.h"
#include "LabelledSurface.h"
#include "Progress.h"
#include "WarpPlan.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <string>

namespace bender
{

/// Which shape of a study.
enum class FlowShape
{
  Original, ///< the surface before the warps, prepared for CFD as the plan says
  Current   ///< the committed surface (the candidate)
};

/// "original", "current shape".
const char* FlowShapeName(FlowShape shape);

/// The session's shapes (deep copies: the work runs on another thread).
struct FlowStudyInput
{
  vtkSmartPointer<vtkPolyData> first; ///< the surface before any step of `plan`
  WarpPlan plan;                      ///< the committed steps (warps, Prepare for CFD steps)
  /// The committed surface: what `plan` makes of `first` (labelled: prepared for CFD).
  vtkSmartPointer<vtkPolyData> current;
  std::string name = "the surface"; ///< in messages
};

struct FlowStudyOptions
{
  /// The flow cache's folder (created when missing); one case folder per key in it.
  std::string cacheDirectory;
  /// The case's settings; caseDirectory and force are the cache's.
  CfdCaseOptions caseOptions;
  /// Each iteration of the solver (its initial residuals), on a thread of the run, in order;
  /// for a case found in the cache, its iterations at once.
  std::function<void(const CfdIteration&)> onIteration;
  /// The Allrun's lines ("bender Allrun: snappyHexMesh"), on the thread that runs the case
  /// (RunFlowStudy: two at once).
  std::function<void(const std::string&)> onLine;
  /// Streamlines from this many seeds over the inlet (FlowStreamlines); 0: none.
  int streamlineSeeds = 60;
  /// Stages "prepare", "case", "mesh: <program>", "solve" (iteration / iteration limit),
  /// "results"; its cancel flag stops the run (Cancelled; the case stays in the cache without
  /// results and is run again next time).
  ProgressReporter progress;
};

/// One shape's flow.
struct FlowShapeResult
{
  FlowShape shape = FlowShape::Original;
  std::string key;           ///< the cache key (FlowCaseKey)
  std::string caseDirectory; ///< CACHE/<key>
  bool cached = false;       ///< found solved in the cache: nothing was run
  CfdFlowResults results;    ///< CASE/results/flow.json
  /// CASE/results/surface.vtp: the CFD-ready surface with Pressure, WallShearStress and
  /// WallShearStressMagnitude (Pa).
  vtkSmartPointer<vtkPolyData> surface;
  /// FlowStreamlines of the case (mm, point data Speed in m/s); null when not asked for or
  /// when they could not be traced (then streamlineProblem says why, one line).
  vtkSmartPointer<vtkPolyData> streamlines;
  std::string streamlineProblem;
};

/// The CFD-ready surface of `shape`. The original: ApplyPlan of the plan's Prepare for CFD
/// steps (no warp) to `first`, or `first` itself when the plan has none and it is labelled. A
/// step made after warps chose its ends on the bent shape: its positions are carried back
/// through those warps first (CarryBack, WarpedPoints.h), so "bend, then Prepare for CFD" cuts
/// the original at the same ends. Throws InputError, one line naming input.name: a shape
/// without two labelled ends ("prepare for CFD first"), a position the warps fold, an original
/// whose ends are not named as the current shape's, ApplyPlan's errors; Cancelled.
LabelledSurface FlowReadySurface(const FlowStudyInput& input,
  FlowShape shape,
  const ProgressReporter& progress = {});

/// The flow of one shape: made CFD-ready, written into the cache, run and mapped unless the
/// cache has its results, read back (with streamlines when asked for). Throws InputError (the
/// shape, the case options, the cache folder), EnvironmentError (no OpenFOAM), Error (a failed step
/// of the run, named with its log; the mapping), Cancelled.
FlowShapeResult RunFlowShape(const FlowStudyInput& input,
  FlowShape shape,
  const FlowStudyOptions& options);

/// Both shapes' flow: shapes[0] the original, shapes[1] the current shape.
struct FlowStudyResult
{
  FlowShapeResult shapes[2];
};

/// "Run flow for the original and the current shape". Both are made CFD-ready and written into
/// the cache first, then run (as RunFlowShape: a case found solved is read back): both at once
/// when `concurrent` (two serial cases on two cores take about the longer one's time instead of
/// the sum, docs/cfd.md "Speed"), else one after the other; a current shape whose case is the
/// original's is run once. `onIteration` gets each shape's iterations (on threads of the runs;
/// options.onIteration is not used); the progress stages are named after their shape
/// ("original: solve"). A shape that fails does not stop the other (one after the other too:
/// only Cancel keeps the second from running), whose case stays solved in the cache; then the first
/// failure is thrown (the original's before the current's), of RunFlowShape's type, its message led
/// by the shape ("current shape: ..."). Cancel stops both (Cancelled).
FlowStudyResult RunFlowStudy(const FlowStudyInput& input,
  const FlowStudyOptions& options,
  const std::function<void(FlowShape, const CfdIteration&)>& onIteration,
  bool concurrent);

/// The results of a case folder that has them (ReadCfdFlowResults and results/surface.vtp).
/// Throws InputError naming the file.
FlowShapeResult ReadFlowShape(const std::string& caseDirectory, FlowShape shape);

} // namespace bender

#endif
