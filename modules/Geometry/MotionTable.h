#ifndef bender_MotionTable_h
#define bender_MotionTable_h

#include "RibbonWarp.h"

#include <vector>

namespace bender
{

/// Linear interpolation of a warp's lifted relative motions along s (spec 9(b)). The samples
/// are the warp's sign table, uniform on each of the (at most three) pieces between s = 0, the
/// two junction parameters and s = 1 (the curvature jumps at the junctions), so interpolation
/// is second order everywhere. Refers to the warp's data: the warp must outlive it.
class MotionTable
{
public:
  using Piece = SampleGrid::Piece;

  /// The warp's own lifted sign table (RibbonWarp::Grid, MotionTable): nothing is recomputed.
  explicit MotionTable(const RibbonWarp& warp);

  /// The motion at s by linear blending of the neighbouring samples, renormalised (DLB).
  DualQuaternion At(double s) const;

  const std::vector<DualQuaternion>& Samples() const { return this->Data; }
  const std::vector<Piece>& Pieces() const { return this->Grid.pieces; }

private:
  const std::vector<DualQuaternion>& Data;
  const SampleGrid& Grid;
};

} // namespace bender

#endif
