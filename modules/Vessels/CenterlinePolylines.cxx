#include "CenterlinePasses.h"

#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace bender
{
namespace centerline
{

double Length(const std::vector<Point3>& p)
{
  double l = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i)
  {
    l += Distance(p[i - 1], p[i]);
  }
  return l;
}

std::vector<Point3> Resample(const std::vector<Point3>& p, double h)
{
  std::vector<Point3> out;
  if (p.empty())
  {
    return out;
  }
  out.push_back(p.front());
  double next = h;
  double walked = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i)
  {
    const double l = Distance(p[i - 1], p[i]);
    while (l > 0 && next <= walked + l)
    {
      const double t = (next - walked) / l;
      out.push_back(Add(p[i - 1], Scale(Sub(p[i], p[i - 1]), t)));
      next += h;
    }
    walked += l;
  }
  if (Distance(out.back(), p.back()) > 1e-3 * h)
  {
    if (out.size() > 1 && Distance(out.back(), p.back()) < 0.25 * h)
    {
      out.back() = p.back();
    }
    else
    {
      out.push_back(p.back());
    }
  }
  return out;
}

void Smooth(std::vector<Point3>& p, double sigmaSamples)
{
  if (p.size() < 3 || sigmaSamples <= 0)
  {
    return;
  }
  const int iterations = static_cast<int>(std::ceil(2.0 * sigmaSamples * sigmaSamples));
  std::vector<Point3> q = p;
  for (int it = 0; it < iterations; ++it)
  {
    for (std::size_t i = 1; i + 1 < p.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        q[i][c] = 0.5 * p[i][c] + 0.25 * (p[i - 1][c] + p[i + 1][c]);
      }
    }
    std::swap(p, q);
    q.front() = p.front();
    q.back() = p.back();
  }
}

void SmoothingSpline(std::vector<Point3>& x,
  const std::vector<Point3>& targets,
  const std::vector<double>& weights,
  const SplineTerms& terms)
{
  const int order = terms.order;
  const double lambda = terms.lambda;
  constexpr int MaxBand = 3;
  constexpr int Width = 2 * MaxBand + 1;
  constexpr int Band = MaxBand; // storage offset; the matrix has `order` diagonals each side
  const std::size_t n = x.size();
  if (n < 4 || order < 2 || order > 3)
  {
    return;
  }
  // Band storage: A[i][k] for column i + k - Band.
  std::vector<std::array<double, Width>> A(n);
  for (auto& row : A)
  {
    row.fill(0.0);
  }
  std::vector<Point3> b(n, Point3{ { 0, 0, 0 } });
  for (std::size_t i = 0; i < n; ++i)
  {
    A[i][Band] += weights[i];
    b[i] = Scale(targets[i], weights[i]);
  }
  const double second[3] = { 1.0, -2.0, 1.0 };
  const double third[4] = { -1.0, 3.0, -3.0, 1.0 };
  const double* stencil = order == 2 ? second : third;
  const std::size_t taps = static_cast<std::size_t>(order) + 1;
  for (std::size_t j = 0; j + taps <= n; ++j)
  {
    for (std::size_t r = 0; r < taps; ++r)
    {
      for (std::size_t c = 0; c < taps; ++c)
      {
        A[j + r][Band + c - r] += lambda * stencil[r] * stencil[c];
      }
    }
  }
  auto fix = [&](std::size_t k)
  {
    const std::size_t lo = k >= Band ? k - Band : 0;
    const std::size_t hi = std::min(n - 1, k + Band);
    for (std::size_t i = lo; i <= hi; ++i)
    {
      if (i != k)
      {
        const double a = A[i][Band + k - i];
        b[i] = Sub(b[i], Scale(x[k], a));
        A[i][Band + k - i] = 0.0;
        A[k][Band + i - k] = 0.0;
      }
    }
    A[k][Band] = 1.0;
    b[k] = x[k];
  };
  if (terms.fixed.first)
  {
    fix(0);
  }
  if (terms.fixed.last)
  {
    fix(n - 1);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const double pivot = A[i][Band];
    if (!(std::abs(pivot) > 0))
    {
      return; // singular (no weight at all): leave x as it is
    }
    const std::size_t last = std::min(n - 1, i + Band);
    for (std::size_t r = i + 1; r <= last; ++r)
    {
      const double f = A[r][Band + i - r] / pivot;
      if (f == 0.0)
      {
        continue;
      }
      for (std::size_t c = i; c <= last; ++c)
      {
        A[r][Band + c - r] -= f * A[i][Band + c - i];
      }
      b[r] = Sub(b[r], Scale(b[i], f));
    }
  }
  std::vector<Point3> out(n);
  for (std::size_t i = n; i-- > 0;)
  {
    Point3 sum = b[i];
    for (std::size_t c = i + 1; c <= std::min(n - 1, i + Band); ++c)
    {
      sum = Sub(sum, Scale(out[c], A[i][Band + c - i]));
    }
    out[i] = Scale(sum, 1.0 / A[i][Band]);
  }
  for (const auto& p : out)
  {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      return;
    }
  }
  x = std::move(out);
}

} // namespace centerline
} // namespace bender
