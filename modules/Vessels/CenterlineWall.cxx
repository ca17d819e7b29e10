#include "CenterlinePasses.h"

#include "Vec3.h"

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>

namespace bender
{
namespace centerline
{
namespace
{

// Boundary loops from the edges used by one triangle only, walked in the direction in which
// their triangle uses them.
std::vector<BoundaryLoop> FindLoops(const Wall& wall, int& openChains)
{
  std::unordered_map<std::uint64_t, int> count;
  count.reserve(wall.triangles.size() * 3);
  for (const auto& t : wall.triangles)
  {
    for (int e = 0; e < 3; ++e)
    {
      ++count[EdgeKey(t[e], t[(e + 1) % 3])];
    }
  }
  std::unordered_multimap<vtkIdType, vtkIdType> next;
  for (const auto& t : wall.triangles)
  {
    for (int e = 0; e < 3; ++e)
    {
      const vtkIdType a = t[e], b = t[(e + 1) % 3];
      if (count[EdgeKey(a, b)] == 1)
      {
        next.emplace(a, b);
      }
    }
  }
  std::vector<BoundaryLoop> loops;
  openChains = 0;
  while (!next.empty())
  {
    auto it = next.begin();
    const vtkIdType start = it->first;
    BoundaryLoop loop;
    vtkIdType current = start;
    bool closed = false;
    while (true)
    {
      auto found = next.find(current);
      if (found == next.end())
      {
        break;
      }
      const vtkIdType to = found->second;
      next.erase(found);
      loop.ids.push_back(current);
      current = to;
      if (current == start)
      {
        closed = true;
        break;
      }
    }
    if (closed && loop.ids.size() >= 3)
    {
      loops.push_back(std::move(loop));
    }
    else
    {
      ++openChains;
    }
  }
  // Loop geometry: centre (edge-length weighted), mean radius, cap normal, planarity.
  for (auto& loop : loops)
  {
    const std::size_t n = loop.ids.size();
    Point3 c{ { 0, 0, 0 } };
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& a = wall.points[loop.ids[i]];
      const Point3& b = wall.points[loop.ids[(i + 1) % n]];
      const double l = Distance(a, b);
      c = Add(c, Scale(Add(a, b), 0.5 * l));
      total += l;
    }
    loop.centre = total > 0 ? Scale(c, 1.0 / total) : wall.points[loop.ids[0]];
    Point3 area{ { 0, 0, 0 } };
    double radius = 0.0, diameter = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& a = wall.points[loop.ids[i]];
      const Point3& b = wall.points[loop.ids[(i + 1) % n]];
      // The cap triangle (centre, b, a) uses the edge the other way round from the wall.
      area = Add(area, Cross(Sub(b, loop.centre), Sub(a, loop.centre)));
      radius += Distance(a, loop.centre);
      diameter = std::max(diameter, 2.0 * Distance(a, loop.centre));
    }
    loop.meanRadius = radius / static_cast<double>(n);
    loop.capNormal = UnitVector(area);
    double off = 0.0;
    for (vtkIdType id : loop.ids)
    {
      off = std::max(off, std::abs(Dot(Sub(wall.points[id], loop.centre), loop.capNormal)));
    }
    loop.isEnd = Norm(area) > 0 && off <= 0.1 * diameter;
  }
  return loops;
}

// ---- thinning the wall's points before the Delaunay -----------------------------------------
// The Voronoi diagram only has to find the paths through the lumen (the centerline is then
// re-centred on the wall itself, see CutSection), so it needs a fraction of the local radius
// between samples, not the mesh's resolution: a 55 k-triangle segmentation has ten times more
// points than that. Local radius from the surface's largest curvature (1 / r on a tube):
// per point, the largest angle between its normal and a neighbour's over their distance,
// averaged over its neighbours, and the spacing `factor` / curvature limited to grow by at most
// a quarter of the distance from where it is smaller (so that flat caps and ends keep samples).
// Points are then clustered on grids of cell sizes growing by 1.5 from the mean edge length, each
// point on the grid of its spacing, and the point nearest each cell's centre is kept. Returns
// the ids of the wall points to keep (all of them when factor is 0); boundary loop points are
// always kept.
// Spacing of the wall's points given to the Delaunay, as a fraction of the local radius (0: every
// point). The Voronoi diagram only has to find the paths and the ends: the centerline itself is
// placed on the centroids of the wall's cross-sections.
constexpr double DelaunaySpacing = 0.0;

std::vector<vtkIdType> ThinWall(const Wall& wall, double factor)
{
  const std::size_t n = wall.points.size();
  std::vector<vtkIdType> kept;
  std::vector<std::vector<vtkIdType>> neighbours(n);
  for (const auto& t : wall.triangles)
  {
    for (int e = 0; e < 3; ++e)
    {
      neighbours[t[e]].push_back(t[(e + 1) % 3]);
      neighbours[t[(e + 1) % 3]].push_back(t[e]);
    }
  }
  std::vector<bool> onBoundary(n, false);
  for (const auto& loop : wall.loops)
  {
    for (vtkIdType id : loop.ids)
    {
      onBoundary[id] = true;
    }
  }
  if (!(factor > 0))
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!neighbours[i].empty())
      {
        kept.push_back(static_cast<vtkIdType>(i));
      }
    }
    return kept;
  }
  std::vector<double> curvature(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (vtkIdType j : neighbours[i])
    {
      const double l = Distance(wall.points[i], wall.points[j]);
      const double c = std::clamp(Dot(wall.normals[i], wall.normals[j]), -1.0, 1.0);
      if (l > 0)
      {
        curvature[i] = std::max(curvature[i], std::acos(c) / l);
      }
    }
  }
  std::vector<double> spacing(n, std::numeric_limits<double>::infinity());
  const double largest = 0.05 * wall.diagonal;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (neighbours[i].empty())
    {
      continue;
    }
    double sum = curvature[i];
    for (vtkIdType j : neighbours[i])
    {
      sum += curvature[j];
    }
    const double k = sum / static_cast<double>(neighbours[i].size() + 1);
    spacing[i] = k > 0 ? std::min(largest, factor / k) : largest;
    spacing[i] = std::max(spacing[i], wall.meanEdge);
  }
  // Gradation: spacing[i] <= spacing[j] + 0.25 |ij| (Dijkstra from every point).
  {
    using Item = std::pair<double, vtkIdType>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (std::isfinite(spacing[i]))
      {
        queue.emplace(spacing[i], static_cast<vtkIdType>(i));
      }
    }
    while (!queue.empty())
    {
      const auto [h, i] = queue.top();
      queue.pop();
      if (h > spacing[i])
      {
        continue;
      }
      for (vtkIdType j : neighbours[i])
      {
        const double g = h + 0.25 * Distance(wall.points[i], wall.points[j]);
        if (g < spacing[j])
        {
          spacing[j] = g;
          queue.emplace(g, j);
        }
      }
    }
  }
  // Clustering, one grid per level of spacing.
  std::unordered_map<std::uint64_t, std::pair<vtkIdType, double>> cells;
  cells.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (neighbours[i].empty())
    {
      continue;
    }
    if (onBoundary[i] || spacing[i] < 1.5 * wall.meanEdge)
    {
      kept.push_back(static_cast<vtkIdType>(i));
      continue;
    }
    const int level = std::min(
      40, static_cast<int>(std::floor(std::log(spacing[i] / wall.meanEdge) / std::log(1.5))));
    const double size = wall.meanEdge * std::pow(1.5, level);
    std::uint64_t key = static_cast<std::uint64_t>(level);
    double offset = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      const double x = wall.points[i][c] / size;
      const double cell = std::floor(x);
      offset += (x - cell - 0.5) * (x - cell - 0.5);
      // 19 bits per axis (the wall's diagonal over the smallest cell is far below 2^18).
      key = (key << 19) |
        (static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) + (1 << 18)) &
          ((1u << 19) - 1));
    }
    auto it = cells.find(key);
    if (it == cells.end())
    {
      cells.emplace(key, std::make_pair(static_cast<vtkIdType>(i), offset));
    }
    else if (offset < it->second.second)
    {
      it->second = std::make_pair(static_cast<vtkIdType>(i), offset);
    }
  }
  for (const auto& cell : cells)
  {
    kept.push_back(cell.second.first);
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

} // namespace

