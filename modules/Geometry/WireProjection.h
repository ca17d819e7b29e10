#ifndef bender_WireProjection_h
#define bender_WireProjection_h

#include "Biarc.h"
#include "SimdLevel.h"
#include "Vec3.h"

#include <cstddef>

namespace bender
{

/// One projection of a point onto a wire: a local minimum of the distance (spec 3).
struct WireProjection
{
  double s = 0.0;        ///< global arc-length parameter of the foot point
  double distance = 0.0; ///< |P - Q|
  Vec3 foot;             ///< Q
};

/// At most two projections, nearest first (ties: smaller s first).
struct WireProjections
{
  int count = 0;
  WireProjection items[2];
};

/// Every local minimum of the distance from p to the wire, found with the signed-plane
/// partition of spec 3.3 (arc 1, arc 2, free ends: no gaps, no duplicates), keeping those
/// with distance < radius; when more than two remain, the two nearest (ties by smaller s).
/// Pass radius = infinity to get all (still at most two kept).
///
/// The arithmetic is branch-free and shared with the batched overload below and with
/// WarpBinding, so that all of them give bit for bit the same result; the angle on an arc is a
/// polynomial atan2 within a few units in the last place of std::atan2.
WireProjections ProjectOntoWire(const Biarc& wire, const Vec3& p, double radius);

/// ProjectOntoWire for each of the n points of `xyz` (x y z interleaved) into out[0, n),
/// computed in vectorised blocks with the best instruction set the CPU has: bit for bit the
/// single-point result.
void ProjectOntoWire(const Biarc& wire,
  const double* xyz,
  std::size_t n,
  double radius,
  WireProjections* out);

/// Same with the instruction set `level` (for comparisons); false, and nothing written, when
/// this build or this CPU cannot run it.
bool ProjectOntoWire(const Biarc& wire,
  const double* xyz,
  std::size_t n,
  double radius,
  WireProjections* out,
  SimdLevel level);

} // namespace bender

#endif
