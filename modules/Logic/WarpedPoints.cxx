#include "WarpedPoints.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "StringUtil.h"
#include "SweepCandidates.h"

#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace bender
{

namespace
{
/// `points` moved through warps[0..count), each warp exact and without subdivision.
std::vector<Vec3> Warped(const std::vector<Vec3>& points,
  const std::vector<WarpSpec>& warps,
  std::size_t count)
{
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  for (const Vec3& p : points)
  {
    xyz->InsertNextPoint(p.x, p.y, p.z);
  }
  cloud->SetPoints(xyz);
  for (std::size_t w = 0; w < std::min(count, warps.size()); ++w)
  {
    WarpSpec single = warps[w];
    single.subdivision.reset();
    cloud = ApplyWarp(cloud, single);
  }
  std::vector<Vec3> moved(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    double p[3];
    cloud->GetPoint(static_cast<vtkIdType>(i), p);
    moved[i] = { p[0], p[1], p[2] };
  }
  return moved;
}

double Determinant(const std::array<Vec3, 3>& c)
{
  return Dot(c[0], Cross(c[1], c[2]));
}

/// The solution d of J d = r, J's columns c (Cramer's rule); false when J is singular.
bool Solve(const std::array<Vec3, 3>& c, const Vec3& r, Vec3& d)
{
  const double det = Determinant(c);
  const double scale = Norm(c[0]) * Norm(c[1]) * Norm(c[2]);
  if (!(std::abs(det) > 1e-9 * scale))
  {
    return false;
  }
  d.x = Determinant({ r, c[1], c[2] }) / det;
  d.y = Determinant({ c[0], r, c[2] }) / det;
  d.z = Determinant({ c[0], c[1], r }) / det;
  return true;
}

constexpr double kStep = 1e-4;      ///< mm, the central differences' half width
constexpr double kTolerance = 1e-7; ///< mm, |W(q) - p| at the answer
constexpr int kIterations = 40;     ///< Newton steps per homotopy step
constexpr int kHomotopy = 8;        ///< fractions of each warp's motion

/// The points q with W(q) = p, `warp` alone, by Newton's method from `q` (its Jacobian by
/// central differences; a step that does not reduce the residual is halved). Throws InputError
/// naming a point with no answer near it (the warp folds the space there).
std::vector<Vec3> Inverted(const WarpSpec& warp, const std::vector<Vec3>& p, std::vector<Vec3> q)
{
  const std::vector<WarpSpec> one = { warp };
  const Vec3 axes[3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  std::vector<double> error(p.size(), std::numeric_limits<double>::infinity());
  std::vector<Vec3> step(p.size());
  std::vector<bool> found(p.size(), false);
  for (int iteration = 0; iteration < kIterations; ++iteration)
  {
    // Each point not yet found, with its six probes: q, q + h e_k, q - h e_k.
    std::vector<Vec3> probes;
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < q.size(); ++i)
    {
      if (found[i])
      {
        continue;
      }
      which.push_back(i);
      probes.push_back(q[i]);
      for (const Vec3& e : axes)
      {
        probes.push_back(q[i] + e * kStep);
        probes.push_back(q[i] - e * kStep);
      }
    }
    if (which.empty())
    {
      break;
    }
    const std::vector<Vec3> moved = Warped(probes, one, 1);
    for (std::size_t k = 0; k < which.size(); ++k)
    {
      const std::size_t i = which[k];
      const Vec3* w = &moved[7 * k];
      const Vec3 residual = p[i] - w[0];
      const double norm = Norm(residual);
      if (norm <= kTolerance)
      {
        found[i] = true;
        continue;
      }
      if (norm >= error[i] && iteration > 0)
      {
        // The last step overshot: go back half of it.
        step[i] = step[i] * 0.5;
        q[i] = q[i] - step[i];
        continue;
      }
      error[i] = norm;
      const std::array<Vec3, 3> jacobian = {
        (w[1] - w[2]) / (2 * kStep), (w[3] - w[4]) / (2 * kStep), (w[5] - w[6]) / (2 * kStep)
      };
      Vec3 d;
      if (!Solve(jacobian, residual, d) || !IsFinite(d))
      {
        break; // singular: reported below
      }
      step[i] = d;
      q[i] = q[i] + d;
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    if (!found[i])
    {
      throw InputError("the point " + FormatPoint({ p[i].x, p[i].y, p[i].z }) +
        " cannot be carried back through the plan's warps (the warps fold the space there)");
    }
  }
  return q;
}
} // namespace

std::vector<Vec3*> CfdStepPoints(CfdStep& step)
{
  std::vector<Vec3*> points;
  for (CfdStepEnd& end : step.ends)
  {
    points.push_back(&end.position);
  }
  for (CfdStepName& name : step.names)
  {
    points.push_back(&name.position);
  }
  for (CfdStepFactor& factor : step.extensionFactors)
  {
    points.push_back(&factor.position);
  }
  return points;
}

void CarryForward(const std::vector<Vec3*>& points,
  const std::vector<WarpSpec>& warps,
  std::size_t count)
{
  std::vector<Vec3> given;
  for (const Vec3* p : points)
  {
    given.push_back(*p);
  }
  const std::vector<Vec3> moved = Warped(given, warps, count);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    *points[i] = moved[i];
  }
}

void CarryBack(const std::vector<Vec3*>& points,
  const std::vector<WarpSpec>& warps,
  std::size_t count)
{
  std::vector<Vec3> p;
  for (const Vec3* given : points)
  {
    p.push_back(*given);
  }
  // The last warp first; each warp followed from no motion to its whole motion in kHomotopy
  // steps (WarpAtFraction), every step solved by Newton's method from the previous answer, so
  // that a large bend is never taken in one Newton leap.
  for (std::size_t w = std::min(count, warps.size()); w-- > 0;)
  {
    WarpSpec warp = warps[w];
    warp.subdivision.reset();
    std::vector<Vec3> q = p;
    for (int k = 1; k <= kHomotopy; ++k)
    {
      q = Inverted(WarpAtFraction(warp, static_cast<double>(k) / kHomotopy), p, q);
    }
    p = q;
  }
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    *points[i] = p[i];
  }
}

} // namespace bender