bool BuildWall(vtkPolyData* surface,
  Wall& wall,
  std::vector<std::string>& warnings,
  std::string& failure)
{
  {
    vtkNew<vtkPolyData> polys;
    polys->SetPoints(surface->GetPoints());
    polys->SetPolys(surface->GetPolys());
    if (!surface->GetPoints() || surface->GetNumberOfPolys() == 0)
    {
      failure = "surface has no polygons: no lumen to find centerlines in";
      return false;
    }
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(polys);
    triangles->PassVertsOff();
    triangles->PassLinesOff();
    vtkNew<vtkCleanPolyData> clean;
    clean->SetInputConnection(triangles->GetOutputPort());
    clean->PointMergingOn();
    clean->SetTolerance(0.0);
    clean->ConvertLinesToPointsOff();
    clean->ConvertPolysToLinesOff();
    vtkNew<vtkPolyDataNormals> orient;
    orient->SetInputConnection(clean->GetOutputPort());
    orient->ConsistencyOn();
    orient->SplittingOff();
    orient->AutoOrientNormalsOff();
    orient->NonManifoldTraversalOn();
    orient->ComputePointNormalsOff();
    orient->ComputeCellNormalsOff();
    orient->Update();
    vtkPolyData* oriented = orient->GetOutput();
    const vtkIdType np = oriented->GetNumberOfPoints();
    wall.points.resize(np);
    for (vtkIdType i = 0; i < np; ++i)
    {
      oriented->GetPoint(i, wall.points[i].data());
      if (!std::isfinite(wall.points[i][0]) || !std::isfinite(wall.points[i][1]) ||
        !std::isfinite(wall.points[i][2]))
      {
        failure = "surface has a non-finite point coordinate";
        return false;
      }
    }
    vtkCellArray* cells = oriented->GetPolys();
    cells->InitTraversal();
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    double edges = 0.0;
    while (cells->GetNextCell(npts, ids))
    {
      if (npts != 3 || ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2])
      {
        continue;
      }
      const Point3& a = wall.points[ids[0]];
      const Point3& b = wall.points[ids[1]];
      const Point3& c = wall.points[ids[2]];
      if (Norm(Cross(Sub(b, a), Sub(c, a))) <= 0)
      {
        continue;
      }
      wall.triangles.push_back({ { ids[0], ids[1], ids[2] } });
      edges += Distance(a, b) + Distance(b, c) + Distance(c, a);
    }
    if (wall.triangles.size() < 4)
    {
      failure = "surface has " + std::to_string(wall.triangles.size()) +
        " non-degenerate triangle(s): no lumen to find centerlines in";
      return false;
    }
    wall.meanEdge = edges / (3.0 * static_cast<double>(wall.triangles.size()));
    double bounds[6];
    oriented->GetBounds(bounds);
    wall.diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  }
  int openChains = 0;
  wall.loops = FindLoops(wall, openChains);
  if (openChains > 0)
  {
    warnings.push_back(std::to_string(openChains) +
      " boundary edge chain(s) do not close into loops (non-manifold edges?); ignored");
  }

  // Orientation: the signed volume of the wall closed by flat fans over its loops.
  double volume = 0.0;
  for (const auto& t : wall.triangles)
  {
    volume += Dot(wall.points[t[0]], Cross(wall.points[t[1]], wall.points[t[2]]));
  }
  for (const auto& loop : wall.loops)
  {
    const std::size_t n = loop.ids.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& a = wall.points[loop.ids[i]];
      const Point3& b = wall.points[loop.ids[(i + 1) % n]];
      volume += Dot(loop.centre, Cross(b, a));
    }
  }
  volume /= 6.0;
  if (!(std::abs(volume) > 1e-9 * wall.diagonal * wall.diagonal * wall.diagonal))
  {
    failure = "surface encloses no volume (flat or a single sheet): no lumen";
    return false;
  }
  const double orientation = volume > 0 ? 1.0 : -1.0;
  wall.normals.assign(wall.points.size(), Point3{ { 0, 0, 0 } });
  for (const auto& t : wall.triangles)
  {
    const Point3 n = Scale(
      Cross(Sub(wall.points[t[1]], wall.points[t[0]]), Sub(wall.points[t[2]], wall.points[t[0]])),
      orientation);
    for (int k = 0; k < 3; ++k)
    {
      wall.normals[t[k]] = Add(wall.normals[t[k]], n);
    }
  }
  for (auto& n : wall.normals)
  {
    n = UnitVector(n);
  }
  for (auto& loop : wall.loops)
  {
    loop.capNormal = Scale(loop.capNormal, orientation);
  }
  {
    auto surfaceCopy = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints(static_cast<vtkIdType>(wall.points.size()));
    for (std::size_t i = 0; i < wall.points.size(); ++i)
    {
      pts->SetPoint(static_cast<vtkIdType>(i), wall.points[i].data());
    }
    vtkNew<vtkCellArray> tris;
    for (const auto& t : wall.triangles)
    {
      const vtkIdType ids[3] = {
        t[0], orientation > 0 ? t[1] : t[2], orientation > 0 ? t[2] : t[1]
      };
      tris->InsertNextCell(3, ids);
    }
    surfaceCopy->SetPoints(pts);
    surfaceCopy->SetPolys(tris);
    wall.surface = surfaceCopy;
  }
  return true;
}

void DelaunaySamples(Wall& wall, std::vector<Point3>& samples, std::vector<Point3>& sampleNormals)
{
  for (vtkIdType id : ThinWall(wall, DelaunaySpacing))
  {
    samples.push_back(wall.points[id]);
    sampleNormals.push_back(wall.normals[id]);
  }
  for (auto& loop : wall.loops)
  {
    loop.centreSampleId = static_cast<vtkIdType>(samples.size());
    samples.push_back(loop.centre);
    sampleNormals.push_back(loop.capNormal);
    const int rings = std::max(1, static_cast<int>(std::lround(loop.meanRadius / wall.meanEdge)));
    const std::size_t n = loop.ids.size();
    for (int k = 1; k < rings; ++k)
    {
      const double t = static_cast<double>(k) / rings;
      const std::size_t count = std::max<std::size_t>(3, static_cast<std::size_t>(n * t));
      for (std::size_t j = 0; j < count; ++j)
      {
        const Point3& q = wall.points[loop.ids[j * n / count]];
        samples.push_back(Add(loop.centre, Scale(Sub(q, loop.centre), t)));
        sampleNormals.push_back(loop.capNormal);
      }
    }
  }
}

} // namespace centerline
} // namespace bender
