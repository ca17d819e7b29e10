#ifndef bender_ApplyPlan_h
#define bender_ApplyPlan_h

#include "PrepareForCfd.h"
#include "Progress.h"
#include "RibbonWarp.h"
#include "WarpBinding.h"
#include "WarpPlan.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

namespace bender
{

/// Options of ApplyWarp / ApplyPlan.
struct ApplyPlanOptions
{
  /// Screw evaluation: Exact (the normative result, the default) or Table.
  WarpPrecision precision = WarpPrecision::Exact;
  /// Points with two projections: the normative blend (default) or the single projection.
  BlendMode blend = BlendMode::TwoProjections;
  /// Name of the plan in messages ("gallery.bender.json"); empty: "plan".
  std::string planName;
  /// Progress ("warp 1 of 3", fraction) and cancellation (checked between warps).
  ProgressReporter progress;
};

/// What one warp did.
struct WarpStepInfo
{
  /// Points of the input inside the region of influence (R), -1 when the warp was subdivided
  /// (the subdivision filter does not count them).
  long long boundPoints = -1;
  long long inputPoints = 0;
  bool flipOccurred = false;     ///< the screw continuity lift was used (paper 3.8)
  std::string warning;           ///< the space-inversion warning, empty when none
  bool subdivided = false;       ///< the WarpSpec carried a subdivision object
  double tolerance = 0.0;        ///< subdivision tolerance (when subdivided)
  int passesRun = 0;             ///< subdivision passes that split edges
  bool converged = true;         ///< false when subdivision stopped at maxPasses
  long long trianglesBefore = 0; ///< polygons + strips of the input
  long long trianglesAfter = 0;  ///< polygons of the output
};

/// The surface after each warp and each Prepare for CFD step of a plan.
struct ApplyPlanResult
{
  /// steps[i] is the surface after warps[0..i] (and the CFD steps before warps[i + 1]); new
  /// objects, points always double.
  std::vector<vtkSmartPointer<vtkPolyData>> steps;
  std::vector<WarpStepInfo> info;
  /// prepared[j] is cfdSteps[j]'s result: the surface after it (Surface) and its ends.
  std::vector<PrepareForCfdResult> prepared;
  /// The final surface (a deep copy of the input, with double points, for an empty plan).
  vtkSmartPointer<vtkPolyData> output;
};

/// THE rule for applying a warp, used by bender-cli, BenderSession, the tests and the
/// benchmarks: the warp is validated (spec convention 11), then
///  - with `warp.subdivision` present: vtkBenderAdaptiveSubdivisionFilter alone (it performs
///    the exact warp itself and refines; maxPasses 0 warps and triangulates without refining);
///  - otherwise: vtkBenderWarpFilter.
/// The input is not modified. Output points are always double.
/// Throws InputError ("<plan>: warps[i]: <problem>") for an invalid warp or a failed filter,
/// Cancelled when options.progress.cancel is set.
vtkSmartPointer<vtkPolyData> ApplyWarp(vtkPolyData* input,
  const WarpSpec& warp,
  const ApplyPlanOptions& options = {},
  WarpStepInfo* info = nullptr);

/// THE rule for a Prepare for CFD step of a plan: PrepareForCfd with the step's options
/// (CfdStepOptions) on the centerlines ComputeCenterlines gives for `input` with its default
/// options; `centerlines`, when given, must be those (the window passes the ones it has, of
/// the same surface). The input is not modified. Throws InputError naming the step (options'
/// planName, "prepareForCfd" when empty: "prepareForCfd: <problem>"), Cancelled.
PrepareForCfdResult ApplyCfdStep(vtkPolyData* input,
  const CfdStep& step,
  const ApplyPlanOptions& options = {},
  vtkPolyData* centerlines = nullptr);

/// Applies every step of `plan` in order (PlanOrder: the warps, and the CFD steps between
/// them; all or nothing: on error nothing is returned). Throws InputError naming the plan and
/// the step ("plan: warps[2]: ...", "plan: prepareForCfd[0]: ..."), Cancelled.
ApplyPlanResult ApplyPlan(vtkPolyData* input,
  const WarpPlan& plan,
  const ApplyPlanOptions& options = {});

} // namespace bender

#endif
