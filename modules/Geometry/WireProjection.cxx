#include "WireProjection.h"

#include <algorithm>
#include <cmath>

namespace bender
{
namespace
{
// Nearest point of an arc's circle (or segment) to p, the angle clamped to the arc.
// Returns false when p is on the circle's axis (every point equidistant).
bool NearestOnArc(const Arc& arc, const Vec3& p, double& u, Vec3& q)
{
  const Vec3 rel = p - arc.start;
  if (arc.line)
  {
    const double t = std::clamp(Dot(rel, arc.tangent), 0.0, arc.length);
    u = arc.length > 0.0 ? t / arc.length : 0.0;
    q = arc.start + arc.tangent * t;
    return true;
  }
  // phi = atan2(kappa (P - Ps).Ts, 1 - kappa (P - Ps).Np): the centre is never formed.
  const double aT = Dot(rel, arc.tangent);
  const double aN = Dot(rel, arc.toCentre);
  const double y = aT;
  const double x = arc.radius - aN;
  // |(x, y)|: the coordinates are within the wire's scale, so the plain square root is exact
  // enough and far cheaper than hypot.
  const double rho = std::sqrt(x * x + y * y);
  if (rho <= 1e-12 * arc.radius)
  {
    return false;
  }
  const double raw = std::atan2(y, x);
  const double phi = std::clamp(raw, 0.0, arc.angle);
  u = arc.angle > 0.0 ? phi / arc.angle : 0.0;
  if (phi != raw)
  {
    q = arc.PointAt(u); // clamped by rounding at an end of the arc
    return true;
  }
  // Q = Ps + r sin(phi) Ts + r (1 - cos(phi)) Np with cos and sin read off (x, y): no
  // trigonometry, and r (1 - cos) = r sin^2 / (1 + cos) keeps nearly straight arcs exact.
  const double c = x / rho;
  const double sn = y / rho;
  const double r = arc.radius;
  const double lift = c > 0.0 ? r * sn * sn / (1.0 + c) : r * (1.0 - c);
  q = arc.start + arc.tangent * (r * sn) + arc.toCentre * lift;
  return true;
}
} // namespace

WireProjections ProjectOntoWire(const Biarc& wire, const Vec3& p, double radius)
{
  // Candidates in the order arc 1, arc 2, start, end; the two nearest with distance < radius
  // kept in place, nearest first, ties by smaller s (a stable insertion: same result as
  // sorting all candidates), without candidate arrays to initialise and copy.
  WireProjections out;
  const auto offer = [&out, radius](double s, double distance, const Vec3& foot)
  {
    if (!(distance < radius))
    {
      return;
    }
    int i = out.count < 2 ? out.count++ : 2;
    while (i > 0 &&
      (distance < out.items[i - 1].distance ||
        (distance == out.items[i - 1].distance && s < out.items[i - 1].s)))
    {
      if (i < 2)
      {
        out.items[i] = out.items[i - 1];
      }
      --i;
    }
    if (i < 2)
    {
      out.items[i] = { s, distance, foot };
    }
  };
  const double sJ = wire.JunctionParameter();
  const double h0 = Dot(p - wire.Start(), wire.StartTangent());
  const double hJ = Dot(p - wire.Junction(), wire.JunctionTangent());
  const double h1 = Dot(p - wire.End(), wire.EndTangent());
  double u = 0.0;
  Vec3 q;
  if (h0 >= 0.0 && hJ < 0.0 && NearestOnArc(wire.FirstArc(), p, u, q))
  {
    offer(sJ * u, Distance(p, q), q);
  }
  if (hJ >= 0.0 && h1 <= 0.0 && NearestOnArc(wire.SecondArc(), p, u, q))
  {
    offer(sJ + (1.0 - sJ) * u, Distance(p, q), q);
  }
  if (h0 < 0.0)
  {
    offer(0.0, Distance(p, wire.Start()), wire.Start());
  }
  if (h1 > 0.0)
  {
    offer(1.0, Distance(p, wire.End()), wire.End());
  }
  return out;
}

} // namespace bender
