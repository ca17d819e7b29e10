#ifndef bender_ExactWarpKernel_h
#define bender_ExactWarpKernel_h

#include "RibbonWarp.h"
#include "WarpBinding.h"

#include <cstddef>
#include <cstdint>

namespace bender
{

/// The exact (double precision) evaluation of many bound points, batched: the closed-form
/// frames of both ribbons, the lifted relative motion and the power f of its screw for blocks
/// of 8 points at a time, branch-free so that the compiler vectorises it, with sin, cos and
/// atan2 as polynomials accurate to a few units in the last place. Agrees with RibbonWarp's
/// single-point evaluation (MotionAt, ApplyScrewFraction) within about 1e-14 of the scene.
///
/// Every point goes through the same operations whatever the block it falls in (blocks are
/// padded, never shortened), so the results are bit-for-bit the same however a range is split
/// between threads. The instruction set is chosen once per process (AVX2 + FMA or AVX-512
/// where the CPU has them, as FastWarpKernel).
class ExactWarpKernel
{
public:
  /// Refers to `warp`, which must outlive the kernel.
  explicit ExactWarpKernel(const RibbonWarp& warp);

  /// Warps the points of `batch` listed in batch.ids[begin, end). Returns how many results are
  /// not finite. Safe to call concurrently on disjoint ranges.
  template<typename T>
  std::size_t EvaluateRange(const WarpBatch<T>& batch, std::size_t begin, std::size_t end) const;

  /// The warp of one point (the same block computation as EvaluateRange).
  Vec3 Apply(const Vec3& p, const BoundPoint& rec) const;

  /// Points per block.
  static constexpr int Lanes = 8;

  /// Per-block input and output, structure of arrays.
  struct Block
  {
    alignas(64) double px[Lanes], py[Lanes], pz[Lanes];
    alignas(64) double s0[Lanes], s1[Lanes], f[Lanes], lambda0[Lanes];
    // Sign references of the lifted rotation at s0 and s1 (from the sign table).
    alignas(64) double r0[4][Lanes], r1[4][Lanes];
    alignas(64) double ox[Lanes], oy[Lanes], oz[Lanes];
  };

  /// Flat copies of the closed-form frames of one ribbon (RibbonWarp::FramePath).
  struct Path
  {
    double sJ, tau;
    double invFirst, invSecond; ///< 1 / sJ and 1 / (1 - sJ) (0 for an empty arc)
    double start[2][3], tangent[2][3], toCentre[2][3], axis[2][3];
    double angle[2], length[2], twistOffset[2];
    double base[2][4];
  };

private:
  const RibbonWarp& Warp;
  Path Paths[2];

  void Fill(Block& b, int lane, const Vec3& p, const BoundPoint& rec) const;
};

} // namespace bender

#endif
