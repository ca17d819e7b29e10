#ifndef bender_WireProjectionLane_h
#define bender_WireProjectionLane_h

// The per-point arithmetic of the projection onto a wire (spec 3.3) and of the binding's weights
// (spec 5, 6), written once, branch-free, on scalars: the scalar paths (ProjectOntoWire,
// WarpBinding::Bind) call it for one point and the batched ones (the block kernels of
// WireProjection.cxx and WarpBinding.cxx) inside `#pragma omp simd` loops compiled for the
// instruction set chosen at run time. Both kinds of callers are compiled with
// -ffp-contract=off and use only IEEE operations (sqrt, division, the polynomial atan2 of
// SimdMath.h), so a vectorised lane gives bit for bit the scalar result. Internal to the
// geometry module.

#include "Biarc.h"
#include "Decay.h"
#include "SimdMath.h"

#include <limits>

namespace bender
{
namespace lane
{

/// One arc of the wire, flattened.
struct FlatArc
{
  double start[3], tangent[3], toCentre[3];
  double radius = 0.0, angle = 0.0, length = 0.0;
  double axisTolerance = 0.0;          ///< 1e-12 r: closer to the axis than this, no interior foot
  double invLength = 0.0;              ///< 1 / L (0 for an empty arc)
  double invAngle = 0.0;               ///< 1 / theta (0 for a line)
  double first[3] = { 0.0, 0.0, 0.0 }; ///< PointAt(0): the foot clamped to the arc's start
  double last[3] = { 0.0, 0.0, 0.0 };  ///< PointAt(1): the foot clamped to the arc's end
  bool line = false;
};

/// The initial wire as the projection reads it.
struct FlatWire
{
  FlatArc arcs[2];
  double start[3], startTangent[3], junction[3], junctionTangent[3], end[3], endTangent[3];
  double sJ = 0.0;
  bool clampedFeet = false; ///< FlatArc::first / last filled (FlattenWire with clampedFeet)
};

/// Copies `wire`; with `clampedFeet` also the arcs' end points (sin and cos of their angles),
/// which only points whose angle rounds outside an arc need.
void FlattenWire(const Biarc& wire, FlatWire& out, bool clampedFeet);

/// The decay of spec 5 (EvaluateDecay) on a lane, selects for branches, the plateau's width
/// given as its inverse (invWidth = 1 / (1 - plateau)).
BENDER_SIMD_INLINE double Decay(bool bell, double plateau, double invWidth, double x)
{
  const bool inside = x < 1.0;
  const double c = 0.0 < x ? x : 0.0; // std::max(0.0, x)
  const double v = 1.0 - c * c;
  const double fb = v * v * v;
  const double u = (c - plateau) * invWidth;
  const double w = 1.0 - u;
  const double fp = c <= plateau ? 1.0 : w * w * w * (1.0 + 3.0 * u + 6.0 * u * u);
  const double f = bell ? fb : fp;
  const double clamped = f < 0.0 ? 0.0 : (1.0 < f ? 1.0 : f); // std::clamp(f, 0.0, 1.0)
  return inside ? clamped : 0.0;
}

/// Nearest point of an arc (a segment when Line) to p, the angle clamped to the arc: the
/// parameter u in [0, 1] along the arc, the foot q, `ok` false when p is on a circle's axis,
/// `clamped` true when the angle fell outside the arc (q is then an end of the arc).
template<bool Line>
BENDER_SIMD_INLINE void NearestOnArc(const FlatArc& a,
  double px,
  double py,
  double pz,
  bool& ok,
  bool& clamped,
  double& u,
  double& qx,
  double& qy,
  double& qz)
{
  const double rx = px - a.start[0];
  const double ry = py - a.start[1];
  const double rz = pz - a.start[2];
  const double aT = rx * a.tangent[0] + ry * a.tangent[1] + rz * a.tangent[2];
  if (Line)
  {
    const double t = aT < 0.0 ? 0.0 : (a.length < aT ? a.length : aT); // std::clamp
    u = t * a.invLength;
    qx = a.start[0] + a.tangent[0] * t;
    qy = a.start[1] + a.tangent[1] * t;
    qz = a.start[2] + a.tangent[2] * t;
    ok = true;
    clamped = false;
    return;
  }
  // phi = atan2(kappa (P - Ps).Ts, 1 - kappa (P - Ps).Np), scaled by r: the centre is never
  // formed.
  const double aN = rx * a.toCentre[0] + ry * a.toCentre[1] + rz * a.toCentre[2];
  const double y = aT;
  const double x = a.radius - aN;
  const double rho = std::sqrt(x * x + y * y);
  ok = !(rho <= a.axisTolerance);
  const double raw = simd::Atan2Signed(y, x);
  const bool low = raw < 0.0;
  const bool high = a.angle < raw;
  const double phi = low ? 0.0 : (high ? a.angle : raw);
  u = phi * a.invAngle;
  clamped = low | high;
  // Q = Ps + r sin(phi) Ts + r (1 - cos(phi)) Np with cos and sin read off (x, y): no
  // trigonometry, and r (1 - cos) = r sin^2 / (1 + cos) keeps nearly straight arcs exact.
  const double invRho = 1.0 / rho;
  const double c = x * invRho;
  const double sn = y * invRho;
  const double r = a.radius;
  const double lift = c > 0.0 ? r * sn * sn / (1.0 + c) : r * (1.0 - c);
  const double along = r * sn;
  // Clamped: Arc::PointAt(u) with u exactly 0 or 1.
  const bool toLast = high & (a.angle > 0.0);
  qx = clamped ? (toLast ? a.last[0] : a.first[0])
               : a.start[0] + a.tangent[0] * along + a.toCentre[0] * lift;
  qy = clamped ? (toLast ? a.last[1] : a.first[1])
               : a.start[1] + a.tangent[1] * along + a.toCentre[1] * lift;
  qz = clamped ? (toLast ? a.last[2] : a.first[2])
               : a.start[2] + a.tangent[2] * along + a.toCentre[2] * lift;
}

/// The (at most two) kept projections of one point, nearest first: distance +infinity marks an
/// empty slot.
struct Kept
{
  double s0 = 0.0, d0 = std::numeric_limits<double>::infinity(), q0x = 0.0, q0y = 0.0, q0z = 0.0;
  double s1 = 0.0, d1 = std::numeric_limits<double>::infinity(), q1x = 0.0, q1y = 0.0, q1z = 0.0;
  bool clamped = false; ///< an arc's foot was clamped to its end (needs FlatArc::first / last)
};

/// Offers a candidate: kept when valid and closer than radius, in place among the two nearest
/// (s0, d0, q0) and (s1, d1, q1), ties by smaller s (a stable insertion, as sorting all
/// candidates would give).
BENDER_SIMD_INLINE void OfferTo(bool valid,
  double radius,
  double s,
  double d,
  double qx,
  double qy,
  double qz,
  double& s0,
  double& d0,
  double& q0x,
  double& q0y,
  double& q0z,
  double& s1,
  double& d1,
  double& q1x,
  double& q1y,
  double& q1z)
{
  // Bitwise operators on the conditions: no short circuit, so that no operand is loaded
  // conditionally (masked loads) in a vectorised loop.
  const bool accept = valid & (d < radius);
  const bool first = accept & ((d < d0) | ((d == d0) & (s < s0)));
  const bool second = accept & !first & ((d < d1) | ((d == d1) & (s < s1)));
  s1 = first ? s0 : (second ? s : s1);
  d1 = first ? d0 : (second ? d : d1);
  q1x = first ? q0x : (second ? qx : q1x);
  q1y = first ? q0y : (second ? qy : q1y);
  q1z = first ? q0z : (second ? qz : q1z);
  s0 = first ? s : s0;
  d0 = first ? d : d0;
  q0x = first ? qx : q0x;
  q0y = first ? qy : q0y;
  q0z = first ? qz : q0z;
}

BENDER_SIMD_INLINE void
Offer(Kept& k, bool valid, double radius, double s, double d, double qx, double qy, double qz)
{
  OfferTo(valid,
    radius,
    s,
    d,
    qx,
    qy,
    qz,
    k.s0,
    k.d0,
    k.q0x,
    k.q0y,
    k.q0z,
    k.s1,
    k.d1,
    k.q1x,
    k.q1y,
    k.q1z);
}

BENDER_SIMD_INLINE double DistanceTo(double px,
  double py,
  double pz,
  double qx,
  double qy,
  double qz)
{
  const double dx = px - qx;
  const double dy = py - qy;
  const double dz = pz - qz;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// Every local minimum of the distance from p to the wire by the signed-plane partition of
/// spec 3.3 (ProjectOntoWire), the two nearest closer than radius kept.
template<bool Line1, bool Line2>
BENDER_SIMD_INLINE void Project(const FlatWire& w,
  double px,
  double py,
  double pz,
  double radius,
  Kept& k)
{
  const double h0 = (px - w.start[0]) * w.startTangent[0] + (py - w.start[1]) * w.startTangent[1] +
    (pz - w.start[2]) * w.startTangent[2];
  const double hJ = (px - w.junction[0]) * w.junctionTangent[0] +
    (py - w.junction[1]) * w.junctionTangent[1] + (pz - w.junction[2]) * w.junctionTangent[2];
  const double h1 = (px - w.end[0]) * w.endTangent[0] + (py - w.end[1]) * w.endTangent[1] +
    (pz - w.end[2]) * w.endTangent[2];
  // Field by field (not k = Kept{}), so that the compiler keeps the lane in registers.
  const double infinity = std::numeric_limits<double>::infinity();
  k.s0 = k.s1 = 0.0;
  k.d0 = k.d1 = infinity;
  k.q0x = k.q0y = k.q0z = k.q1x = k.q1y = k.q1z = 0.0;
  bool ok, clamped;
  double u, qx, qy, qz;
  NearestOnArc<Line1>(w.arcs[0], px, py, pz, ok, clamped, u, qx, qy, qz);
  const bool in1 = (h0 >= 0.0) & (hJ < 0.0) & ok;
  k.clamped = in1 & clamped;
  Offer(k, in1, radius, w.sJ * u, DistanceTo(px, py, pz, qx, qy, qz), qx, qy, qz);
  NearestOnArc<Line2>(w.arcs[1], px, py, pz, ok, clamped, u, qx, qy, qz);
  const bool in2 = (hJ >= 0.0) & (h1 <= 0.0) & ok;
  k.clamped = k.clamped | (in2 & clamped);
  Offer(k, in2, radius, w.sJ + (1.0 - w.sJ) * u, DistanceTo(px, py, pz, qx, qy, qz), qx, qy, qz);
  // The wire's two end points, at s = 0 and s = 1.
  const auto offerEnd = [&](bool valid, double s, const double* e)
  { Offer(k, valid, radius, s, DistanceTo(px, py, pz, e[0], e[1], e[2]), e[0], e[1], e[2]); };
  offerEnd(h0 < 0.0, 0.0, w.start);
  offerEnd(h1 > 0.0, 1.0, w.end);
}

/// Project for one point, the arcs' kinds read at run time.
inline void ProjectOne(const FlatWire& w, double px, double py, double pz, double radius, Kept& k)
{
  const bool l1 = w.arcs[0].line;
  const bool l2 = w.arcs[1].line;
  if (l1 && l2)
  {
    Project<true, true>(w, px, py, pz, radius, k);
  }
  else if (l1)
  {
    Project<true, false>(w, px, py, pz, radius, k);
  }
  else if (l2)
  {
    Project<false, true>(w, px, py, pz, radius, k);
  }
  else
  {
    Project<false, false>(w, px, py, pz, radius, k);
  }
}

/// What the binding's weights depend on besides the distances.
struct WeightParameters
{
  double radius = 1.0;
  double invRadius = 1.0;
  double plateau = 0.0;
  double invWidth = 1.0; ///< 1 / (1 - plateau)
  bool bell = true;
  bool singleProjection = false;
};

/// The binding's record of a point from its kept projections (WarpBinding::Bind): returns the
/// flag 0 (not bound), 1 (bound, one projection counts) or 2 (two: lambda0 < 1), as a double
/// so that a vectorised loop stays in one element width.
BENDER_SIMD_INLINE double Weights(double d0,
  double d1,
  double ks0,
  double ks1,
  const WeightParameters& q,
  double& s0,
  double& s1,
  double& f,
  double& lambda0)
{
  const double f0 = Decay(q.bell, q.plateau, q.invWidth, d0 * q.invRadius);
  const double f1 = Decay(q.bell, q.plateau, q.invWidth, d1 * q.invRadius);
  const bool one = !(d1 < q.radius) | q.singleProjection;
  const double sum = f0 + f1;
  const double combined = 1.0 - (1.0 - f0) * (1.0 - f1);
  const double share = f0 / sum;
  s0 = ks0;
  s1 = one ? ks0 : ks1;
  f = one ? f0 : combined;
  lambda0 = one ? 1.0 : share;
  const bool bound = one ? f0 > 0.0 : sum > 0.0;
  return bound ? (lambda0 < 1.0 ? 2.0 : 1.0) : 0.0;
}

#ifdef BENDER_LANE_BLOCKS // the files compiled with -fopenmp-simd (WireProjection, WarpBinding)
// --- Blocks: the same arithmetic on many points, one candidate kind per pass -----------------
//
// Each pass is a vectorised loop over the block; a pass whose candidate no point of the block
// can have (every point on the other side of its planes) is skipped, which changes nothing
// since an invalid candidate is never kept. The passes offer the candidates in the order of
// Project (arc 1, arc 2, start, end), so every point gets bit for bit Project's result.

/// Points per block.
constexpr int BlockSize = 256;

/// A block of points, their kept projections and (binding) their records, structure of arrays.
struct Block
{
  alignas(64) double x[BlockSize], y[BlockSize], z[BlockSize];
  alignas(64) double h0[BlockSize], hJ[BlockSize], h1[BlockSize];
  alignas(64) double s0[BlockSize], d0[BlockSize], s1[BlockSize], d1[BlockSize];
  alignas(64) double q0x[BlockSize], q0y[BlockSize], q0z[BlockSize];
  alignas(64) double q1x[BlockSize], q1y[BlockSize], q1z[BlockSize];
  alignas(64) double f[BlockSize], lambda0[BlockSize], flag[BlockSize];
};

/// One candidate projection of a point: valid or not, its parameter, distance and foot.
struct Candidate
{
  bool valid;
  double s, d, qx, qy, qz;
};

/// OfferTo on point i of a block: its kept projections (and, with Feet, their feet) are read
/// from the block and written back.
template<bool Feet>
BENDER_SIMD_INLINE void OfferToBlock(const Candidate& c, double radius, Block& b, int i)
{
  double s0 = b.s0[i], d0 = b.d0[i], s1 = b.s1[i], d1 = b.d1[i];
  double q0x = 0.0, q0y = 0.0, q0z = 0.0, q1x = 0.0, q1y = 0.0, q1z = 0.0;
  if (Feet)
  {
    q0x = b.q0x[i];
    q0y = b.q0y[i];
    q0z = b.q0z[i];
    q1x = b.q1x[i];
    q1y = b.q1y[i];
    q1z = b.q1z[i];
  }
  OfferTo(
    c.valid, radius, c.s, c.d, c.qx, c.qy, c.qz, s0, d0, q0x, q0y, q0z, s1, d1, q1x, q1y, q1z);
  b.s0[i] = s0;
  b.d0[i] = d0;
  b.s1[i] = s1;
  b.d1[i] = d1;
  if (Feet)
  {
    b.q0x[i] = q0x;
    b.q0y[i] = q0y;
    b.q0z[i] = q0z;
    b.q1x[i] = q1x;
    b.q1y[i] = q1y;
    b.q1z[i] = q1z;
  }
}

template<int A, bool Line, bool Feet>
BENDER_SIMD_INLINE void ArcPass(const FlatWire& w, double radius, Block& b, int n)
{
  const FlatArc& a = w.arcs[A];
  const double sJ = w.sJ;
#pragma omp simd
  for (int i = 0; i < n; ++i)
  {
    bool ok, clamped;
    double u, qx, qy, qz;
    NearestOnArc<Line>(a, b.x[i], b.y[i], b.z[i], ok, clamped, u, qx, qy, qz);
    const double h0 = b.h0[i], hJ = b.hJ[i], h1 = b.h1[i];
    const bool valid = A == 0 ? (h0 >= 0.0) & (hJ < 0.0) & ok : (hJ >= 0.0) & (h1 <= 0.0) & ok;
    const double s = A == 0 ? sJ * u : sJ + (1.0 - sJ) * u;
    const double d = DistanceTo(b.x[i], b.y[i], b.z[i], qx, qy, qz);
    OfferToBlock<Feet>(Candidate{ valid, s, d, qx, qy, qz }, radius, b, i);
  }
}

template<bool AtEnd, bool Feet>
BENDER_SIMD_INLINE void EndPass(const FlatWire& w, double radius, Block& b, int n)
{
  const double ex = AtEnd ? w.end[0] : w.start[0];
  const double ey = AtEnd ? w.end[1] : w.start[1];
  const double ez = AtEnd ? w.end[2] : w.start[2];
  const double s = AtEnd ? 1.0 : 0.0;
#pragma omp simd
  for (int i = 0; i < n; ++i)
  {
    const bool valid = AtEnd ? b.h1[i] > 0.0 : b.h0[i] < 0.0;
    const double d = DistanceTo(b.x[i], b.y[i], b.z[i], ex, ey, ez);
    OfferToBlock<Feet>(Candidate{ valid, s, d, ex, ey, ez }, radius, b, i);
  }
}

/// Project for the points [0, n) of a block: b.s0, d0, s1, d1 (and with Feet the feet).
template<bool Line1, bool Line2, bool Feet>
BENDER_SIMD_INLINE void ProjectBlock(const FlatWire& w, double radius, Block& b, int n)
{
  const double infinity = std::numeric_limits<double>::infinity();
#pragma omp simd
  for (int i = 0; i < n; ++i)
  {
    const double px = b.x[i], py = b.y[i], pz = b.z[i];
    b.h0[i] = (px - w.start[0]) * w.startTangent[0] + (py - w.start[1]) * w.startTangent[1] +
      (pz - w.start[2]) * w.startTangent[2];
    b.hJ[i] = (px - w.junction[0]) * w.junctionTangent[0] +
      (py - w.junction[1]) * w.junctionTangent[1] + (pz - w.junction[2]) * w.junctionTangent[2];
    b.h1[i] = (px - w.end[0]) * w.endTangent[0] + (py - w.end[1]) * w.endTangent[1] +
      (pz - w.end[2]) * w.endTangent[2];
    b.s0[i] = b.s1[i] = 0.0;
    b.d0[i] = b.d1[i] = infinity;
    if (Feet)
    {
      b.q0x[i] = b.q0y[i] = b.q0z[i] = b.q1x[i] = b.q1y[i] = b.q1z[i] = 0.0;
    }
  }
  int first = 0, second = 0, start = 0, end = 0;
#pragma omp simd reduction(| : first, second, start, end)
  for (int i = 0; i < n; ++i)
  {
    const double h0 = b.h0[i], hJ = b.hJ[i], h1 = b.h1[i];
    first |= (h0 >= 0.0) & (hJ < 0.0) ? 1 : 0;
    second |= (hJ >= 0.0) & (h1 <= 0.0) ? 1 : 0;
    start |= h0 < 0.0 ? 1 : 0;
    end |= h1 > 0.0 ? 1 : 0;
  }
  if (first)
  {
    ArcPass<0, Line1, Feet>(w, radius, b, n);
  }
  if (second)
  {
    ArcPass<1, Line2, Feet>(w, radius, b, n);
  }
  if (start)
  {
    EndPass<false, Feet>(w, radius, b, n);
  }
  if (end)
  {
    EndPass<true, Feet>(w, radius, b, n);
  }
}

/// Weights for the points [0, n) of a projected block: b.s0, s1, f, lambda0 and the flag
/// (Weights). Blocks where no point kept two projections skip the second weight (its results
/// are not selected there).
BENDER_SIMD_INLINE void WeightBlock(const WeightParameters& q, Block& b, int n)
{
  int pairs = 0;
#pragma omp simd reduction(| : pairs)
  for (int i = 0; i < n; ++i)
  {
    pairs |= b.d1[i] < q.radius ? 1 : 0;
  }
  if (pairs)
  {
#pragma omp simd
    for (int i = 0; i < n; ++i)
    {
      double s0, s1, f, lambda0;
      b.flag[i] = Weights(b.d0[i], b.d1[i], b.s0[i], b.s1[i], q, s0, s1, f, lambda0);
      b.s0[i] = s0;
      b.s1[i] = s1;
      b.f[i] = f;
      b.lambda0[i] = lambda0;
    }
    return;
  }
  // Weights with no second projection: what its selects give when `one` holds.
#pragma omp simd
  for (int i = 0; i < n; ++i)
  {
    const double f0 = Decay(q.bell, q.plateau, q.invWidth, b.d0[i] * q.invRadius);
    b.s1[i] = b.s0[i];
    b.f[i] = f0;
    b.lambda0[i] = 1.0;
    b.flag[i] = f0 > 0.0 ? 1.0 : 0.0;
  }
}

#endif // BENDER_LANE_BLOCKS

} // namespace lane
} // namespace bender

#endif
