#ifndef bender_FastWarpKernel_h
#define bender_FastWarpKernel_h

#include "MotionTable.h"

#include <cstddef>
#include <vector>

namespace bender
{

/// The interactive evaluation path of spec 9(b): single-precision, branch-free, vectorised
/// evaluation of points that have one projection, from the lifted dual-quaternion table
/// interpolated linearly in s and renormalised, raised to the power f with polynomial
/// trigonometry. Positions are relative to an origin near the wire so that float keeps
/// about 1e-7 of the ribbon's size. Accuracy: within about 1e-5 of the ribbon's size of the
/// exact warp; use the exact path (WarpEvaluator, Exact) for commits.
class FastWarpKernel
{
public:
  /// Prepares the per-move table from `table`, for positions given relative to `origin`.
  void SetMotion(const MotionTable& table, const Vec3& origin);

  /// For k in [begin, end): (ox, oy, oz)[k] = warp of (px, py, pz)[k] (relative to the origin)
  /// with projection parameter s[k] and weight f[k]. Safe to call concurrently.
  void Evaluate(const float* px, const float* py, const float* pz, const float* s,
    const float* f, float* ox, float* oy, float* oz, std::size_t begin, std::size_t end) const;

private:
  std::vector<float> Table; // 8 floats per sample: real (w, x, y, z), dual (w, x, y, z)
  // The table's (up to three) uniform pieces; unused pieces start beyond s = 1.
  float End[3] = { 2.0f, 2.0f, 2.0f };
  float Start[3] = { 0.0f, 0.0f, 0.0f };
  float Scale[3] = { 0.0f, 0.0f, 0.0f };
  int Offset[3] = { 0, 0, 0 };
  int Last[3] = { 0, 0, 0 };
};

} // namespace bender

#endif
