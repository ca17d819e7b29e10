#include "CfdWallEnds.h"

#include "BenderErrors.h"
#include "MeshTopology.h"
#include "StringUtil.h"
#include "Vec3.h"

#include <vtkCellType.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace bender
{

namespace
{
constexpr double kPi = 3.14159265358979323846;
/// Normals of one flat region agree within 1 degree.
const double kFlatCosine = std::cos(kPi / 180.0);
/// A cap's rim: the wall beside it turns by more than 60 degrees (|cos| < 0.5) on average and
/// along at least half of it (a coarse tube's flat facet turns sharply at its two short ends
/// only; a cap cut 45 degrees across its vessel still qualifies).
constexpr double kRimCosine = 0.5;
/// 4 pi area / perimeter^2: 1 for a disc, 0.79 for a square, 0.03 for a 1:40 strip.
constexpr double kMinimumRoundness = 0.5;

struct Triangle
{
  std::array<std::int64_t, 3> points{};
  Vec3 normal;
  double area = 0.0;
  Vec3 centre;
  bool wall = false;
};

/// The triangles of `surface` (polygons of three points; others are left out, so they stay in
/// no region), with their cells' wall flag.
std::vector<Triangle> WallTriangles(const LabelledSurface& surface)
{
  vtkPolyData* mesh = surface.surface;
  const std::vector<int> ids = CellPatchIds(mesh);
  int wallId = kWallEntityId;
  for (const PatchLabel& p : surface.patches)
  {
    wallId = p.type == PatchType::Wall ? p.id : wallId;
  }
  std::vector<Triangle> triangles;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, cell);
    if (cell->GetNumberOfIds() != 3 || mesh->GetCellType(c) != VTK_TRIANGLE)
    {
      continue;
    }
    Triangle t;
    Vec3 p[3];
    for (int k = 0; k < 3; ++k)
    {
      t.points[k] = cell->GetId(k);
      double x[3];
      mesh->GetPoint(cell->GetId(k), x);
      p[k] = { x[0], x[1], x[2] };
    }
    const Vec3 n = Cross(p[1] - p[0], p[2] - p[0]);
    const double twice = Norm(n);
    t.area = 0.5 * twice;
    t.normal = twice > 0.0 ? n / twice : Vec3{};
    t.centre = (p[0] + p[1] + p[2]) / 3.0;
    t.wall = static_cast<std::size_t>(c) < ids.size() && ids[c] == wallId;
    triangles.push_back(t);
  }
  return triangles;
}
} // namespace

