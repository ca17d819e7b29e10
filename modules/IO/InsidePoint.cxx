#include "InsidePoint.h"

#include "PatchSidecar.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>

namespace bender
{

namespace
{
Vec3 Corner(const std::vector<std::array<double, 3>>& points, vtkIdType id)
{
  return ToVec3(points[static_cast<std::size_t>(id)]);
}
} // namespace

double WindingNumber(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<vtkIdType, 3>>& triangles,
  const double point[3])
{
  // Sum of the signed solid angles of the triangles seen from the point (Van Oosterom and
  // Strackee), over 4 pi.
  const Vec3 q{ point[0], point[1], point[2] };
  double total = 0.0;
  for (const auto& t : triangles)
  {
    const Vec3 a = Corner(points, t[0]) - q;
    const Vec3 b = Corner(points, t[1]) - q;
    const Vec3 c = Corner(points, t[2]) - q;
    const double la = Norm(a), lb = Norm(b), lc = Norm(c);
    const double numerator = Dot(a, Cross(b, c));
    const double denominator = la * lb * lc + Dot(a, b) * lc + Dot(a, c) * lb + Dot(b, c) * la;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

std::optional<LumenPoint> FindLumenPoint(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<vtkIdType, 3>>& triangles,
  const std::vector<InwardRay>& seeds,
  const std::vector<bool>& shoot)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    pts->SetPoint(static_cast<vtkIdType>(i), points[i].data());
  }
  vtkNew<vtkCellArray> polys;
  double volume6 = 0.0;
  for (const auto& t : triangles)
  {
    polys->InsertNextCell({ t[0], t[1], t[2] });
    volume6 += Dot(Corner(points, t[0]), Cross(Corner(points, t[1]), Corner(points, t[2])));
  }
  if (triangles.empty())
  {
    return std::nullopt;
  }
  // Outward triangles enclose a positive volume: their normals point out.
  const double orientation = volume6 < 0 ? -1.0 : 1.0;
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(pts);
  surface->SetPolys(polys);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(surface);
  locator->BuildLocator();
  double bounds[6];
  surface->GetBounds(bounds);
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  if (!(diagonal > 0))
  {
    return std::nullopt;
  }

  // The seeds, then triangles spread along the list against their normals.
  std::vector<InwardRay> rays = seeds;
  const std::size_t wanted = 48;
  const std::size_t stride = std::max<std::size_t>(1, triangles.size() / wanted);
  for (std::size_t t = 0; t < triangles.size(); t += stride)
  {
    if (!shoot.empty() && !shoot[t])
    {
      continue;
    }
    const Vec3 a = Corner(points, triangles[t][0]);
    const Vec3 b = Corner(points, triangles[t][1]);
    const Vec3 c = Corner(points, triangles[t][2]);
    const Vec3 n = Cross(b - a, c - a);
    const double len = Norm(n);
    if (!(len > 0))
    {
      continue;
    }
    const Vec3 centroid{ (a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3, (a.z + b.z + c.z) / 3 };
    rays.push_back({ centroid,
      { -orientation * n.x / len, -orientation * n.y / len, -orientation * n.z / len } });
  }

  std::optional<LumenPoint> best;
  double clearance = 0.0;
  for (const InwardRay& ray : rays)
  {
    const double eps = 1e-7 * diagonal;
    double p1[3], p2[3];
    for (int a = 0; a < 3; ++a)
    {
      p1[a] = ray.origin[a] + eps * ray.direction[a];
      p2[a] = ray.origin[a] + 2.0 * diagonal * ray.direction[a];
    }
    double t = 0, x[3], pcoords[3];
    int subId = 0;
    vtkIdType cell = -1;
    if (!locator->IntersectWithLine(p1, p2, 0.0, t, x, pcoords, subId, cell))
    {
      continue;
    }
    const double candidate[3] = { (p1[0] + x[0]) / 2, (p1[1] + x[1]) / 2, (p1[2] + x[2]) / 2 };
    double closest[3], dist2 = 0;
    vtkIdType closestCell = -1;
    locator->FindClosestPoint(candidate, closest, closestCell, subId, dist2);
    const double distance = std::sqrt(dist2);
    if (distance <= clearance)
    {
      continue;
    }
    if (std::abs(WindingNumber(points, triangles, candidate)) > 0.5)
    {
      best = LumenPoint{ { candidate[0], candidate[1], candidate[2] }, distance };
      clearance = distance;
    }
  }
  return best;
}

std::optional<LumenPoint> FindInsidePoint(const LabelledSurface& surface)
{
  const PatchSidecar measured = ComputePatchSidecar(surface, ExportTransform(StlFrame::LPS, "mm"));
  if (!measured.hasInsidePoint)
  {
    return std::nullopt;
  }
  return LumenPoint{ ToVec3(measured.insidePoint), measured.insideClearance };
}

} // namespace bender
