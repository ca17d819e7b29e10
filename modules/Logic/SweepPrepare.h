#ifndef bender_SweepPrepare_h
#define bender_SweepPrepare_h

// One candidate of a sweep made ready to solve (issue 24): warped exactly, checked (a candidate
// that folds or self-intersects is rejected, not solved), clipped with the same ends, names,
// roles and flow extensions as the original (the original's Prepare for CFD resolved once, its
// positions carried by the candidate's warps, every end matched by name), and written as an
// OpenFOAM case with the original's settings (the same cell size and inlet flow rate).
// Surfaces in LPS mm; the case in metres (CfdCase.h).

#include "CfdCase.h"
#include "Progress.h"
#include "SweepCandidates.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <limits>
#include <string>
#include <vector>

namespace bender
{

/// What every candidate of a sweep shares, computed once from the original surface.
struct SweepBase
{
  vtkSmartPointer<vtkPolyData> surface; ///< the input as read
  std::string surfaceName;              ///< for messages ("aneurysm.stl")
  /// The original's Prepare for CFD, resolved: every end's cut, name, role and extension
  /// factor written out at the original's positions.
  CfdStep step;
  std::vector<std::string> endNames; ///< the original's ends, by id
  /// The case settings of every candidate: the original's cell size and inlet flow rate fixed,
  /// caseDirectory and force set per candidate.
  CfdCaseOptions caseOptions;
  long long selfIntersections = 0; ///< of the original (a candidate may not add any)
  /// Where the bend is: the middle of the first warp's initial wire (the branch measured).
  Vec3 bendPoint;
};

/// PrepareSweepBase's input: the surface, the plan's Prepare for CFD step (its last one; a
/// default step when the plan has none) and the case settings the user chose.
struct SweepBaseOptions
{
  std::string surfacePath;
  CfdStep step;
  CfdCaseOptions caseOptions;
  Vec3 bendPoint;
  /// A folder for a throw-away case of the original (to read the resolved cell size and flow
  /// rate); removed afterwards.
  std::string scratchFolder;
};

/// Reads the surface, prepares the original for CFD and resolves the case settings. Throws
/// InputError naming the surface (unreadable, cannot be clipped, fewer than two ends),
/// Cancelled.
SweepBase PrepareSweepBase(const SweepBaseOptions& options, const ProgressReporter& progress = {});

/// The bend measures of a candidate: of the centerline branch nearest the bend.
struct SweepMeasures
{
  double bendAngle = std::numeric_limits<double>::quiet_NaN();    ///< degrees
  double lengthChange = std::numeric_limits<double>::quiet_NaN(); ///< % (ribbon wire length)
  double minRadius = std::numeric_limits<double>::quiet_NaN();    ///< mm, inscribed
};

/// A candidate made ready (or rejected).
struct PreparedCandidate
{
  bool rejected = false;
  std::string reason; ///< why it was rejected (one line)
  SweepMeasures measures;
  std::vector<std::string> warnings;
};

/// Warps, checks, prepares and writes the candidate's case into `caseDirectory` (replaced when
/// there). A candidate whose warp folds the surface (flipped triangles), makes it
/// self-intersect (more pairs than the original) or loses a named end is rejected (no case
/// written). Throws InputError for a warp that cannot be applied at all, Cancelled.
PreparedCandidate PrepareCandidate(const SweepBase& base,
  const SweepCandidate& candidate,
  const std::string& caseDirectory,
  const ProgressReporter& progress = {});

} // namespace bender

#endif
