#include "VesselCenterlines.h"

#include "CenterlinePasses.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace bender
{
namespace
{
using centerline::UnitVector;

// Least-squares cubic fit of the samples around i, parameter = abscissa - s_i; returns the
// first three derivatives.
void CubicDerivatives(const std::vector<Point3>& p,
  const std::vector<double>& s,
  std::size_t i,
  double window,
  Point3& d1,
  Point3& d2,
  Point3& d3)
{
  const std::size_t n = p.size();
  std::size_t lo = i, hi = i;
  while (lo > 0 && (s[i] - s[lo - 1] <= window || i - lo < 3))
  {
    --lo;
  }
  while (hi + 1 < n && (s[hi + 1] - s[i] <= window || hi - i < 3))
  {
    ++hi;
  }
  // Keep the fit well-posed near the ends: at least 7 samples when the line has them.
  while (hi - lo < 6 && (lo > 0 || hi + 1 < n))
  {
    if (lo > 0)
    {
      --lo;
    }
    if (hi - lo < 6 && hi + 1 < n)
    {
      ++hi;
    }
  }
  const int order = (hi - lo >= 4) ? 3 : static_cast<int>(hi - lo) - 1;
  const int m = order + 1;
  double ata[4][4] = {};
  double atb[4][3] = {};
  const double scale = std::max(window, 1e-12);
  for (std::size_t k = lo; k <= hi; ++k)
  {
    const double u = (s[k] - s[i]) / scale;
    double pw[4] = { 1, u, u * u, u * u * u };
    for (int a = 0; a < m; ++a)
    {
      for (int b = 0; b < m; ++b)
      {
        ata[a][b] += pw[a] * pw[b];
      }
      for (int c = 0; c < 3; ++c)
      {
        atb[a][c] += pw[a] * p[k][c];
      }
    }
  }
  // Solve the (m x m) normal equations by Gaussian elimination with partial pivoting.
  double coef[4][3] = {};
  double A[4][7] = {};
  for (int a = 0; a < m; ++a)
  {
    for (int b = 0; b < m; ++b)
    {
      A[a][b] = ata[a][b];
    }
    for (int c = 0; c < 3; ++c)
    {
      A[a][m + c] = atb[a][c];
    }
  }
  for (int col = 0; col < m; ++col)
  {
    int pivot = col;
    for (int r = col + 1; r < m; ++r)
    {
      if (std::abs(A[r][col]) > std::abs(A[pivot][col]))
      {
        pivot = r;
      }
    }
    for (int c = 0; c < m + 3; ++c)
    {
      std::swap(A[col][c], A[pivot][c]);
    }
    if (std::abs(A[col][col]) < 1e-300)
    {
      continue;
    }
    for (int r = 0; r < m; ++r)
    {
      if (r == col)
      {
        continue;
      }
      const double f = A[r][col] / A[col][col];
      for (int c = col; c < m + 3; ++c)
      {
        A[r][c] -= f * A[col][c];
      }
    }
  }
  for (int a = 0; a < m; ++a)
  {
    for (int c = 0; c < 3; ++c)
    {
      coef[a][c] = std::abs(A[a][a]) > 1e-300 ? A[a][m + c] / A[a][a] : 0.0;
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    d1[c] = coef[1][c] / scale;
    d2[c] = 2.0 * coef[2][c] / (scale * scale);
    d3[c] = 6.0 * coef[3][c] / (scale * scale * scale);
  }
}

} // namespace

std::vector<CurveSample> ComputeCurveFrames(const std::vector<Point3>& points,
  double window,
  double startAbscissa)
{
  std::vector<CurveSample> out(points.size());
  if (points.empty())
  {
    return out;
  }
  std::vector<double> s(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i)
  {
    s[i] = s[i - 1] + Distance(points[i - 1], points[i]);
  }
  Point3 previousNormal{ { 0, 0, 0 } };
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    CurveSample& c = out[i];
    c.position = points[i];
    c.abscissa = startAbscissa + s[i];
    if (points.size() < 2)
    {
      continue;
    }
    Point3 d1, d2, d3;
    CubicDerivatives(points, s, i, window, d1, d2, d3);
    const double speed = Norm(d1);
    if (speed <= 0)
    {
      continue;
    }
    c.tangent = Scale(d1, 1.0 / speed);
    const Point3 b = Cross(d1, d2);
    const double bn = Norm(b);
    c.curvature = bn / (speed * speed * speed);
    c.torsion = bn > 0 ? Dot(b, d3) / (bn * bn) : 0.0;
    Point3 n = Sub(d2, Scale(c.tangent, Dot(d2, c.tangent)));
    // Where the line is (nearly) straight the Frenet normal is undefined: carry the previous
    // normal along (projected), or pick any perpendicular at the start.
    if (Norm(n) < 1e-6 * (Norm(d2) + 1e-12) || c.curvature * window < 1e-6)
    {
      n = Sub(previousNormal, Scale(c.tangent, Dot(previousNormal, c.tangent)));
      if (Norm(n) < 1e-6)
      {
        const Point3 axis =
          std::abs(c.tangent[0]) < 0.9 ? Point3{ { 1, 0, 0 } } : Point3{ { 0, 1, 0 } };
        n = Cross(c.tangent, Cross(axis, c.tangent));
      }
    }
    c.normal = UnitVector(n);
    previousNormal = c.normal;
  }
  return out;
}

} // namespace bender
