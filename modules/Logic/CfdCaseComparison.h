#ifndef bender_CfdCaseComparison_h
#define bender_CfdCaseComparison_h

// The workflow behind `bender-cli compare CASE_A CASE_B` and the flow report (issue 23): two
// CFD cases already run and mapped (CASE/results/flow.json and surface.vtp, MapCfdResults),
// read and checked, their comparison table (CfdComparison.h), the bend between the two shapes
// measured on their centerlines (each branch's bend angle, length and minimal inscribed radius
// in A and in B, the branches matched by the names of the ends they lead to), and the plan's
// description and warps when a plan is given. Everything a report needs, without Qt.
//
// Surfaces and lengths in LPS millimetres, pressures in Pa, angles in degrees.

#include "CfdComparison.h"
#include "CfdFlowResults.h"
#include "Progress.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <optional>
#include <string>
#include <vector>

namespace bender
{

/// Options of CompareCfdCases.
struct CompareCfdCasesOptions
{
  std::string caseA; ///< the reference (the original vessel): a case folder after a run
  std::string caseB; ///< the candidate
  std::string labelA = "original";
  std::string labelB = "candidate";
  /// A plan (.bender.json) that made B's shape from A's: its name and warps are reported;
  /// empty: none.
  std::string plan;
  /// Measure each branch on the centerlines of both surfaces (a few seconds per surface).
  bool measureBends = true;
  CfdHighlightRule rule;
  ProgressReporter progress;
};

/// One case as compared: its results and its surface with the mapped fields.
struct ComparedCfdCase
{
  std::string directory;
  std::string label;
  CfdFlowResults results;
  /// CASE/results/surface.vtp: point data Pressure (Pa), WallShearStressMagnitude (Pa).
  vtkSmartPointer<vtkPolyData> surface;
};

/// One branch measured in A and in B (matched by the ends it leads to).
struct BendBranchMeasures
{
  std::string name; ///< the outlets the branch leads to, "outlet_1" or "outlet_1 + outlet_2"
  std::optional<double> angleA, angleB;         ///< bend angle, degrees
  std::optional<double> lengthA, lengthB;       ///< centerline length, mm
  std::optional<double> minRadiusA, minRadiusB; ///< minimal inscribed radius, mm
};

/// One warp of the plan.
struct PlanWarpMeasures
{
  double endTurn = 0.0;      ///< degrees between the ribbon's end tangent at grab and release
  double lengthChange = 0.0; ///< the ribbon's length change, fraction (-0.1: 10 % shorter)
  double radius = 0.0;       ///< R, mm
};

/// What the plan says (when options.plan is given).
struct PlanDescription
{
  std::string file;
  std::string name; ///< its "name" (or "description", "note") field; may be empty
  std::vector<PlanWarpMeasures> warps;
  bool preparedForCfd = false; ///< the plan has a Prepare for CFD step
};

/// Everything the report shows.
struct CfdCaseComparison
{
  ComparedCfdCase a, b;
  CfdComparison table;
  std::vector<BendBranchMeasures> bends; ///< empty when not measured (see unavailable)
  std::optional<PlanDescription> plan;
  /// What could not be had, one line each ("bend measures: no centerline in B: ...").
  std::vector<std::string> unavailable;
};

/// Reads both cases and compares them. Throws InputError with one line naming the case and the
/// problem: not a case folder, a case not run ("no results: run bender-cli cfd-case --run"),
/// results missing or not matching the case (flow.json or surface.vtp absent, a field missing,
/// ends of the results not among the case's), an unreadable plan; Cancelled when cancelled.
CfdCaseComparison CompareCfdCases(const CompareCfdCasesOptions& options);

/// The comparison, the plan and the bend measures as one JSON object (the table of
/// CfdComparisonToJson plus "cases", "plan", "bends", "unavailable").
std::string CfdCaseComparisonToJson(const CfdCaseComparison& comparison);

/// The mesh and convergence figures of one case, one short sentence each: the mesh (cells, the
/// cell size at the wall), the run (its status: converged or stopped, with the residuals), the
/// inlet (flow rate, Reynolds number) and the mass imbalance.
std::vector<std::string> CfdMeshAndConvergenceLines(const CfdFlowResults& results);

/// The bend measures and the plan as lines of text (after the table, for bender-cli).
std::string BendMeasuresToText(const CfdCaseComparison& comparison);

} // namespace bender

#endif
