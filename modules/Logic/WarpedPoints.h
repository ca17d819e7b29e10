#ifndef bender_WarpedPoints_h
#define bender_WarpedPoints_h

// Points carried through a plan's warps, forwards and back: where a point given on the surface
// before the warps lands after them (the same exact warp as the surface's, each point alone: no
// subdivision), and where a point given on the warped surface was before them. The Prepare for
// CFD positions of a plan (its ends' cuts, names and extension factors) travel this way, so that
// the sweep's candidates and the Flow panel's original are clipped at the ends the user chose on
// another shape. Coordinates are the surface's (LPS mm).

#include "Vec3.h"
#include "WarpPlan.h"

#include <cstddef>
#include <vector>

namespace bender
{

/// The positions of a Prepare for CFD step: its ends' cuts, then its names, then its extension
/// factors (pointers into `step`).
std::vector<Vec3*> CfdStepPoints(CfdStep& step);

/// Moves each point through `warps[0..count)` in order (count clamped to warps.size()).
/// Throws InputError for an invalid warp.
void CarryForward(const std::vector<Vec3*>& points,
  const std::vector<WarpSpec>& warps,
  std::size_t count);

/// Moves each point back through `warps[0..count)`: the point q with W(q) = p, W the warps in
/// order, found by Newton's method on W (its Jacobian by central differences), from p. Throws
/// InputError naming the point when the warps have no such point near it (a folding warp).
void CarryBack(const std::vector<Vec3*>& points,
  const std::vector<WarpSpec>& warps,
  std::size_t count);

} // namespace bender

#endif
