#ifndef bender_Quaternion_h
#define bender_Quaternion_h

#include "Frame.h"
#include "Vec3.h"

#include <cmath>

namespace bender
{

/// A quaternion w + (x, y, z); unit quaternions represent rotations.
struct Quaternion
{
  double w = 1.0;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  Vec3 Vector() const { return { x, y, z }; }
  Quaternion operator-() const { return { -w, -x, -y, -z }; }
};

inline Quaternion operator*(const Quaternion& a, const Quaternion& b)
{
  return { a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
    a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
    a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
    a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w };
}
inline Quaternion Conjugate(const Quaternion& q)
{
  return { q.w, -q.x, -q.y, -q.z };
}
inline double Dot4(const Quaternion& a, const Quaternion& b)
{
  return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}
/// Rotate v by the unit quaternion q.
inline Vec3 RotateByQuaternion(const Quaternion& q, const Vec3& v)
{
  // v' = v + 2w (u x v) + 2 u x (u x v), u = q.vec
  const Vec3 u = q.Vector();
  const Vec3 t = Cross(u, v) * 2.0;
  return v + t * q.w + Cross(u, t);
}

/// Unit quaternion of the rotation matrix whose columns are c0, c1, c2 (Shepperd's method,
/// which picks the largest diagonal term, so it is accurate for every rotation).
inline Quaternion QuaternionFromColumns(const Vec3& c0, const Vec3& c1, const Vec3& c2)
{
  const double m00 = c0.x, m10 = c0.y, m20 = c0.z;
  const double m01 = c1.x, m11 = c1.y, m21 = c1.z;
  const double m02 = c2.x, m12 = c2.y, m22 = c2.z;
  const double tr = m00 + m11 + m22;
  Quaternion q;
  if (tr >= m00 && tr >= m11 && tr >= m22)
  {
    const double r = std::sqrt(1.0 + tr) * 2.0;
    q = { 0.25 * r, (m21 - m12) / r, (m02 - m20) / r, (m10 - m01) / r };
  }
  else if (m00 >= m11 && m00 >= m22)
  {
    const double r = std::sqrt(1.0 + m00 - m11 - m22) * 2.0;
    q = { (m21 - m12) / r, 0.25 * r, (m01 + m10) / r, (m02 + m20) / r };
  }
  else if (m11 >= m22)
  {
    const double r = std::sqrt(1.0 + m11 - m00 - m22) * 2.0;
    q = { (m02 - m20) / r, (m01 + m10) / r, 0.25 * r, (m12 + m21) / r };
  }
  else
  {
    const double r = std::sqrt(1.0 + m22 - m00 - m11) * 2.0;
    q = { (m10 - m01) / r, (m02 + m20) / r, (m12 + m21) / r, 0.25 * r };
  }
  const double n = std::sqrt(Dot4(q, q));
  return { q.w / n, q.x / n, q.y / n, q.z / n };
}

/// Orientation of a frame as a unit quaternion (maps the world axes to T, N, B).
inline Quaternion QuaternionOfFrame(const Frame& f)
{
  return QuaternionFromColumns(f.t, f.n, f.b);
}

} // namespace bender

#endif
