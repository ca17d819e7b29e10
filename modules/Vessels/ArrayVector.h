#ifndef bender_ArrayVector_h
#define bender_ArrayVector_h

// Vector arithmetic on std::array<double, 3>, the point type of the vessel-end code (clipping,
// flow extensions), so that each file does not carry its own copy. Internal to bender_vessels.

#include <array>
#include <cmath>

namespace bender
{
namespace vessel_detail
{
using V3 = std::array<double, 3>;

inline V3 Sub(const V3& a, const V3& b)
{
  return { { a[0] - b[0], a[1] - b[1], a[2] - b[2] } };
}
inline double Dot(const V3& a, const V3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline V3 Cross(const V3& a, const V3& b)
{
  return { { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] } };
}
inline double Norm(const V3& a)
{
  return std::sqrt(Dot(a, a));
}
inline double Distance(const V3& a, const V3& b)
{
  return Norm(Sub(a, b));
}
inline V3 Lerp(const V3& a, const V3& b, double t)
{
  return { { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]) } };
}
/// a / |a|, or the zero vector for a zero a.
inline V3 Unit(const V3& a)
{
  const double n = Norm(a);
  return n > 0 ? V3{ { a[0] / n, a[1] / n, a[2] / n } } : V3{ { 0, 0, 0 } };
}
} // namespace vessel_detail
} // namespace bender

#endif
