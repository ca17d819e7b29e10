#ifndef bender_LumenGuard_h
#define bender_LumenGuard_h

// The lumen guard: what a bend did to the lumen along the centerline. The centerlines of the
// surface before and after the bend (ComputeCenterlines, the after's seeded with the before's
// endpoints carried along by MatchedSeeds, so that the branches pair by the outlets they lead
// to) give each branch's minimal inscribed radius (MeasureBranches' minRadius); a branch the
// bend moved (any surface point the bend moved lies nearer to it than to any other branch:
// the region the warp moved, up to the next bifurcation or open end) is judged, and one that
// lost more than a fraction of its minimal radius is a problem: a false stenosis. Used by the
// commit guard of the window (the release job), by `bender-cli check AFTER --before BEFORE`,
// and by the demos' tests. Lengths in the surfaces' unit (LPS mm for Bender's surfaces).

#include "VesselCenterlines.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <set>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

struct LumenGuardOptions
{
  /// Measure the lumen at all (the window's guard; the CLI measures when --before is given).
  bool enabled = true;
  /// The largest loss of a branch's minimal radius that passes, a fraction in [0, 1):
  /// default 0.05 (5 %).
  double maxNarrowing = 0.05;
};

/// One branch, paired before and after by the outlets it leads to.
struct BranchLumenChange
{
  int branchId = -1;     ///< the branch after the bend (BranchId), -1 when gone
  std::set<int> outlets; ///< the outlets reached through the branch (its identity)
  double beforeMinRadius = 0.0;
  double afterMinRadius = 0.0;
  /// 1 - after / before: 0.08 when the branch lost 8 % of its minimal radius (negative: wider).
  double narrowing = 0.0;
  Point3 narrowest{ { 0, 0, 0 } }; ///< where the branch is narrowest after the bend
  bool moved = false;              ///< the bend moved the wall around it: it is judged
  bool tooNarrow = false;          ///< judged, and narrowed by more than the threshold
};

/// The lumen guard's result.
struct LumenCheck
{
  /// False when the lumen was not measured: off, or no centerline before the bend (a shape
  /// that is no vessel); notMeasured says why.
  bool checked = false;
  std::string notMeasured;
  double maxNarrowing = 0.05; ///< the threshold applied
  std::vector<BranchLumenChange> branches;
  int worst = -1; ///< the judged branch that narrowed most (index into branches), -1 none
  /// One sentence per branch narrowed past the threshold (or the after's centerlines lost);
  /// empty when the bend may be committed.
  std::vector<std::string> problems;
  double seconds = 0.0; ///< time spent computing centerlines (before and after)
  /// The centerlines of the surface after the bend (null when not computed): the next bend's
  /// "before" once this one is committed.
  std::shared_ptr<const CenterlineResult> after;

  bool Passed() const { return this->problems.empty(); }
  /// The problems in one line, or "no branch narrowed by more than 5 %".
  std::string Summary() const;
};

/// The centerlines the guard measures: ComputeCenterlines with default options and `seeds`
/// (empty: the endpoints found automatically). Never throws for geometry (Ok false).
CenterlineResult LumenCenterlines(vtkPolyData* surface, const std::vector<Point3>& seeds = {});

/// Compares the centerlines `before` and `after` (the after's seeded with MatchedSeeds of the
/// before's endpoints). `moved`: the points of the surface before the bend that the bend
/// moved; a branch is judged when one of them is nearer to it than to any other branch. All
/// branches are judged when `allMoved` (surfaces of different points: nothing pairs them).
LumenCheck CompareLumen(const CenterlineResult& before,
  const CenterlineResult& after,
  const std::vector<Point3>& moved,
  bool allMoved,
  double maxNarrowing);

/// The guard on two surfaces of a vessel, before and after a bend: the centerlines of both
/// (before's taken from `beforeCenterlines` when given: computed once per grab), the branches
/// the bend moved (the points that differ when both have the same points; else every branch)
/// and CompareLumen. Never throws for geometry: no centerline before gives checked = false;
/// none after (the lumen closed?) is a problem. Throws InputError for a null surface or a
/// threshold outside [0, 1).
LumenCheck CheckLumen(vtkPolyData* before,
  vtkPolyData* after,
  const LumenGuardOptions& options = {},
  const CenterlineResult* beforeCenterlines = nullptr);

/// Text for a terminal: one line per branch (minimal radius before -> after, change, whether
/// it was judged), then the verdict.
std::string LumenCheckText(const LumenCheck& check);
/// One JSON object: {"checked", "notMeasured" (when not), "maxNarrowing", "passed",
/// "branches": [{"branchId", "outlets", "beforeMinRadius", "afterMinRadius", "narrowing",
/// "narrowest", "moved", "tooNarrow"}], "problems", "seconds"}.
nlohmann::ordered_json LumenCheckToJson(const LumenCheck& check);

} // namespace bender

#endif
