#ifndef bender_Vec3_h
#define bender_Vec3_h

#include <array>
#include <cmath>

namespace bender
{

/// A 3-vector of doubles. Frame and unit are those of the data it belongs to
/// (meshes from the segmentation are in LPS millimetres).
struct Vec3
{
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  constexpr Vec3() = default;
  constexpr Vec3(double ax, double ay, double az)
    : x(ax)
    , y(ay)
    , z(az)
  {
  }

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3 operator+(const Vec3& o) const { return { x + o.x, y + o.y, z + o.z }; }
  constexpr Vec3 operator-(const Vec3& o) const { return { x - o.x, y - o.y, z - o.z }; }
  constexpr Vec3 operator-() const { return { -x, -y, -z }; }
  constexpr Vec3 operator*(double s) const { return { x * s, y * s, z * s }; }
  constexpr Vec3 operator/(double s) const { return { x / s, y / s, z / s }; }
  Vec3& operator+=(const Vec3& o)
  {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  Vec3& operator-=(const Vec3& o)
  {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  Vec3& operator*=(double s)
  {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};

constexpr Vec3 operator*(double s, const Vec3& v)
{
  return v * s;
}
constexpr double Dot(const Vec3& a, const Vec3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline double Norm(const Vec3& a)
{
  return std::sqrt(Dot(a, a));
}
inline double Distance(const Vec3& a, const Vec3& b)
{
  return Norm(a - b);
}
/// a/|a|; the zero vector stays zero (callers that care test the norm first).
inline Vec3 Normalized(const Vec3& a)
{
  const double n = Norm(a);
  return n > 0.0 ? a / n : a;
}
inline bool IsFinite(const Vec3& a)
{
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

/// Rodrigues: rotate v about the unit axis k by the angle phi (radians, right-handed).
inline Vec3 Rotate(const Vec3& k, double phi, const Vec3& v)
{
  const double c = std::cos(phi);
  const double s = std::sin(phi);
  return v * c + Cross(k, v) * s + k * (Dot(k, v) * (1.0 - c));
}
/// Same, with cos and sin given.
inline Vec3 Rotate(const Vec3& k, double c, double s, const Vec3& v)
{
  return v * c + Cross(k, v) * s + k * (Dot(k, v) * (1.0 - c));
}

/// sang(u, v, k) = atan2((u x v).k, u.v): signed angle from u to v about k.
inline double SignedAngle(const Vec3& u, const Vec3& v, const Vec3& k)
{
  return std::atan2(Dot(Cross(u, v), k), Dot(u, v));
}

/// The same arithmetic on std::array<double, 3>, the storage of the VTK-facing code
/// (vtkPoints::GetPoint and vtkDataArray::GetTuple write into its data()), so that such code
/// carries no private copy of it. ToVec3 and ToArray convert between the two.
using Array3 = std::array<double, 3>;

inline Array3 Sub(const Array3& a, const Array3& b)
{
  return { { a[0] - b[0], a[1] - b[1], a[2] - b[2] } };
}
inline Array3 Add(const Array3& a, const Array3& b)
{
  return { { a[0] + b[0], a[1] + b[1], a[2] + b[2] } };
}
inline Array3 Scale(const Array3& a, double s)
{
  return { { a[0] * s, a[1] * s, a[2] * s } };
}
inline double Dot(const Array3& a, const Array3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Array3 Cross(const Array3& a, const Array3& b)
{
  return { { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] } };
}
inline double Norm(const Array3& a)
{
  return std::sqrt(Dot(a, a));
}
inline double Distance(const Array3& a, const Array3& b)
{
  return Norm(Sub(a, b));
}
/// a + t (b - a).
inline Array3 Lerp(const Array3& a, const Array3& b, double t)
{
  return { { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]) } };
}
/// a / |a|; the zero vector stays zero.
inline Array3 Normalized(const Array3& a)
{
  const double n = Norm(a);
  return n > 0.0 ? Array3{ { a[0] / n, a[1] / n, a[2] / n } } : Array3{ { 0.0, 0.0, 0.0 } };
}
inline Vec3 ToVec3(const Array3& a)
{
  return { a[0], a[1], a[2] };
}
inline Array3 ToArray(const Vec3& a)
{
  return { { a.x, a.y, a.z } };
}

} // namespace bender

#endif
