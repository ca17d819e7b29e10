#include "Screw.h"

#include <cmath>

namespace bender
{

DualQuaternion MotionBetween(const Frame& c, const Frame& cp, const Quaternion& q)
{
  // t = O' - R O; dual = 1/2 (0, t) q.
  const Vec3 t = cp.origin - RotateByQuaternion(q, c.origin);
  DualQuaternion m;
  m.real = q;
  m.dual = Quaternion{ 0.0, 0.5 * t.x, 0.5 * t.y, 0.5 * t.z } * q;
  return m;
}

namespace
{
// Decomposition of a unit dual quaternion into (half angle, axis, pitch translation,
// perpendicular part of the dual vector). With w = cos(h), v = sin(h) K,
// dual = (-(d/2) sin h, (d/2) cos h K + sin h M):
//   d = 2 (cos h (dv.K) - dw sin h), and the part of dv perpendicular to K is sin h M.
struct ScrewParts
{
  double h = 0.0;  // half angle, [0, pi]
  double sh = 0.0; // sin h = |v|
  Vec3 k;
  double d = 0.0;
  Vec3 perp; // sin(h) M
  bool translation = false;
  Vec3 t; // translation when pure
};

// Below this |v| the rotation is rounding noise: report a pure translation (spec 4.1 eps_rot).
constexpr double EpsRot = 1e-12;

ScrewParts Decompose(const DualQuaternion& m)
{
  ScrewParts p;
  const Vec3 v = m.real.Vector();
  const double sv = Norm(v);
  const Vec3 dv = m.dual.Vector();
  if (sv == 0.0)
  {
    // Pure translation: real = +-1, t = 2 dual real*.
    p.translation = true;
    const Quaternion tq = m.dual * Conjugate(m.real);
    p.t = tq.Vector() * 2.0;
    p.h = m.real.w >= 0.0 ? 0.0 : 3.14159265358979323846;
    return p;
  }
  p.sh = sv;
  p.h = std::atan2(sv, m.real.w);
  p.k = v / sv;
  const double ch = m.real.w;
  p.d = 2.0 * (ch * Dot(dv, p.k) - m.dual.w * sv);
  p.perp = dv - p.k * (0.5 * p.d * ch);
  return p;
}
} // namespace

Screw ScrewOf(const DualQuaternion& m)
{
  const ScrewParts p = Decompose(m);
  Screw s;
  s.flipped = m.real.w < 0.0;
  if (p.translation || (p.sh < EpsRot && m.real.w > 0.0))
  {
    const Vec3 t = (m.dual * Conjugate(m.real)).Vector() * 2.0;
    const double n = Norm(t);
    s.k = n > 0.0 ? t / n : Vec3{ 1, 0, 0 };
    s.d = n;
    s.beta = p.translation ? 2.0 * p.h : 0.0;
    s.a = Vec3{};
    return s;
  }
  s.k = p.k;
  s.beta = 2.0 * p.h;
  s.d = p.d;
  // perp = sin(h) M with M = A x K the moment of the axis line; A = K x M is the axis point
  // closest to the origin.
  s.a = Cross(p.k, p.perp / p.sh);
  return s;
}

Vec3 ApplyMotion(const DualQuaternion& m, const Vec3& p)
{
  const Quaternion tq = m.dual * Conjugate(m.real);
  return RotateByQuaternion(m.real, p) + tq.Vector() * 2.0;
}

Vec3 ApplyScrewFraction(const DualQuaternion& m, const Vec3& p, double f)
{
  if (f == 0.0)
  {
    return p;
  }
  const ScrewParts s = Decompose(m);
  if (s.translation)
  {
    if (m.real.w >= 0.0)
    {
      return p + s.t * f;
    }
    // -1 real part: a full turn; its fraction rotates about an undefined axis. Excluded by the
    // 340 degree rule; keep the point finite.
    return p + s.t * f;
  }
  const double hf = s.h * f;
  const double cf = std::cos(hf);
  const double sf = std::sin(hf);
  // m^f: real (cos hf, sin hf K), dual (-(f d/2) sin hf, (f d/2) cos hf K + sin hf M).
  const double ratio = sf / s.sh;
  Quaternion r{ cf, sf * s.k.x, sf * s.k.y, sf * s.k.z };
  const Vec3 dvec = s.k * (0.5 * f * s.d * cf) + s.perp * ratio;
  Quaternion du{ -0.5 * f * s.d * sf, dvec.x, dvec.y, dvec.z };
  const Quaternion tq = du * Conjugate(r);
  return RotateByQuaternion(r, p) + tq.Vector() * 2.0;
}

} // namespace bender
