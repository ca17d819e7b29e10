#include "CommitGuard.h"

#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "RibbonWarp.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>
#include <utility>

namespace bender
{

namespace
{

struct Triangle
{
  vtkIdType cell; // id in the surface (vertices and lines first, then polygons)
  std::array<vtkIdType, 3> v;
};

// The polygons as triangles (fans for larger polygons), with their cell ids.
std::vector<Triangle> Triangles(vtkPolyData* mesh)
{
  std::vector<Triangle> tris;
  vtkIdType cell = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  vtkCellArray* polys = mesh->GetPolys();
  if (!polys)
  {
    return tris;
  }
  vtkNew<vtkIdList> ids;
  for (polys->InitTraversal(); polys->GetNextCell(ids); ++cell)
  {
    for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
    {
      tris.push_back({ cell, { ids->GetId(0), ids->GetId(k), ids->GetId(k + 1) } });
    }
  }
  return tris;
}

Vec3 PointOf(vtkPolyData* mesh, vtkIdType i)
{
  double p[3];
  mesh->GetPoint(i, p);
  return { p[0], p[1], p[2] };
}

// The triangles `which` of `tris` as a surface of their own, points taken from `mesh` and
// numbered in order of first use (the same numbering for the surfaces before and after).
vtkSmartPointer<vtkPolyData> SubSurface(vtkPolyData* mesh,
  const std::vector<Triangle>& tris,
  const std::vector<std::size_t>& which)
{
  std::unordered_map<vtkIdType, vtkIdType> local;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> cells;
  for (std::size_t t : which)
  {
    vtkIdType v[3];
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType g = tris[t].v[k];
      auto found = local.find(g);
      if (found == local.end())
      {
        found = local.emplace(g, points->InsertNextPoint(mesh->GetPoint(g))).first;
      }
      v[k] = found->second;
    }
    cells->InsertNextCell(3, v);
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetPolys(cells);
  return surface;
}

std::set<std::pair<vtkIdType, vtkIdType>> IntersectingCells(vtkPolyData* mesh,
  const std::vector<Triangle>& tris,
  const std::vector<std::size_t>& which)
{
  MeshCheckOptions options;
  options.selfIntersections = true;
  options.maxExamples = 1000000;
  const MeshCheckReport report = CheckMesh(SubSurface(mesh, tris, which), nullptr, options);
  std::set<std::pair<vtkIdType, vtkIdType>> pairs;
  for (const auto& [a, b] : report.intersectingPairs)
  {
    const vtkIdType ca = tris[which[static_cast<std::size_t>(a)]].cell;
    const vtkIdType cb = tris[which[static_cast<std::size_t>(b)]].cell;
    pairs.emplace(std::min(ca, cb), std::max(ca, cb));
  }
  return pairs;
}

std::string Plural(long long n, const char* one, const char* many)
{
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

} // namespace

std::string CommitCheck::Summary() const
{
  if (this->problems.empty())
  {
    return "no problems";
  }
  std::string text;
  for (const std::string& problem : this->problems)
  {
    text += (text.empty() ? "" : "; ") + problem;
  }
  return text;
}

CommitCheck CheckCommit(vtkPolyData* before,
  vtkPolyData* after,
  const WarpSpec& warp,
  const CommitCheckOptions& options,
  const CenterlineResult* lumenBefore)
{
  if (!before || !after || before->GetNumberOfPoints() != after->GetNumberOfPoints() ||
    before->GetNumberOfCells() != after->GetNumberOfCells())
  {
    throw InputError("commit check: the surfaces before and after the warp differ in points "
                     "or cells");
  }
  const RibbonWarp ribbonWarp(warp);
  CommitCheck check;
  check.checked = true;
  check.radius = warp.radius;
  check.minimumRadius =
    std::min(ribbonWarp.InitialMinimumRadius(), ribbonWarp.FinalMinimumRadius());
  check.spaceInversionRisk = ribbonWarp.SpaceInversionRisk();

  const std::vector<Triangle> tris = Triangles(before);
  const vtkIdType np = before->GetNumberOfPoints();
  std::vector<std::uint8_t> moved(static_cast<std::size_t>(np), 0);
  for (vtkIdType i = 0; i < np; ++i)
  {
    const Vec3 a = PointOf(before, i);
    const Vec3 b = PointOf(after, i);
    if (!(a.x == b.x && a.y == b.y && a.z == b.z))
    {
      moved[i] = 1;
      ++check.movedPoints;
    }
  }
  std::vector<std::size_t> region;
  std::vector<std::uint8_t> touched(static_cast<std::size_t>(np), 0);
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    const auto& v = tris[t].v;
    if (moved[v[0]] || moved[v[1]] || moved[v[2]])
    {
      region.push_back(t);
      touched[v[0]] = touched[v[1]] = touched[v[2]] = 1;
    }
  }
  check.regionTriangles = static_cast<long long>(region.size());

