#include "WireProjection.h"

#include "FastWarpKernel.h"
#define BENDER_LANE_BLOCKS
#include "WireProjectionLane.h"

#include <algorithm>
#include <cmath>

namespace bender
{
namespace lane
{
void FlattenWire(const Biarc& wire, FlatWire& out, bool clampedFeet)
{
  const auto copy = [](const Vec3& v, double* to)
  {
    to[0] = v.x;
    to[1] = v.y;
    to[2] = v.z;
  };
  for (int i = 0; i < 2; ++i)
  {
    const Arc& arc = wire.GetArc(i);
    FlatArc& a = out.arcs[i];
    copy(arc.start, a.start);
    copy(arc.tangent, a.tangent);
    copy(arc.toCentre, a.toCentre);
    a.radius = arc.radius;
    a.angle = arc.angle;
    a.length = arc.length;
    a.axisTolerance = 1e-12 * arc.radius;
    a.invLength = arc.length > 0.0 ? 1.0 / arc.length : 0.0;
    // Biarc flags every arc that turns by exactly 0 (or whose radius overflows) a line, so
    // the circle's formulas, which would put every point on the axis of such an arc and find
    // no foot, only ever see a positive turn and a finite radius.
    a.line = arc.line;
    a.invAngle = a.line ? 0.0 : 1.0 / arc.angle;
    if (clampedFeet && !a.line)
    {
      copy(arc.PointAt(0.0), a.first);
      copy(arc.PointAt(1.0), a.last);
    }
  }
  copy(wire.Start(), out.start);
  copy(wire.StartTangent(), out.startTangent);
  copy(wire.Junction(), out.junction);
  copy(wire.JunctionTangent(), out.junctionTangent);
  copy(wire.End(), out.end);
  copy(wire.EndTangent(), out.endTangent);
  out.sJ = wire.JunctionParameter();
  out.clampedFeet = clampedFeet;
}
} // namespace lane

namespace
{
using lane::FlatWire;
using lane::Kept;

void ProjectPoint(const FlatWire& w, const Vec3& p, double radius, Kept& k)
{
  lane::ProjectOne(w, p.x, p.y, p.z, radius, k);
}

WireProjections ToProjections(const Kept& k)
{
  WireProjections out;
  if (k.d0 < std::numeric_limits<double>::infinity())
  {
    out.items[out.count++] = { k.s0, k.d0, { k.q0x, k.q0y, k.q0z } };
  }
  if (k.d1 < std::numeric_limits<double>::infinity())
  {
    out.items[out.count++] = { k.s1, k.d1, { k.q1x, k.q1y, k.q1z } };
  }
  return out;
}

using lane::Block;
using lane::BlockSize;

template<bool Line1, bool Line2>
BENDER_SIMD_INLINE void ProjectBlockBody(const FlatWire& wire, double radius, Block& b, int n)
{
  const FlatWire w = wire; // a local copy: the stores into b cannot alias it
  lane::ProjectBlock<Line1, Line2, true>(w, radius, b, n);
}

using ProjectBlockFunction = void (*)(const FlatWire&, double, Block&, int);

#define BENDER_PROJECT_VARIANT(Attributes, Name)                                                   \
  template<bool Line1, bool Line2>                                                                 \
  Attributes void Name(const FlatWire& wire, double radius, Block& b, int n)                       \
  {                                                                                                \
    ProjectBlockBody<Line1, Line2>(wire, radius, b, n);                                            \
  }
BENDER_PROJECT_VARIANT(, ProjectBaseline)
#ifdef BENDER_SIMD_DISPATCH
BENDER_PROJECT_VARIANT(BENDER_TARGET_AVX2, ProjectAvx2)
BENDER_PROJECT_VARIANT(BENDER_TARGET_AVX512, ProjectAvx512)
#endif
#undef BENDER_PROJECT_VARIANT

template<bool Line1, bool Line2>
ProjectBlockFunction ProjectFunctionOf(SimdLevel level)
{
#ifdef BENDER_SIMD_DISPATCH
  switch (level)
  {
    case SimdLevel::Avx512:
      return ProjectAvx512<Line1, Line2>;
    case SimdLevel::Avx2:
      return ProjectAvx2<Line1, Line2>;
    case SimdLevel::Baseline:
      break;
  }
#else
  (void)level;
#endif
  return ProjectBaseline<Line1, Line2>;
}

ProjectBlockFunction ProjectFunctionOf(SimdLevel level, bool line1, bool line2)
{
  if (line1)
  {
    return line2 ? ProjectFunctionOf<true, true>(level) : ProjectFunctionOf<true, false>(level);
  }
  return line2 ? ProjectFunctionOf<false, true>(level) : ProjectFunctionOf<false, false>(level);
}
} // namespace

WireProjections ProjectOntoWire(const Biarc& wire, const Vec3& p, double radius)
{
  // The arcs' end points (sin and cos) are needed only when a foot's angle rounds outside its
  // arc: computed then, and the point projected again.
  FlatWire w;
  lane::FlattenWire(wire, w, false);
  Kept k;
  ProjectPoint(w, p, radius, k);
  if (k.clamped)
  {
    lane::FlattenWire(wire, w, true);
    ProjectPoint(w, p, radius, k);
  }
  return ToProjections(k);
}

void ProjectOntoWire(const Biarc& wire,
  const double* xyz,
  std::size_t n,
  double radius,
  WireProjections* out)
{
  ProjectOntoWire(wire, xyz, n, radius, out, FastWarpKernel::BestLevel());
}

bool ProjectOntoWire(const Biarc& wire,
  const double* xyz,
  std::size_t n,
  double radius,
  WireProjections* out,
  SimdLevel level)
{
  if (!FastWarpKernel::Supports(level))
  {
    return false;
  }
  FlatWire w;
  lane::FlattenWire(wire, w, true);
  const ProjectBlockFunction project = ProjectFunctionOf(level, w.arcs[0].line, w.arcs[1].line);
  Block b;
  for (std::size_t first = 0; first < n; first += BlockSize)
  {
    const int count = static_cast<int>(std::min<std::size_t>(BlockSize, n - first));
    for (int i = 0; i < count; ++i)
    {
      const double* p = xyz + 3 * (first + static_cast<std::size_t>(i));
      b.x[i] = p[0];
      b.y[i] = p[1];
      b.z[i] = p[2];
    }
    project(w, radius, b, count);
    for (int i = 0; i < count; ++i)
    {
      Kept k;
      k.s0 = b.s0[i];
      k.d0 = b.d0[i];
      k.q0x = b.q0x[i];
      k.q0y = b.q0y[i];
      k.q0z = b.q0z[i];
      k.s1 = b.s1[i];
      k.d1 = b.d1[i];
      k.q1x = b.q1x[i];
      k.q1y = b.q1y[i];
      k.q1z = b.q1z[i];
      out[first + static_cast<std::size_t>(i)] = ToProjections(k);
    }
  }
  return true;
}

} // namespace bender