std::vector<CfdWallEnd> FindWallEnds(const LabelledSurface& surface, double minDiameter)
{
  std::vector<CfdWallEnd> found;
  if (!surface.surface || surface.surface->GetNumberOfCells() == 0)
  {
    return found;
  }
  const std::vector<Triangle> triangles = WallTriangles(surface);
  std::vector<std::int64_t> flat;
  flat.reserve(3 * triangles.size());
  for (const Triangle& t : triangles)
  {
    flat.insert(flat.end(), t.points.begin(), t.points.end());
  }
  const TriangleEdges edges(flat, surface.surface->GetNumberOfPoints());
  // Each triangle's edges, for the walk from triangle to triangle.
  std::vector<std::vector<std::size_t>> edgesOf(triangles.size());
  for (std::size_t e = 0; e < edges.Edges().size(); ++e)
  {
    const MeshEdge& edge = edges.Edges()[e];
    for (std::size_t u = 0; u < edge.uses; ++u)
    {
      edgesOf[edges.Uses()[edge.first + u].triangle].push_back(e);
    }
  }
  double bounds[6];
  surface.surface->GetBounds(bounds);
  const double tolerance = 1e-5 *
    std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));

  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> regionOf(triangles.size(), kNone); // the seed of its region
  std::vector<std::size_t> region, stack;
  for (std::size_t seed = 0; seed < triangles.size(); ++seed)
  {
    if (regionOf[seed] != kNone || !triangles[seed].wall || triangles[seed].area <= 0.0)
    {
      continue;
    }
    // The flat region of the seed: wall triangles reached edge to edge in the seed's plane.
    const Vec3 n0 = triangles[seed].normal;
    const double d0 = Dot(n0, triangles[seed].centre);
    const auto inPlane = [&](const Triangle& t)
    {
      if (!t.wall || Dot(t.normal, n0) < kFlatCosine)
      {
        return false;
      }
      double x[3];
      for (const std::int64_t p : t.points)
      {
        surface.surface->GetPoint(p, x);
        if (std::abs(Dot(n0, Vec3{ x[0], x[1], x[2] }) - d0) > tolerance)
        {
          return false;
        }
      }
      return true;
    };
    region.clear();
    stack.assign(1, seed);
    regionOf[seed] = seed;
    while (!stack.empty())
    {
      const std::size_t t = stack.back();
      stack.pop_back();
      region.push_back(t);
      for (const std::size_t e : edgesOf[t])
      {
        const MeshEdge& edge = edges.Edges()[e];
        for (std::size_t u = 0; u < edge.uses; ++u)
        {
          const auto other = static_cast<std::size_t>(edges.Uses()[edge.first + u].triangle);
          if (regionOf[other] == kNone && inPlane(triangles[other]))
          {
            regionOf[other] = seed;
            stack.push_back(other);
          }
        }
      }
    }
    if (region.size() < 3)
    {
      continue;
    }
    // Its area, centre, perimeter and how sharply the wall turns at its rim.
    double area = 0.0, perimeter = 0.0, rimTurn = 0.0, sharpRim = 0.0;
    Vec3 centre;
    for (const std::size_t t : region)
    {
      area += triangles[t].area;
      centre += triangles[t].centre * triangles[t].area;
    }
    for (const std::size_t t : region)
    {
      for (const std::size_t e : edgesOf[t])
      {
        const MeshEdge& edge = edges.Edges()[e];
        double cosine = 0.0; // an open edge: no wall beyond, as sharp as a rim gets
        bool inside = false;
        for (std::size_t u = 0; u < edge.uses; ++u)
        {
          const auto other = static_cast<std::size_t>(edges.Uses()[edge.first + u].triangle);
          if (other == t)
          {
            continue;
          }
          if (regionOf[other] == seed)
          {
            inside = true;
            break;
          }
          cosine = std::max(cosine, std::abs(Dot(triangles[other].normal, n0)));
        }
        if (!inside)
        {
          double a[3], b[3];
          surface.surface->GetPoint(edge.lo, a);
          surface.surface->GetPoint(edge.hi, b);
          const double length = Distance(Vec3{ a[0], a[1], a[2] }, Vec3{ b[0], b[1], b[2] });
          perimeter += length;
          rimTurn += cosine * length;
          sharpRim += cosine < kRimCosine ? length : 0.0;
        }
      }
    }
    const double diameter = 2.0 * std::sqrt(area / kPi);
    if (perimeter <= 0.0 || diameter < minDiameter ||
      4.0 * kPi * area / (perimeter * perimeter) < kMinimumRoundness ||
      rimTurn / perimeter >= kRimCosine || sharpRim < 0.5 * perimeter)
    {
      continue;
    }
    centre = centre / area;
    found.push_back({ { centre.x, centre.y, centre.z },
      { n0.x, n0.y, n0.z },
      diameter,
      static_cast<long long>(region.size()) });
  }
  std::sort(found.begin(),
    found.end(),
    [](const CfdWallEnd& a, const CfdWallEnd& b) { return a.diameter > b.diameter; });
  return found;
}

void CheckNoWallEnd(const LabelledSurface& surface, double smallestEnd, const std::string& name)
{
  const std::vector<CfdWallEnd> ends = FindWallEnds(surface, 0.5 * smallestEnd);
  if (ends.empty())
  {
    return;
  }
  const CfdWallEnd& end = ends.front();
  throw InputError(name + ": the end at " + FormatPoint(end.centre) + " mm (" +
    FormatNumber(end.diameter) +
    " mm wide) is labelled wall: the case would close that vessel (label every end inlet or "
    "outlet: bender-cli clip, or Prepare for CFD)" +
    (ends.size() > 1 ? " (" + std::to_string(ends.size() - 1) + " more such end(s))" : ""));
}

} // namespace bender
