#ifndef bender_VesselWorkflows_h
#define bender_VesselWorkflows_h

// The vessel workflows behind `bender-cli centerline` and `bender-cli measure` (and the
// application): read a surface, compute its centerlines (modules/Vessels), measure every
// branch, and compare a surface with its warped version (another file, or the surface after a
// plan applied with ApplyPlan) with the branches matched. Coordinates and lengths in the
// surface's unit (LPS mm for Bender's surfaces), angles in degrees.

#include "VesselCenterlines.h"
#include "VesselMeasures.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <optional>
#include <string>
#include <vector>

namespace bender
{

struct CenterlineWorkflowOptions
{
  std::string input;         ///< surface file (.stl .obj .ply .vtp .vtk .off)
  std::string output;        ///< centerline file (.vtp or .vtk); empty: not written
  std::vector<Point3> seeds; ///< inlet first; empty: automatic endpoints
};

struct CenterlineWorkflowResult
{
  vtkSmartPointer<vtkPolyData> surface;
  CenterlineResult centerlines;
  VesselMeasurements measures;
};

/// Reads, computes, measures and (when options.output is set) writes the branch polylines
/// atomically. Throws InputError ("<file>: <problem>") for an unreadable surface, centerlines
/// that cannot be computed (the library's message), an output that is not .vtp/.vtk, names the
/// input, or cannot be written.
CenterlineWorkflowResult ComputeCenterlinesOfFile(const CenterlineWorkflowOptions& options);

struct MeasureWorkflowOptions
{
  std::string input;         ///< the surface before
  std::string after;         ///< the surface after (same vessel, warped or remeshed); or
  std::string plan;          ///< a plan (.bender.json) applied to the input to get "after"
  std::vector<Point3> seeds; ///< inlet first; empty: automatic endpoints
};

/// One matched branch: before and after measures and the turn of its end directions.
struct BranchComparison
{
  std::optional<BranchMeasures> before;
  std::optional<BranchMeasures> after;
  double startTurn = 0; ///< degrees between the start tangents before and after
  double endTurn = 0;   ///< degrees between the end tangents before and after
};

struct MeasureWorkflowResult
{
  CenterlineWorkflowResult before;
  std::optional<CenterlineWorkflowResult> after; ///< with --after or --plan
  std::vector<BranchComparison> branches;        ///< matched by the outlets they lead to
  std::vector<std::string> warnings;
};

/// Measures the input; with `after` or `plan`, also the other surface (its centerlines seeded
/// with the input's endpoints carried along, MatchedSeeds) and the matched comparison.
/// Throws InputError for unreadable files, an invalid plan, both `after` and `plan`, or
/// centerlines that cannot be computed.
MeasureWorkflowResult MeasureVessels(const MeasureWorkflowOptions& options);

/// One JSON object (text, indented) of a centerline result: input, endpoints (position,
/// radius, kind, inlet, reached), bifurcations (position, parent, children, angles), branches
/// with their measures, warnings, stage times.
std::string CenterlinesToJson(const CenterlineWorkflowResult& result);
/// One JSON object of a measurement: {"before": ..., "after": ..., "comparison": [...]}, each
/// comparison entry with the branch's outlets, its measures before and after and their change.
std::string MeasurementsToJson(const MeasureWorkflowResult& result);
/// Plain-text table for a terminal.
std::string MeasurementsToText(const MeasureWorkflowResult& result);

/// Parses "x,y,z" (three finite numbers); throws InputError naming `what`.
Point3 ParsePoint(const std::string& text, const std::string& what);

} // namespace bender

#endif
