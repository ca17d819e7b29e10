#include "WarpBinding.h"

#include "Decay.h"
#include "ExactWarpKernel.h"
#include "FastWarpKernel.h"
#include "GeometryErrors.h"
#define BENDER_LANE_BLOCKS
#include "WireProjectionLane.h"

#include <algorithm>
#include <cmath>

namespace bender
{
namespace
{
bool SameEnd(const RibbonEnd& a, const RibbonEnd& b)
{
  auto eq = [](const Vec3& u, const Vec3& v) { return u.x == v.x && u.y == v.y && u.z == v.z; };
  return eq(a.position, b.position) && eq(a.tangent, b.tangent) && eq(a.normal, b.normal);
}

using lane::FlatWire;

using lane::Block;
using lane::BlockSize;
using lane::WeightParameters;

template<bool Line1, bool Line2>
BENDER_SIMD_INLINE void BindBlockBody(const FlatWire& wire,
  const WeightParameters& parameters,
  Block& b,
  int n)
{
  // Local copies: the stores into b cannot alias them.
  const FlatWire w = wire;
  const WeightParameters q = parameters;
  lane::ProjectBlock<Line1, Line2, false>(w, q.radius, b, n);
  lane::WeightBlock(q, b, n);
}

using BindBlockFunction = void (*)(const FlatWire&, const WeightParameters&, Block&, int);

#define BENDER_BIND_VARIANT(Attributes, Name)                                                      \
  template<bool Line1, bool Line2>                                                                 \
  Attributes void Name(const FlatWire& wire, const WeightParameters& q, Block& b, int n)           \
  {                                                                                                \
    BindBlockBody<Line1, Line2>(wire, q, b, n);                                                    \
  }
BENDER_BIND_VARIANT(, BindBaseline)
#ifdef BENDER_SIMD_DISPATCH
BENDER_BIND_VARIANT(BENDER_TARGET_AVX2, BindAvx2)
BENDER_BIND_VARIANT(BENDER_TARGET_AVX512, BindAvx512)
#endif
#undef BENDER_BIND_VARIANT

template<bool Line1, bool Line2>
BindBlockFunction BindFunctionOf(SimdLevel level)
{
#ifdef BENDER_SIMD_DISPATCH
  switch (level)
  {
    case SimdLevel::Avx512:
      return BindAvx512<Line1, Line2>;
    case SimdLevel::Avx2:
      return BindAvx2<Line1, Line2>;
    case SimdLevel::Baseline:
      break;
  }
#else
  (void)level;
#endif
  return BindBaseline<Line1, Line2>;
}

BindBlockFunction BindFunctionOf(SimdLevel level, bool line1, bool line2)
{
  if (line1)
  {
    return line2 ? BindFunctionOf<true, true>(level) : BindFunctionOf<true, false>(level);
  }
  return line2 ? BindFunctionOf<false, true>(level) : BindFunctionOf<false, false>(level);
}
} // namespace

WarpBinding::WarpBinding(const WarpSpec& spec, BlendMode blend)
  : InitialSpec(spec.initial)
  , R(spec.radius)
  , Decay(spec.decay)
  , Blend(blend)
{
  if (!std::isfinite(spec.radius) || !(spec.radius > 0.0))
  {
    throw InvalidWarpError("radius", "must be a finite number > 0");
  }
  try
  {
    this->Initial = Ribbon(spec.initial);
  }
  catch (const InvalidRibbonError& e)
  {
    throw InvalidRibbonError(e.field().empty() ? "initial" : "initial." + e.field(), e.problem());
  }
  // The tube of radius R around the wire lies in the box of the wire's points grown by R.
  // The wire is sampled densely enough that the sagitta between samples (at most
  // L^2 / (8 r n^2) per arc) is covered by a small extra margin.
  const Biarc& w = this->Initial.Wire();
  const int n = 256;
  Vec3 lo = w.Start(), hi = w.Start();
  for (int i = 0; i <= n; ++i)
  {
    const Vec3 p = w.PointAt(static_cast<double>(i) / n);
    lo = { std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z) };
    hi = { std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z) };
  }
  const double margin = this->R + w.Length() / n + 1e-9 * std::max(1.0, Norm(hi - lo));
  this->BoxMin = lo - Vec3{ margin, margin, margin };
  this->BoxMax = hi + Vec3{ margin, margin, margin };
  // Capsules: each arc lies within `deviation` of its chord, measured at n + 1 samples; a point
  // of the arc between two samples is within L / (2 n) of one of them. A point within R of the
  // arc is then within R + deviation + L / (2 n) of the chord; the radius adds L / n and a
  // relative 1e-9 so that rounding never rejects a point the projection would keep.
  const Arc* arcs[2] = { &w.FirstArc(), &w.SecondArc() };
  for (int a = 0; a < 2; ++a)
  {
    const Arc& arc = *arcs[a];
    Capsule& c = this->Capsules[a];
    c.start = arc.start;
    const Vec3 chord = arc.PointAt(1.0) - arc.start;
    c.length = Norm(chord);
    c.axis = c.length > 0.0 ? chord / c.length : Vec3{ 0.0, 0.0, 0.0 };
    double deviation = 0.0;
    for (int i = 0; i <= n; ++i)
    {
      const Vec3 rel = arc.PointAt(static_cast<double>(i) / n) - c.start;
      const double t = std::clamp(Dot(rel, c.axis), 0.0, c.length);
      deviation = std::max(deviation, Norm(rel - c.axis * t));
    }
    const double r =
      (this->R + deviation + arc.length / n) * (1.0 + 1e-9) + 1e-9 * std::max(1.0, Norm(hi - lo));
    c.radiusSquared = r * r;
  }
  auto flat = std::make_shared<FlatWire>();
  lane::FlattenWire(w, *flat, true);
  this->Flat = std::move(flat);
  auto weighting = std::make_shared<WeightParameters>();
  weighting->radius = this->R;
  weighting->invRadius = 1.0 / this->R;
  weighting->plateau = this->Decay.plateau;
  weighting->invWidth = 1.0 / (1.0 - this->Decay.plateau);
  weighting->bell = this->Decay.shape == DecayShape::Bell;
  weighting->singleProjection = this->Blend == BlendMode::SingleProjection;
  this->Weighting = std::move(weighting);
}

