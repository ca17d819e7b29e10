#ifndef bender_WarpBinding_h
#define bender_WarpBinding_h

#include "MotionTable.h"
#include "RibbonWarp.h"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace bender
{
class ExactWarpKernel;
namespace lane
{
struct FlatWire;
struct WeightParameters;
}

/// What a point needs from the initial ribbon to be warped (spec 6, 9): the parameters of its
/// (at most two) projections and its weights. lambda0 == 1 means one projection counts.
struct BoundPoint
{
  double s0 = 0.0;
  double s1 = 0.0;
  double f = 0.0;       ///< combined weight f = 1 - (1 - f0)(1 - f1), or f0 alone
  double lambda0 = 1.0; ///< f0 / (f0 + f1); the second image gets 1 - lambda0
};

/// Points to warp, all of them x y z interleaved: for each listed id i, out[3 i + c] is the
/// warp of in[3 i + c] with the record records[i]; the other points are not touched.
template<typename T>
struct WarpBatch
{
  const T* in = nullptr;
  T* out = nullptr;
  const BoundPoint* records = nullptr;
  const std::int64_t* ids = nullptr;
};

/// The per-grab half of the warp (spec 9): projections of points onto the initial wire,
/// depending only on the initial ribbon, R, the decay and the blend mode. Computed once when
/// the user grabs; the final ribbon can then move freely at the cost of an evaluation only.
class WarpBinding
{
public:
  /// Throws InvalidRibbonError (initial ribbon) and InvalidWarpError (radius) as RibbonWarp
  /// does.
  WarpBinding(const WarpSpec& spec, BlendMode blend);

  /// True when a warp with this spec and mode can reuse this binding (same initial ribbon,
  /// radius, decay and blend mode).
  bool Matches(const WarpSpec& spec, BlendMode blend) const;

  /// The record of one point; false when it is outside the region of influence (P' = P).
  bool Bind(const Vec3& p, BoundPoint& out) const;

  /// Binds points [begin, end) of the xyz array (3 values each): bound[i] = 0 when point i is
  /// outside the region of influence (records[i] is then left as it was), 1 when it is bound
  /// with one projection counting (lambda0 == 1), 2 with two (lambda0 < 1). The records are bit
  /// for bit those of Bind(): the same arithmetic, batched (box and capsule tests, then the
  /// projection and the weights of the points left, vectorised with the instruction set chosen
  /// at run time). Safe to call concurrently on disjoint ranges; how a range is split does not
  /// change any record.
  template<typename T>
  void BindRange(const T* xyz,
    std::size_t begin,
    std::size_t end,
    BoundPoint* records,
    std::uint8_t* bound) const;

  const Ribbon& InitialRibbon() const { return this->Initial; }
  double Radius() const { return this->R; }

private:
  RibbonSpec InitialSpec;
  Ribbon Initial;
  double R;
  DecaySpec Decay;
  BlendMode Blend;
  Vec3 BoxMin, BoxMax; // bounds of the region of influence, for quick rejection
  /// A capsule around each arc's chord holding every point within R of the arc: a point
  /// outside both is outside the region of influence, rejected before any projection.
  struct Capsule
  {
    Vec3 start;
    Vec3 axis;           ///< unit chord direction (zero for a zero-length chord)
    double length = 0.0; ///< chord length
    double radiusSquared = 0.0;
  };
  Capsule Capsules[2];
  std::shared_ptr<const lane::FlatWire> Flat; // the initial wire as the projection reads it
  std::shared_ptr<const lane::WeightParameters> Weighting; // R and the decay, for the weights
  bool InBox(const Vec3& p) const;
  static bool InCapsule(const Capsule& c, const Vec3& p);
  bool InCapsules(const Vec3& p) const;
  /// Bind() for a point that passed the box (and optionally the capsule) test.
  bool BindProjected(const Vec3& p, BoundPoint& out) const;
};

/// How the screws are evaluated per point.
enum class WarpPrecision
{
  Exact, ///< frames and screw at each point's exact s (double precision; the normative result)
  Table  ///< screws interpolated from a MotionTable (second order in ds; interactive moves)
};

/// The per-move half of the warp: evaluates the bound points under a RibbonWarp.
class WarpEvaluator
{
public:
  WarpEvaluator(const RibbonWarp& warp, WarpPrecision precision);
  ~WarpEvaluator();

  /// The interpolation table (Table precision only, else null).
  const MotionTable* GetMotionTable() const { return this->Table.get(); }

  /// The lifted relative motion at s, exact or interpolated per the precision.
  DualQuaternion MotionAt(double s) const;

  /// The warped position of p with its record. Exact precision: the batched ExactWarpKernel's
  /// result, bit-for-bit what EvaluateRange gives for the point.
  Vec3 Apply(const Vec3& p, const BoundPoint& rec) const;

  /// Warps the points of `batch` listed in batch.ids[begin, end). Safe to call concurrently on
  /// disjoint ranges; exact results do not depend on how a range is split (thread counts).
  template<typename T>
  void EvaluateRange(const WarpBatch<T>& batch, std::size_t begin, std::size_t end) const;

private:
  const RibbonWarp& Warp;
  WarpPrecision Precision;
  std::unique_ptr<MotionTable> Table;
  std::unique_ptr<ExactWarpKernel> Exact;
};

} // namespace bender

#endif
