#ifndef bender_WireProjection_h
#define bender_WireProjection_h

#include "Biarc.h"
#include "Vec3.h"

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
WireProjections ProjectOntoWire(const Biarc& wire, const Vec3& p, double radius);

} // namespace bender

#endif
