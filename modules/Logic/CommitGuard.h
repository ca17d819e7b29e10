#ifndef bender_CommitGuard_h
#define bender_CommitGuard_h

#include "LumenGuard.h"
#include "WarpPlan.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <limits>
#include <string>
#include <vector>

namespace bender
{

/// What the commit guard looks at.
struct CommitCheckOptions
{
  /// New self-intersections: pairs of triangles crossing after the warp that did not before.
  bool selfIntersections = true;
  /// The spec's rule (paper 3.8): R >= r_min of the initial or the final wire makes space
  /// inversion possible; counted as a problem of its own.
  bool spaceInversionRule = true;
  /// The lumen guard (LumenGuard.h): each branch the warp moved keeps its minimal inscribed
  /// radius within the threshold. Off here; the window's session turns it on.
  LumenGuardOptions lumen{ false, 0.05 };
};

/// The check of the region a warp changed, before it is committed (issue 12): flipped
/// triangles against the surface before the warp, new self-intersections, the
/// space-inversion rule, and (when asked) the lumen guard (issue 22). Cell ids are those of the
/// surface before the warp (the warped surface without subdivision has the same cells).
struct CommitCheck
{
  bool checked = false;          ///< false when the guard did not run (nothing moved, off)
  long long movedPoints = 0;     ///< points the warp moved
  long long regionTriangles = 0; ///< triangles with a moved point
  /// Flipped triangles in the changed region, as the export check counts them (CheckMesh).
  long long flippedTriangles = 0;
  /// Pairs of triangles intersecting after the warp and not before.
  long long newSelfIntersections = 0;
  bool spaceInversionRisk = false;
  double radius = 0.0; ///< R of the warp
  /// r_min of the warp: the smaller of the initial and the final wire's (infinite: straight).
  double minimumRadius = std::numeric_limits<double>::infinity();
  /// The triangles to show: turned inside out by the warp (the local map reverses their
  /// orientation) or in a new intersecting pair. Sorted, unique.
  std::vector<vtkIdType> problemCells;
  /// Those triangles after the warp (their own points), for drawing; empty when none.
  vtkSmartPointer<vtkPolyData> problemTriangles;
  /// The lumen guard's measure (checked false when off or not measurable); its problems are
  /// among `problems`, its narrowest point is lumen.branches[lumen.worst].narrowest.
  LumenCheck lumen;
  /// One short sentence per problem; empty when the warp may be committed.
  std::vector<std::string> problems;

  bool Passed() const { return this->problems.empty(); }
  /// The problems in one line ("12 flipped triangles, 3 new self-intersections"), or "no
  /// problems".
  std::string Summary() const;
};

/// Checks the warp `warp` that took `before` to `after` (the same points and cells: the warp
/// without subdivision). Looks only at the triangles the warp moved (and, for intersections,
/// at every triangle near them). With options.lumen on, also CheckLumen (`lumenBefore`: the
/// centerlines of `before` when known, e.g. computed once per grab). Throws InputError when
/// the two surfaces do not match.
CommitCheck CheckCommit(vtkPolyData* before,
  vtkPolyData* after,
  const WarpSpec& warp,
  const CommitCheckOptions& options = {},
  const CenterlineResult* lumenBefore = nullptr);

} // namespace bender

#endif