BENDER_SIMD_INLINE bool WarpBinding::InCapsule(const Capsule& c, const Vec3& p)
{
  const Vec3 rel = p - c.start;
  const double along = Dot(rel, c.axis);
  const double t = along < 0.0 ? 0.0 : (c.length < along ? c.length : along); // std::clamp
  const Vec3 off = rel - c.axis * t;
  return Dot(off, off) <= c.radiusSquared;
}

bool WarpBinding::InCapsules(const Vec3& p) const
{
  return InCapsule(this->Capsules[0], p) || InCapsule(this->Capsules[1], p);
}

bool WarpBinding::Matches(const WarpSpec& spec, BlendMode blend) const
{
  return blend == this->Blend && spec.radius == this->R && spec.decay.shape == this->Decay.shape &&
    (spec.decay.shape == DecayShape::Bell || spec.decay.plateau == this->Decay.plateau) &&
    spec.initial.extraTurns == this->InitialSpec.extraTurns &&
    SameEnd(spec.initial.start, this->InitialSpec.start) &&
    SameEnd(spec.initial.end, this->InitialSpec.end);
}

bool WarpBinding::InBox(const Vec3& p) const
{
  return p.x >= this->BoxMin.x && p.x <= this->BoxMax.x && p.y >= this->BoxMin.y &&
    p.y <= this->BoxMax.y && p.z >= this->BoxMin.z && p.z <= this->BoxMax.z;
}

bool WarpBinding::Bind(const Vec3& p, BoundPoint& out) const
{
  return this->InBox(p) && this->InCapsules(p) && this->BindProjected(p, out);
}

bool WarpBinding::BindProjected(const Vec3& p, BoundPoint& out) const
{
  lane::Kept k;
  lane::ProjectOne(*this->Flat, p.x, p.y, p.z, this->R, k);
  BoundPoint rec;
  if (lane::Weights(k.d0, k.d1, k.s0, k.s1, *this->Weighting, rec.s0, rec.s1, rec.f, rec.lambda0) ==
    0.0)
  {
    return false;
  }
  out = rec;
  return true;
}

