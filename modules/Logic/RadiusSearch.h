#ifndef bender_RadiusSearch_h
#define bender_RadiusSearch_h

// "Reduce R": the largest region of influence, at most the warp's own R and never below the
// vessel's radius, whose warp passes the commit guard's checks (flips, new self-intersections,
// the space-inversion rule when on, and the lumen guard when on), found by trying the warp at
// a few radii from R down to that floor. Model units (LPS mm).

#include "CommitGuard.h"
#include "Progress.h"
#include "WarpPlan.h"

#include <memory>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

struct RadiusSearchOptions
{
  /// The floor: the vessel's radius (> 0); no radius below it is tried (a smaller R moves
  /// part of the vessel's cross-section only and pinches it).
  double lowest = 0.0;
  /// Radii tried below R, spaced geometrically down to `lowest` (which is the last); [1, 20].
  int candidates = 6;
  /// Each radius tried is rounded up to a multiple of this (the precision R is set with: the
  /// radius found is then the one the release uses); 0 (default): not rounded.
  double step = 0.0;
  /// The checks, as the release applies them (CommitGuard.h).
  CommitCheckOptions check;
  /// The centerlines of the surface before the bend (the lumen guard's, known once per grab);
  /// computed once here when null and the lumen guard is on.
  std::shared_ptr<const CenterlineResult> lumenBefore;
  ProgressReporter progress;
};

struct RadiusSearchResult
{
  bool found = false;
  double radius = 0.0; ///< the largest radius tried that passes (when found)
  CommitCheck check;   ///< its check (found), or that of the last radius tried
  /// Each radius tried, largest first, with the check's summary.
  std::vector<std::pair<double, std::string>> tried;
};

/// Tries `warp` (its subdivision ignored: the checks compare cell by cell) on `before` at
/// radii below warp.radius, largest first, down to options.lowest, and returns the first that
/// passes. Nothing is found when warp.radius <= options.lowest. Throws InputError for a
/// floor that is not positive, Cancelled when asked to stop.
RadiusSearchResult FindPassingRadius(vtkPolyData* before,
  const WarpSpec& warp,
  const RadiusSearchOptions& options);

} // namespace bender

#endif