  std::set<vtkIdType> problemCells;
  if (!region.empty())
  {
    // Flips, as the export check counts them, on the region and the ring around it (the fold
    // test compares neighbours across edges).
    std::vector<std::size_t> ring;
    for (std::size_t t = 0; t < tris.size(); ++t)
    {
      const auto& v = tris[t].v;
      if (touched[v[0]] || touched[v[1]] || touched[v[2]])
      {
        ring.push_back(t);
      }
    }
    MeshCheckOptions flipOptions;
    flipOptions.selfIntersections = false;
    check.flippedTriangles =
      CheckMesh(SubSurface(after, tris, ring), SubSurface(before, tris, ring), flipOptions)
        .flippedTriangles;

    if (check.flippedTriangles > 0)
    {
      // Where: the triangles on a fold, whose neighbour across an edge faced about the same
      // way before the warp (within 60 degrees) and about the opposite way after it (more than
      // 120 degrees apart): a warp that inverts space folds the surface along the border of
      // the inverted region.
      std::map<std::pair<vtkIdType, vtkIdType>, std::vector<std::size_t>> edges;
      for (std::size_t t : ring)
      {
        for (int k = 0; k < 3; ++k)
        {
          const vtkIdType a = tris[t].v[k], b = tris[t].v[(k + 1) % 3];
          edges[{ std::min(a, b), std::max(a, b) }].push_back(t);
        }
      }
      const auto normal = [&](vtkPolyData* mesh, std::size_t t)
      {
        const Vec3 a = PointOf(mesh, tris[t].v[0]);
        return Cross(PointOf(mesh, tris[t].v[1]) - a, PointOf(mesh, tris[t].v[2]) - a);
      };
      for (const auto& [edge, users] : edges)
      {
        if (users.size() != 2)
        {
          continue;
        }
        const Vec3 bt = normal(before, users[0]), bu = normal(before, users[1]);
        const Vec3 at = normal(after, users[0]), au = normal(after, users[1]);
        const double nb = Norm(bt) * Norm(bu), na = Norm(at) * Norm(au);
        if (nb > 0.0 && na > 0.0 && Dot(bt, bu) > 0.5 * nb && Dot(at, au) < -0.5 * na)
        {
          problemCells.insert(tris[users[0]].cell);
          problemCells.insert(tris[users[1]].cell);
        }
      }
    }

    if (options.selfIntersections)
    {
      // New intersections involve a moved triangle; the other one lies near the region.
      double box[6] = { HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL };
      for (std::size_t t : region)
      {
        for (vtkIdType i : tris[t].v)
        {
          const Vec3 p = PointOf(after, i);
          for (int a = 0; a < 3; ++a)
          {
            box[2 * a] = std::min(box[2 * a], p[a]);
            box[2 * a + 1] = std::max(box[2 * a + 1], p[a]);
          }
        }
      }
      std::vector<std::size_t> near;
      for (std::size_t t = 0; t < tris.size(); ++t)
      {
        bool overlap = true;
        for (int a = 0; a < 3 && overlap; ++a)
        {
          double lo = HUGE_VAL, hi = -HUGE_VAL;
          for (vtkIdType i : tris[t].v)
          {
            const double x = after->GetPoint(i)[a];
            lo = std::min(lo, x);
            hi = std::max(hi, x);
          }
          overlap = lo <= box[2 * a + 1] && hi >= box[2 * a];
        }
        if (overlap)
        {
          near.push_back(t);
        }
      }
      const auto afterPairs = IntersectingCells(after, tris, near);
      const auto beforePairs = IntersectingCells(before, tris, near);
      for (const auto& pair : afterPairs)
      {
        if (!beforePairs.count(pair))
        {
          ++check.newSelfIntersections;
          problemCells.insert(pair.first);
          problemCells.insert(pair.second);
        }
      }
    }
    if (check.flippedTriangles > 0)
    {
      check.problems.push_back(
        Plural(check.flippedTriangles, "flipped triangle", "flipped triangles") +
        " (turned inside out by the warp)");
    }
    if (check.newSelfIntersections > 0)
    {
      check.problems.push_back(
        Plural(check.newSelfIntersections, "new self-intersection", "new self-intersections") +
        " (the surface crosses itself)");
    }
  }
  if (options.spaceInversionRule && check.spaceInversionRisk)
  {
    std::ostringstream text;
    text.precision(3);
    text << "space inversion possible: R = " << check.radius
         << " mm is not smaller than r_min = " << check.minimumRadius
         << " mm, the ribbon's smallest arc radius";
    check.problems.push_back(text.str());
  }
  if (options.lumen.enabled && check.movedPoints > 0)
  {
    check.lumen = CheckLumen(before, after, options.lumen, lumenBefore);
    check.problems.insert(
      check.problems.end(), check.lumen.problems.begin(), check.lumen.problems.end());
  }

  check.problemCells.assign(problemCells.begin(), problemCells.end());
  if (!check.problemCells.empty())
  {
    std::vector<std::size_t> shown;
    for (std::size_t t = 0; t < tris.size(); ++t)
    {
      if (problemCells.count(tris[t].cell))
      {
        shown.push_back(t);
      }
    }
    check.problemTriangles = SubSurface(after, tris, shown);
  }
  return check;
}

} // namespace bender