template<typename T>
void WarpBinding::BindRange(const T* xyz,
  std::size_t begin,
  std::size_t end,
  BoundPoint* records,
  std::uint8_t* bound) const
{
  const FlatWire& wire = *this->Flat;
  const WeightParameters& q = *this->Weighting;
  const BindBlockFunction bind =
    BindFunctionOf(FastWarpKernel::BestLevel(), wire.arcs[0].line, wire.arcs[1].line);
  Block b;
  std::size_t ids[BlockSize];
  // The capsule test pays where points fall in the box but outside the capsules (a curved
  // wire, a mesh filling the box) and only costs where every point is inside them (a tube
  // around a straight wire). It is conservative, so skipping it changes no record: blocks of
  // points use it while the last probed block had at least 1/8 of its in-box points rejected
  // by it, and every 16th block probes again.
  bool useCapsules = true;
  std::size_t blockIndex = 0;
  for (std::size_t first = begin; first < end; first += BlockSize, ++blockIndex)
  {
    const std::size_t last = std::min(end, first + BlockSize);
    const bool probe = useCapsules || blockIndex % 16 == 0;
    // The box and capsule tests of the whole block, vectorised (the operations of InBox and
    // InCapsules, so that Bind decides alike), then the points left packed for the kernel.
    const int count = static_cast<int>(last - first);
    const T* c = xyz + 3 * first;
    for (int i = 0; i < count; ++i)
    {
      b.x[i] = static_cast<double>(c[3 * i]);
      b.y[i] = static_cast<double>(c[3 * i + 1]);
      b.z[i] = static_cast<double>(c[3 * i + 2]);
    }
    const Vec3 lo = this->BoxMin;
    const Vec3 hi = this->BoxMax;
    const Capsule c0 = this->Capsules[0];
    const Capsule c1 = this->Capsules[1];
    if (probe)
    {
#pragma omp simd
      for (int i = 0; i < count; ++i)
      {
        const Vec3 p{ b.x[i], b.y[i], b.z[i] };
        const bool box = (p.x >= lo.x) & (p.x <= hi.x) & (p.y >= lo.y) & (p.y <= hi.y) &
          (p.z >= lo.z) & (p.z <= hi.z);
        const bool capsules = InCapsule(c0, p) | InCapsule(c1, p);
        b.flag[i] = box ? (capsules ? 2.0 : 1.0) : 0.0;
      }
    }
    else
    {
#pragma omp simd
      for (int i = 0; i < count; ++i)
      {
        const double x = b.x[i], y = b.y[i], z = b.z[i];
        const bool box =
          (x >= lo.x) & (x <= hi.x) & (y >= lo.y) & (y <= hi.y) & (z >= lo.z) & (z <= hi.z);
        b.flag[i] = box ? 2.0 : 0.0;
      }
    }
    std::size_t inBox = 0;
    std::size_t rejected = 0;
    int n = 0;
    for (int i = 0; i < count; ++i)
    {
      const double flag = b.flag[i];
      if (flag == 0.0)
      {
        continue;
      }
      ++inBox;
      if (flag == 1.0)
      {
        ++rejected;
        continue;
      }
      b.x[n] = b.x[i];
      b.y[n] = b.y[i];
      b.z[n] = b.z[i];
      ids[n++] = first + static_cast<std::size_t>(i);
    }
    std::fill(bound + first, bound + last, std::uint8_t{ 0 });
    if (probe)
    {
      useCapsules = inBox > 0 && 8 * rejected >= inBox;
    }
    if (n == 0)
    {
      continue;
    }
    bind(wire, q, b, n);
    for (int k = 0; k < n; ++k)
    {
      if (b.flag[k] == 0.0)
      {
        continue;
      }
      const std::size_t i = ids[k];
      records[i] = { b.s0[k], b.s1[k], b.f[k], b.lambda0[k] };
      bound[i] = b.flag[k] == 2.0 ? 2 : 1;
    }
  }
}

template void WarpBinding::BindRange<float>(const float*,
  std::size_t,
  std::size_t,
  BoundPoint*,
  std::uint8_t*) const;
template void WarpBinding::BindRange<double>(const double*,
  std::size_t,
  std::size_t,
  BoundPoint*,
  std::uint8_t*) const;

WarpEvaluator::WarpEvaluator(const RibbonWarp& warp, WarpPrecision precision)
  : Warp(warp)
  , Precision(precision)
{
  if (precision == WarpPrecision::Table)
  {
    this->Table.reset(new MotionTable(warp));
  }
  else
  {
    this->Exact.reset(new ExactWarpKernel(warp));
  }
}

WarpEvaluator::~WarpEvaluator() = default;

DualQuaternion WarpEvaluator::MotionAt(double s) const
{
  return this->Precision == WarpPrecision::Exact ? this->Warp.MotionAt(s) : this->Table->At(s);
}

Vec3 WarpEvaluator::Apply(const Vec3& p, const BoundPoint& rec) const
{
  if (this->Exact)
  {
    return this->Exact->Apply(p, rec);
  }
  if (rec.lambda0 >= 1.0)
  {
    return ApplyScrewFraction(this->MotionAt(rec.s0), p, rec.f);
  }
  return ApplyScrewFraction(this->MotionAt(rec.s0), p, rec.f) * rec.lambda0 +
    ApplyScrewFraction(this->MotionAt(rec.s1), p, rec.f) * (1.0 - rec.lambda0);
}

template<typename T>
void WarpEvaluator::EvaluateRange(const WarpBatch<T>& batch,
  std::size_t begin,
  std::size_t end) const
{
  if (this->Exact)
  {
    this->Exact->EvaluateRange(batch, begin, end);
    return;
  }
  for (std::size_t k = begin; k < end; ++k)
  {
    const std::int64_t i = batch.ids[k];
    const T* q = batch.in + 3 * i;
    const Vec3 p{ static_cast<double>(q[0]), static_cast<double>(q[1]), static_cast<double>(q[2]) };
    const Vec3 r = this->Apply(p, batch.records[i]);
    T* o = batch.out + 3 * i;
    o[0] = static_cast<T>(r.x);
    o[1] = static_cast<T>(r.y);
    o[2] = static_cast<T>(r.z);
  }
}

template void WarpEvaluator::EvaluateRange(const WarpBatch<float>&, std::size_t, std::size_t) const;
template void WarpEvaluator::EvaluateRange(const WarpBatch<double>&,
  std::size_t,
  std::size_t) const;

} // namespace bender
