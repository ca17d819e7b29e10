#ifndef bender_MotionTable_h
#define bender_MotionTable_h

#include "RibbonWarp.h"

#include <vector>

namespace bender
{

/// The lifted relative motions of a warp sampled along s for fast interpolation (spec 9(b)).
/// The motion is smooth in s except where either wire passes its junction (the curvature
/// jumps there), so the samples are uniform on each of the (at most three) pieces between
/// s = 0, the two junction parameters and s = 1: linear interpolation is then second order
/// everywhere, with no first-order error at the junctions.
class MotionTable
{
public:
  /// A uniform piece [start, start + length] sampled at indices [offset, last].
  struct Piece
  {
    double start = 0.0;
    double end = 1.0;
    double scale = 0.0; ///< (samples - 1) / length
    int offset = 0;
    int last = 0; ///< index of the piece's final sample
  };

  /// About `samples` samples in all (at least 2 per piece).
  MotionTable(const RibbonWarp& warp, int samples = 2048);

  /// The motion at s by linear blending of the neighbouring samples, renormalised (DLB).
  DualQuaternion At(double s) const;

  const std::vector<DualQuaternion>& Samples() const { return this->Data; }
  const std::vector<Piece>& Pieces() const { return this->Parts; }

private:
  std::vector<DualQuaternion> Data;
  std::vector<Piece> Parts;
};

} // namespace bender

#endif
