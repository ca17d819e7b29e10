#ifndef bender_FastWarpKernel_h
#define bender_FastWarpKernel_h

#include "MotionTable.h"
#include "SimdLevel.h"
#include "WarpBinding.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace bender
{

/// Points for FastWarpKernel, structure of arrays: each point's position relative to the
/// kernel's origin (px, py, pz), its projection parameter s in [0, 1] and its weight f.
struct FastWarpPoints
{
  const float* px = nullptr;
  const float* py = nullptr;
  const float* pz = nullptr;
  const float* s = nullptr;
  const float* f = nullptr;

  /// The points from index `first` on.
  FastWarpPoints From(std::size_t first) const
  {
    return {
      this->px + first, this->py + first, this->pz + first, this->s + first, this->f + first
    };
  }
};

/// The interactive evaluation path of spec 9(b): single-precision, branch-free, vectorised
/// evaluation of points that have one projection, from the lifted dual-quaternion table
/// interpolated linearly in s and renormalised, raised to the power f with polynomial
/// trigonometry. Positions are relative to an origin near the wire so that float keeps
/// about 1e-7 of the ribbon's size. Accuracy: within about 1e-5 of the ribbon's size of the
/// exact warp; use the exact path (WarpEvaluator, Exact) for commits.
class FastWarpKernel
{
public:
  /// The instruction sets the kernel is compiled for (SimdLevel.h); the best one the CPU
  /// supports is chosen at run time (the build itself targets the portable baseline).
  using SimdLevel = bender::SimdLevel;
  /// True when this build has a kernel for `level` and the CPU can run it.
  static bool Supports(SimdLevel level);
  /// The best supported level: what a new kernel uses.
  static SimdLevel BestLevel();
  static const char* LevelName(SimdLevel level);
  /// Selects another supported level (for comparisons); false, and no change, when unsupported.
  bool SetLevel(SimdLevel level);
  SimdLevel Level() const { return this->Simd; }

  /// Prepares the per-move table from `table`, for positions given relative to `origin`.
  void SetMotion(const MotionTable& table, const Vec3& origin);

  /// For k in [begin, end): out[c][k] = coordinate c of the warp of point k of `points`
  /// (relative to the origin). Safe to call concurrently.
  void Evaluate(const FastWarpPoints& points,
    const std::array<float*, 3>& out,
    std::size_t begin,
    std::size_t end) const;

  /// Same, written interleaved: xyz[3 k + c] for k in [begin, end), each point plus
  /// `shift` (3 floats; null for none). Returns how many results are not finite.
  std::size_t EvaluateInterleaved(const FastWarpPoints& points,
    float* xyz,
    const float* shift,
    std::size_t begin,
    std::size_t end) const;

private:
  SimdLevel Simd = BestLevel();
  /// 16 floats per sample j: m_j (real w x y z, dual w x y z), then m_{j+1} - m_j.
  std::vector<float> Table;
  // The table's (up to three) uniform pieces; unused pieces start beyond s = 1.
  float End[3] = { 2.0f, 2.0f, 2.0f };
  float Start[3] = { 0.0f, 0.0f, 0.0f };
  float Scale[3] = { 0.0f, 0.0f, 0.0f };
  int Offset[3] = { 0, 0, 0 };
  int Last[3] = { 0, 0, 0 };
};

/// The data layout of the interactive path for one binding (built once per grab): the bound
/// points split into those with one projection, stored as float structure-of-arrays relative to
/// an origin for FastWarpKernel, and those with two projections (lambda0 < 1), which the exact
/// evaluator handles. Scratch arrays for the kernel's output are kept here, so that a move
/// allocates nothing.
class FastWarpLayout
{
public:
  /// Runs body(first, last) over subranges covering [0, count), possibly concurrently.
  using ParallelFor =
    std::function<void(std::size_t count, const std::function<void(std::size_t, std::size_t)>&)>;

  /// Lays out the points of `xyz` (n points, x y z interleaved) whose `bound` flag is set, with
  /// their `records`, relative to `origin` (a point near the wire). The flags are those of
  /// WarpBinding::BindRange: 0 outside, 1 one projection, 2 two (lambda0 < 1). With
  /// `parallelFor` (for instance vtkSMPTools) computed in parallel, counts per fixed chunk, then
  /// every chunk written at its offset; without it serially: the same layout either way.
  template<typename T>
  void Build(const T* xyz,
    std::size_t n,
    const BoundPoint* records,
    const std::uint8_t* bound,
    const Vec3& origin,
    const ParallelFor& parallelFor = nullptr);
  void Clear();

  const Vec3& Origin() const { return this->Center; }
  /// Every bound point, in increasing order.
  const std::vector<std::int64_t>& BoundIds() const { return this->Ids; }
  /// The bound points with one projection (kernel path) and with two (exact evaluator).
  const std::vector<std::int64_t>& SingleIds() const { return this->Singles; }
  const std::vector<std::int64_t>& PairIds() const { return this->Pairs; }

  /// Evaluates the one-projection points k in [begin, end) of SingleIds() with `kernel` (set on
  /// Origin()) and writes them into `out` (n points, interleaved) at their ids. Returns how many
  /// results were not finite. Safe to call concurrently on disjoint ranges.
  template<typename T>
  std::size_t EvaluateSingles(const FastWarpKernel& kernel,
    T* out,
    std::size_t begin,
    std::size_t end) const;

private:
  Vec3 Center;
  std::vector<std::int64_t> Ids, Singles, Pairs;
  std::vector<float> Px, Py, Pz, S, F;
};

} // namespace bender

#endif
