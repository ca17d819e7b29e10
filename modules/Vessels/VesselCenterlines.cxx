#include "VesselCenterlines.h"

#include "DelaunayTetrahedra.h"
#include "VesselArrayNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCleanPolyData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkGenericCell.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkStaticCellLocator.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <random>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace bender
{
namespace
{

// ---- small vector helpers -------------------------------------------------------------------
inline Point3 Sub(const Point3& a, const Point3& b)
{
  return { { a[0] - b[0], a[1] - b[1], a[2] - b[2] } };
}
inline Point3 Add(const Point3& a, const Point3& b)
{
  return { { a[0] + b[0], a[1] + b[1], a[2] + b[2] } };
}
inline Point3 Scale(const Point3& a, double s)
{
  return { { a[0] * s, a[1] * s, a[2] * s } };
}
inline double Dot(const Point3& a, const Point3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Point3 Cross(const Point3& a, const Point3& b)
{
  return { { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] } };
}
inline double Norm(const Point3& a)
{
  return std::sqrt(Dot(a, a));
}
inline double Distance(const Point3& a, const Point3& b)
{
  return Norm(Sub(a, b));
}
inline Point3 Normalized(const Point3& a)
{
  const double n = Norm(a);
  return n > 0 ? Scale(a, 1.0 / n) : Point3{ { 0, 0, 0 } };
}

std::string FormatPoint(const Point3& p)
{
  std::ostringstream s;
  s.precision(4);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// ---- the oriented wall ----------------------------------------------------------------------
struct BoundaryLoop
{
  std::vector<vtkIdType> Ids; // loop vertices in boundary-edge order
  Point3 Centre{ { 0, 0, 0 } };
  Point3 CapNormal{ { 0, 0, 0 } }; // outward when the wall's normals point outward
  double MeanRadius = 0.0;
  bool IsEnd = false;            // planar-ish: a vessel end, not a hole
  vtkIdType CentreSampleId = -1; // id of the centre among the Delaunay points
};

struct Wall
{
  std::vector<Point3> Points;
  std::vector<std::array<vtkIdType, 3>> Triangles;
  std::vector<Point3> Normals; // per point, outward, unit (zero for unused points)
  std::vector<BoundaryLoop> Loops;
  double MeanEdge = 0.0;
  double Diagonal = 0.0;
  vtkSmartPointer<vtkPolyData> Surface; // oriented outward, for distance queries
};

// Boundary loops from the edges used by one triangle only, walked in the direction in which
// their triangle uses them.
std::vector<BoundaryLoop> FindLoops(const Wall& wall, int& openChains)
{
  std::unordered_map<std::uint64_t, int> count;
  count.reserve(wall.Triangles.size() * 3);
  auto key = [](vtkIdType a, vtkIdType b)
  {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    return (hi << 32) | lo;
  };
  for (const auto& t : wall.Triangles)
  {
    for (int e = 0; e < 3; ++e)
    {
      ++count[key(t[e], t[(e + 1) % 3])];
    }
  }
  std::unordered_multimap<vtkIdType, vtkIdType> next;
  for (const auto& t : wall.Triangles)
  {
    for (int e = 0; e < 3; ++e)
    {
      const vtkIdType a = t[e], b = t[(e + 1) % 3];
      if (count[key(a, b)] == 1)
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
      loop.Ids.push_back(current);
      current = to;
      if (current == start)
      {
        closed = true;
        break;
      }
    }
    if (closed && loop.Ids.size() >= 3)
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
    const std::size_t n = loop.Ids.size();
    Point3 c{ { 0, 0, 0 } };
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& a = wall.Points[loop.Ids[i]];
      const Point3& b = wall.Points[loop.Ids[(i + 1) % n]];
      const double l = Distance(a, b);
      c = Add(c, Scale(Add(a, b), 0.5 * l));
      total += l;
    }
    loop.Centre = total > 0 ? Scale(c, 1.0 / total) : wall.Points[loop.Ids[0]];
    Point3 area{ { 0, 0, 0 } };
    double radius = 0.0, diameter = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& a = wall.Points[loop.Ids[i]];
      const Point3& b = wall.Points[loop.Ids[(i + 1) % n]];
      // The cap triangle (centre, b, a) uses the edge the other way round from the wall.
      area = Add(area, Cross(Sub(b, loop.Centre), Sub(a, loop.Centre)));
      radius += Distance(a, loop.Centre);
      diameter = std::max(diameter, 2.0 * Distance(a, loop.Centre));
    }
    loop.MeanRadius = radius / static_cast<double>(n);
    loop.CapNormal = Normalized(area);
    double off = 0.0;
    for (vtkIdType id : loop.Ids)
    {
      off = std::max(off, std::abs(Dot(Sub(wall.Points[id], loop.Centre), loop.CapNormal)));
    }
    loop.IsEnd = Norm(area) > 0 && off <= 0.1 * diameter;
  }
  return loops;
}

// ---- 3D Delaunay ----------------------------------------------------------------------------
using Tetra = std::array<vtkIdType, 4>;

// Our incremental Delaunay (DelaunayTetrahedra.h: exact predicates, three to six times faster
// than Qhull on vessel surfaces, see bench_centerlines); Qhull, where the system has it, only
// should the incremental one report an internal inconsistency. The points are snapped to the
// triangulation's grid. `neighbours`: the tetrahedron across the face opposite each vertex.
// `warning`: set when Qhull had to step in.
bool Tetrahedralise(std::vector<Point3>& points,
  std::vector<Tetra>& tets,
  std::vector<Tetra>& neighbours,
  std::string& error,
  std::string& warning)
{
  tets.clear();
  if (DelaunayTetrahedra(points, tets, error, nullptr, &neighbours))
  {
    return true;
  }
  if (error.rfind("internal error", 0) == 0)
  {
    std::string qhullError;
    if (QhullTetrahedra(points, tets, qhullError, &neighbours))
    {
      warning = "the Delaunay reported an " + error + "; Qhull's was used instead";
      return true;
    }
    error += "; " + qhullError;
  }
  return false;
}

// ---- thinning the wall's points before the Delaunay -----------------------------------------
// The Voronoi diagram only has to find the paths through the lumen (the centerline is then
// re-centred on the wall itself, see SectionCentre), so it needs a fraction of the local radius
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
  const std::size_t n = wall.Points.size();
  std::vector<vtkIdType> kept;
  std::vector<std::vector<vtkIdType>> neighbours(n);
  for (const auto& t : wall.Triangles)
  {
    for (int e = 0; e < 3; ++e)
    {
      neighbours[t[e]].push_back(t[(e + 1) % 3]);
      neighbours[t[(e + 1) % 3]].push_back(t[e]);
    }
  }
  std::vector<bool> onBoundary(n, false);
  for (const auto& loop : wall.Loops)
  {
    for (vtkIdType id : loop.Ids)
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
      const double l = Distance(wall.Points[i], wall.Points[j]);
      const double c = std::clamp(Dot(wall.Normals[i], wall.Normals[j]), -1.0, 1.0);
      if (l > 0)
      {
        curvature[i] = std::max(curvature[i], std::acos(c) / l);
      }
    }
  }
  std::vector<double> spacing(n, std::numeric_limits<double>::infinity());
  const double largest = 0.05 * wall.Diagonal;
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
    spacing[i] = std::max(spacing[i], wall.MeanEdge);
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
        const double g = h + 0.25 * Distance(wall.Points[i], wall.Points[j]);
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
    if (onBoundary[i] || spacing[i] < 1.5 * wall.MeanEdge)
    {
      kept.push_back(static_cast<vtkIdType>(i));
      continue;
    }
    const int level = std::min(
      40, static_cast<int>(std::floor(std::log(spacing[i] / wall.MeanEdge) / std::log(1.5))));
    const double size = wall.MeanEdge * std::pow(1.5, level);
    std::uint64_t key = static_cast<std::uint64_t>(level);
    double offset = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      const double x = wall.Points[i][c] / size;
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

// ---- Dijkstra on the Voronoi graph ----------------------------------------------------------
struct Graph
{
  std::vector<Point3> Centres;
  std::vector<double> Radii;
  std::vector<int> Offsets; // CSR
  std::vector<int> Neighbours;
  std::vector<double> Lengths; // of the edges, as Neighbours

  int Size() const { return static_cast<int>(this->Centres.size()); }
};

struct ShortestPaths
{
  std::vector<double> Cost;
  std::vector<int> Previous;
  std::vector<int> Origin; // the source each node was reached from
};

enum class Weight
{
  Length,
  LengthOverRadius
};

// Makes `sources` sources of sp (cost 0) and relaxes from them: on an empty sp, Dijkstra from
// the sources; on the result of an earlier call, the same as Dijkstra from the old and the new
// sources together (costs only decrease), for the cost of the nodes that change only.
void AddSources(const Graph& g, ShortestPaths& sp, const std::vector<int>& sources, Weight weight)
{
  const int n = g.Size();
  if (sp.Cost.empty())
  {
    sp.Cost.assign(n, std::numeric_limits<double>::infinity());
    sp.Previous.assign(n, -1);
    sp.Origin.assign(n, -1);
  }
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int s : sources)
  {
    sp.Cost[s] = 0.0;
    sp.Previous[s] = -1;
    sp.Origin[s] = s;
    queue.emplace(0.0, s);
  }
  while (!queue.empty())
  {
    const auto [cost, u] = queue.top();
    queue.pop();
    if (cost > sp.Cost[u])
    {
      continue;
    }
    for (int k = g.Offsets[u]; k < g.Offsets[u + 1]; ++k)
    {
      const int v = g.Neighbours[k];
      double w = g.Lengths[k];
      if (weight == Weight::LengthOverRadius)
      {
        w *= 0.5 * (1.0 / g.Radii[u] + 1.0 / g.Radii[v]);
      }
      if (cost + w < sp.Cost[v])
      {
        sp.Cost[v] = cost + w;
        sp.Previous[v] = u;
        sp.Origin[v] = sp.Origin[u];
        queue.emplace(sp.Cost[v], v);
      }
    }
  }
}

ShortestPaths Dijkstra(const Graph& g, const std::vector<int>& sources, Weight weight)
{
  ShortestPaths sp;
  AddSources(g, sp, sources, weight);
  return sp;
}

std::vector<int> Backtrace(const ShortestPaths& sp, int target)
{
  std::vector<int> nodes;
  for (int v = target; v >= 0; v = sp.Previous[v])
  {
    nodes.push_back(v);
  }
  std::reverse(nodes.begin(), nodes.end());
  return nodes;
}

// ---- polylines ------------------------------------------------------------------------------
double Length(const std::vector<Point3>& p)
{
  double l = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i)
  {
    l += Distance(p[i - 1], p[i]);
  }
  return l;
}

// Samples at abscissae 0, h, 2h, ... from the first point, and the last point.
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

// Laplacian smoothing with fixed ends; the kernel's standard deviation is about sigmaSamples.
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

// Distance queries against the oriented wall.
class WallDistance
{
public:
  explicit WallDistance(vtkPolyData* wall)
    : Wall(wall)
  {
    this->Locator->SetDataSet(wall);
    this->Locator->BuildLocator();
  }

  /// Unsigned distance to the wall and whether p is on the inner side of the closest triangle.
  double Query(const Point3& p, bool& inside, Point3& closest)
  {
    double x[3] = { p[0], p[1], p[2] }, c[3];
    vtkIdType cellId = -1;
    int subId = 0;
    double d2 = 0.0;
    this->Locator->FindClosestPoint(x, c, this->Cell, cellId, subId, d2);
    closest = { { c[0], c[1], c[2] } };
    inside = true;
    if (cellId >= 0)
    {
      const vtkIdType* ids = nullptr;
      vtkIdType npts = 0;
      this->Wall->GetCellPoints(cellId, npts, ids);
      double a[3], b[3], e[3], n[3];
      this->Wall->GetPoint(ids[0], a);
      this->Wall->GetPoint(ids[1], b);
      this->Wall->GetPoint(ids[2], e);
      vtkTriangle_Normal(a, b, e, n);
      inside = (x[0] - c[0]) * n[0] + (x[1] - c[1]) * n[1] + (x[2] - c[2]) * n[2] <= 0.0;
    }
    return std::sqrt(d2);
  }

  /// First wall hit from p along the unit direction u within length; false when none.
  bool Ray(const Point3& p, const Point3& u, double length, Point3& hit, vtkIdType& cellId)
  {
    const double a[3] = { p[0], p[1], p[2] };
    const double b[3] = { p[0] + length * u[0], p[1] + length * u[1], p[2] + length * u[2] };
    double t = 0.0, x[3], pcoords[3];
    int subId = 0;
    cellId = -1;
    if (!this->Locator->IntersectWithLine(a, b, 0.0, t, x, pcoords, subId, cellId, this->Cell))
    {
      return false;
    }
    hit = { { x[0], x[1], x[2] } };
    return true;
  }

  vtkPolyData* GetWall() const { return this->Wall; }

private:
  static void vtkTriangle_Normal(const double a[3],
    const double b[3],
    const double c[3],
    double n[3])
  {
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    vtkMath::Cross(u, v, n);
  }

  vtkPolyData* Wall;
  vtkNew<vtkStaticCellLocator> Locator;
  vtkNew<vtkGenericCell> Cell;
};

// The triangles on either side of every edge of the wall (-1: none; an edge of three or more
// triangles keeps its first two and is marked by a third entry of -2).
using EdgeTriangles = std::unordered_map<std::uint64_t, std::array<vtkIdType, 3>>;

inline std::uint64_t EdgeKey(vtkIdType a, vtkIdType b)
{
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32) | lo;
}

EdgeTriangles BuildEdgeTriangles(vtkPolyData* wall)
{
  EdgeTriangles edges;
  edges.reserve(static_cast<std::size_t>(wall->GetNumberOfCells()) * 2);
  for (vtkIdType c = 0; c < wall->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids = nullptr;
    vtkIdType npts = 0;
    wall->GetCellPoints(c, npts, ids);
    for (vtkIdType k = 0; k < npts; ++k)
    {
      auto& entry = edges
                      .try_emplace(EdgeKey(ids[k], ids[(k + 1) % npts]),
                        std::array<vtkIdType, 3>{ { -1, -1, -1 } })
                      .first->second;
      if (entry[0] < 0)
      {
        entry[0] = c;
      }
      else if (entry[1] < 0)
      {
        entry[1] = c;
      }
      else
      {
        entry[2] = -2;
      }
    }
  }
  return edges;
}

enum class SectionKind
{
  Closed,  ///< the section closes around the point
  Escaped, ///< it runs out through an open end of the wall
  Failed   ///< too long, not around the point, a non-manifold edge, a degenerate cut
};

struct Section
{
  SectionKind Kind = SectionKind::Failed;
  Point3 Centroid{ { 0, 0, 0 } };
  double Roundness = 0;  ///< largest over smallest distance from the centroid to the loop
  double MeanRadius = 0; ///< sqrt(area / pi)
};

// The cross-section of the lumen through p in the plane normal to t: the loop of the wall's
// intersection with that plane around p, traced triangle by triangle from the wall point hit by
// a ray from p in the plane. The plane is cut exactly, edge by edge, so the loop is the same
// polygon whatever the tessellation of a flat stretch of wall, and its area centroid is an
// integral over the whole wall around the lumen: unlike the Voronoi vertices it does not depend
// on where the wall's points happen to be. The centroid of any oblique section of a straight
// tube (circular or elliptic) lies on its axis, so errors of the plane's direction do not move
// it either.
Section CutSection(WallDistance& distance,
  const EdgeTriangles& edges,
  const Point3& p,
  const Point3& t,
  double reach,
  double maxLength)
{
  Section section;
  vtkPolyData* wall = distance.GetWall();
  const Point3 axis = std::abs(t[0]) < 0.9 ? Point3{ { 1, 0, 0 } } : Point3{ { 0, 1, 0 } };
  const Point3 e1 = Normalized(Cross(t, axis));
  const Point3 e2 = Cross(t, e1);
  Point3 hit;
  vtkIdType start = -1;
  if (!distance.Ray(p, e1, reach, hit, start) || start < 0)
  {
    section.Kind = SectionKind::Escaped;
    return section;
  }
  auto height = [&](vtkIdType id)
  {
    Point3 x;
    wall->GetPoint(id, x.data());
    return Dot(Sub(x, p), t);
  };
  // Crossing of the plane on edge (a, b), in plane coordinates.
  auto cross = [&](vtkIdType a, vtkIdType b)
  {
    Point3 xa, xb;
    wall->GetPoint(a, xa.data());
    wall->GetPoint(b, xb.data());
    const double ha = Dot(Sub(xa, p), t), hb = Dot(Sub(xb, p), t);
    const double w = ha / (ha - hb);
    const Point3 x = Sub(Add(xa, Scale(Sub(xb, xa), w)), p);
    return std::array<double, 2>{ { Dot(x, e1), Dot(x, e2) } };
  };
  // The two edges of triangle c that cross the plane (heights >= 0 count as above).
  auto crossingEdges = [&](vtkIdType c, std::array<std::array<vtkIdType, 2>, 2>& out)
  {
    const vtkIdType* ids = nullptr;
    vtkIdType npts = 0;
    wall->GetCellPoints(c, npts, ids);
    if (npts != 3)
    {
      return false;
    }
    const double h[3] = { height(ids[0]), height(ids[1]), height(ids[2]) };
    int found = 0;
    for (int k = 0; k < 3; ++k)
    {
      const int j = (k + 1) % 3;
      if ((h[k] >= 0) != (h[j] >= 0))
      {
        if (found < 2)
        {
          out[found] = { { ids[k], ids[j] } };
        }
        ++found;
      }
    }
    return found == 2;
  };
  std::array<std::array<vtkIdType, 2>, 2> pair;
  if (!crossingEdges(start, pair))
  {
    return section;
  }
  std::vector<std::array<double, 2>> loop;
  std::array<vtkIdType, 2> edge = pair[1];
  const std::uint64_t firstEdge = EdgeKey(pair[0][0], pair[0][1]);
  vtkIdType current = start;
  double length = 0.0;
  loop.push_back(cross(pair[0][0], pair[0][1]));
  while (true)
  {
    const std::uint64_t key = EdgeKey(edge[0], edge[1]);
    if (key == firstEdge)
    {
      break; // closed
    }
    loop.push_back(cross(edge[0], edge[1]));
    const auto& a = loop[loop.size() - 2];
    const auto& b = loop.back();
    length += std::hypot(b[0] - a[0], b[1] - a[1]);
    if (length > maxLength)
    {
      return section;
    }
    auto found = edges.find(key);
    if (found == edges.end() || found->second[2] == -2)
    {
      return section;
    }
    const vtkIdType next = found->second[0] == current ? found->second[1] : found->second[0];
    if (next < 0)
    {
      section.Kind = SectionKind::Escaped;
      return section;
    }
    if (!crossingEdges(next, pair))
    {
      return section;
    }
    edge = EdgeKey(pair[0][0], pair[0][1]) == key ? pair[1] : pair[0];
    current = next;
  }
  const std::size_t n = loop.size();
  if (n < 3)
  {
    return section;
  }
  bool inside = false;
  double area = 0.0, cx = 0.0, cy = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto& a = loop[i];
    const auto& b = loop[(i + 1) % n];
    if ((a[1] > 0) != (b[1] > 0) && a[0] - a[1] * (b[0] - a[0]) / (b[1] - a[1]) > 0)
    {
      inside = !inside;
    }
    const double w = a[0] * b[1] - a[1] * b[0];
    area += w;
    cx += (a[0] + b[0]) * w;
    cy += (a[1] + b[1]) * w;
  }
  if (!inside || !(std::abs(area) > 0))
  {
    return section;
  }
  cx /= 3.0 * area;
  cy /= 3.0 * area;
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto& a = loop[i];
    const auto& b = loop[(i + 1) % n];
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double l2 = dx * dx + dy * dy;
    const double u =
      std::clamp(l2 > 0 ? ((cx - a[0]) * dx + (cy - a[1]) * dy) / l2 : 0.0, 0.0, 1.0);
    nearest = std::min(nearest, std::hypot(a[0] + u * dx - cx, a[1] + u * dy - cy));
    farthest = std::max(farthest, std::hypot(a[0] - cx, a[1] - cy));
  }
  section.Kind = SectionKind::Closed;
  section.Centroid = Add(p, Add(Scale(e1, cx), Scale(e2, cy)));
  section.Roundness = nearest > 0 ? farthest / nearest : std::numeric_limits<double>::infinity();
  section.MeanRadius = std::sqrt(0.5 * std::abs(area) / 3.14159265358979323846);
  return section;
}

// Sections are trusted fully up to this roundness (the elliptic stretches of the gmsh
// aneurysm's vessels measure up to about 1.5), not at all from the next value on (a
// bifurcation, an aneurysm's neck: 2 to 5), linearly in between, so that the centerline does
// not jump where a section crosses a threshold.
constexpr double RoundSection = 1.5;
constexpr double NotRoundSection = 1.9;

// Smoothing length of the spline through the section centroids, in median inscribed radii.
constexpr double SplineLength = 0.25;
// Smoothing length of the spline that bridges the sections not trusted, in median radii.
constexpr double BridgeLength = 0.5;

// Weight of a section's centroid for the point p it was cut through: its roundness and how far
// the centroid is from p (more than half the section's mean radius: the plane is not across the
// vessel p is in), tapered; WidthWeight: how its mean radius compares with the inscribed radius
// at the centroid (more than 1.35 times: the plane cuts a bifurcation's or an aneurysm's wide
// region, where the section of one vessel's tube is not defined; an elliptic section of ratio
// 1.5 measures 1.22), tapered.
double SectionWeight(const Section& s, const Point3& p)
{
  if (s.Kind != SectionKind::Closed || !(s.MeanRadius > 0))
  {
    return 0.0;
  }
  const double round =
    std::clamp((NotRoundSection - s.Roundness) / (NotRoundSection - RoundSection), 0.0, 1.0);
  const double move = Distance(s.Centroid, p) / s.MeanRadius;
  const double near = std::clamp((0.65 - move) / 0.2, 0.0, 1.0);
  return round * near;
}

double WidthWeight(const Section& s, double inscribed)
{
  return inscribed > 0 ? std::clamp((1.6 - s.MeanRadius / inscribed) / 0.25, 0.0, 1.0) : 0.0;
}

// Smoothing spline through weighted targets: minimises
//   sum_i w_i |x_i - c_i|^2 + lambda sum_i |order-th difference of x at i|^2   (order 2 or 3)
// with x_0 and x_{n-1} fixed where fixFirst / fixLast (to their current values), else free.
// Runs of zero weight are bridged by cubic (order 2) or quintic (order 3) curves. The ends of a
// second-difference spline straighten (its natural end condition is zero curvature), those of a
// third-difference spline keep their curvature. The system is symmetric positive definite and
// banded; solved by banded Gaussian elimination without pivoting.
void SmoothingSpline(std::vector<Point3>& x,
  const std::vector<Point3>& targets,
  const std::vector<double>& weights,
  int order,
  double lambda,
  bool fixFirst,
  bool fixLast)
{
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
  if (fixFirst)
  {
    fix(0);
  }
  if (fixLast)
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

struct PathSamples
{
  std::vector<Point3> Points;
  std::vector<double> Radius;
  std::vector<CurveSample> Frames;
  int Outlet = -1;
};

void AppendSamples(const PathSamples& path,
  std::size_t from,
  std::size_t to,
  vtkPoints* points,
  vtkDoubleArray* radius,
  vtkDoubleArray* abscissa,
  vtkDoubleArray* tangent,
  vtkDoubleArray* normal,
  vtkDoubleArray* curvature,
  vtkDoubleArray* torsion,
  vtkIdList* line)
{
  for (std::size_t k = from; k <= to; ++k)
  {
    const vtkIdType id = points->InsertNextPoint(path.Points[k].data());
    radius->InsertNextValue(path.Radius[k]);
    abscissa->InsertNextValue(path.Frames[k].Abscissa);
    tangent->InsertNextTuple(path.Frames[k].Tangent.data());
    normal->InsertNextTuple(path.Frames[k].Normal.data());
    curvature->InsertNextValue(path.Frames[k].Curvature);
    torsion->InsertNextValue(path.Frames[k].Torsion);
    line->InsertNextId(id);
  }
}

struct PointArrays
{
  vtkNew<vtkPoints> Points;
  vtkNew<vtkDoubleArray> Radius;
  vtkNew<vtkDoubleArray> Abscissa;
  vtkNew<vtkDoubleArray> Tangent;
  vtkNew<vtkDoubleArray> Normal;
  vtkNew<vtkDoubleArray> Curvature;
  vtkNew<vtkDoubleArray> Torsion;
  vtkNew<vtkCellArray> Lines;

  PointArrays()
  {
    this->Points->SetDataTypeToDouble();
    this->Radius->SetName(VesselArrays::MaximumInscribedSphereRadius);
    this->Abscissa->SetName(VesselArrays::Abscissa);
    this->Tangent->SetName(VesselArrays::FrenetTangent);
    this->Tangent->SetNumberOfComponents(3);
    this->Normal->SetName(VesselArrays::FrenetNormal);
    this->Normal->SetNumberOfComponents(3);
    this->Curvature->SetName(VesselArrays::Curvature);
    this->Torsion->SetName(VesselArrays::Torsion);
  }

  void Add(const PathSamples& path, std::size_t from, std::size_t to)
  {
    vtkNew<vtkIdList> line;
    AppendSamples(path,
      from,
      to,
      this->Points,
      this->Radius,
      this->Abscissa,
      this->Tangent,
      this->Normal,
      this->Curvature,
      this->Torsion,
      line);
    this->Lines->InsertNextCell(line);
  }

  vtkSmartPointer<vtkPolyData> Build()
  {
    auto out = vtkSmartPointer<vtkPolyData>::New();
    out->SetPoints(this->Points);
    out->SetLines(this->Lines);
    out->GetPointData()->AddArray(this->Radius);
    out->GetPointData()->AddArray(this->Abscissa);
    out->GetPointData()->AddArray(this->Tangent);
    out->GetPointData()->AddArray(this->Normal);
    out->GetPointData()->AddArray(this->Curvature);
    out->GetPointData()->AddArray(this->Torsion);
    return out;
  }
};

vtkSmartPointer<vtkIntArray> MakeIntArray(const char* name)
{
  auto a = vtkSmartPointer<vtkIntArray>::New();
  a->SetName(name);
  return a;
}

CenterlineResult Fail(CenterlineResult result, const std::string& message)
{
  result.Ok = false;
  result.Message = message;
  result.Branches = vtkSmartPointer<vtkPolyData>::New();
  result.Paths = vtkSmartPointer<vtkPolyData>::New();
  return result;
}

} // namespace

// ---- frames ---------------------------------------------------------------------------------
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
    c.Position = points[i];
    c.Abscissa = startAbscissa + s[i];
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
    c.Tangent = Scale(d1, 1.0 / speed);
    const Point3 b = Cross(d1, d2);
    const double bn = Norm(b);
    c.Curvature = bn / (speed * speed * speed);
    c.Torsion = bn > 0 ? Dot(b, d3) / (bn * bn) : 0.0;
    Point3 n = Sub(d2, Scale(c.Tangent, Dot(d2, c.Tangent)));
    // Where the line is (nearly) straight the Frenet normal is undefined: carry the previous
    // normal along (projected), or pick any perpendicular at the start.
    if (Norm(n) < 1e-6 * (Norm(d2) + 1e-12) || c.Curvature * window < 1e-6)
    {
      n = Sub(previousNormal, Scale(c.Tangent, Dot(previousNormal, c.Tangent)));
      if (Norm(n) < 1e-6)
      {
        const Point3 axis =
          std::abs(c.Tangent[0]) < 0.9 ? Point3{ { 1, 0, 0 } } : Point3{ { 0, 1, 0 } };
        n = Cross(c.Tangent, Cross(axis, c.Tangent));
      }
    }
    c.Normal = Normalized(n);
    previousNormal = c.Normal;
  }
  return out;
}

// ---- the workflow ---------------------------------------------------------------------------
CenterlineResult ComputeCenterlines(vtkPolyData* surface, const CenterlineOptions& options)
{
  if (!surface)
  {
    throw std::invalid_argument("ComputeCenterlines: the surface is null");
  }
  if (!(options.Step >= 0) ||
    !(options.BranchLengthToRadius >= 1 && options.BranchLengthToRadius <= 20) ||
    !(options.EndTrimFactor >= 1 && options.EndTrimFactor <= 3))
  {
    throw std::invalid_argument("ComputeCenterlines: an option is out of range (Step >= 0, "
                                "BranchLengthToRadius in [1, 20], EndTrimFactor in [1, 3])");
  }
  for (const auto& seed : options.Seeds)
  {
    if (!std::isfinite(seed[0]) || !std::isfinite(seed[1]) || !std::isfinite(seed[2]))
    {
      throw std::invalid_argument("ComputeCenterlines: a seed has a non-finite coordinate");
    }
  }
  if (options.Seeds.size() == 1)
  {
    throw std::invalid_argument("ComputeCenterlines: give at least two seeds (the inlet first), "
                                "or none");
  }

  CenterlineResult result;
  auto clock = std::chrono::steady_clock::now();

  // 1. The wall: triangles, merged points, consistent orientation.
  Wall wall;
  {
    vtkNew<vtkPolyData> polys;
    polys->SetPoints(surface->GetPoints());
    polys->SetPolys(surface->GetPolys());
    if (!surface->GetPoints() || surface->GetNumberOfPolys() == 0)
    {
      return Fail(result, "surface has no polygons: no lumen to find centerlines in");
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
    wall.Points.resize(np);
    for (vtkIdType i = 0; i < np; ++i)
    {
      oriented->GetPoint(i, wall.Points[i].data());
      if (!std::isfinite(wall.Points[i][0]) || !std::isfinite(wall.Points[i][1]) ||
        !std::isfinite(wall.Points[i][2]))
      {
        return Fail(result, "surface has a non-finite point coordinate");
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
      const Point3& a = wall.Points[ids[0]];
      const Point3& b = wall.Points[ids[1]];
      const Point3& c = wall.Points[ids[2]];
      if (Norm(Cross(Sub(b, a), Sub(c, a))) <= 0)
      {
        continue;
      }
      wall.Triangles.push_back({ { ids[0], ids[1], ids[2] } });
      edges += Distance(a, b) + Distance(b, c) + Distance(c, a);
    }
    if (wall.Triangles.size() < 4)
    {
      return Fail(result,
        "surface has " + std::to_string(wall.Triangles.size()) +
          " non-degenerate triangle(s): no lumen to find centerlines in");
    }
    wall.MeanEdge = edges / (3.0 * static_cast<double>(wall.Triangles.size()));
    double bounds[6];
    oriented->GetBounds(bounds);
    wall.Diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  }
  int openChains = 0;
  wall.Loops = FindLoops(wall, openChains);
  if (openChains > 0)
  {
    result.Warnings.push_back(std::to_string(openChains) +
      " boundary edge chain(s) do not close into loops (non-manifold edges?); ignored");
  }

  // Orientation: the signed volume of the wall closed by flat fans over its loops.
  double volume = 0.0;
  for (const auto& t : wall.Triangles)
  {
    volume += Dot(wall.Points[t[0]], Cross(wall.Points[t[1]], wall.Points[t[2]]));
  }
  for (const auto& loop : wall.Loops)
  {
    const std::size_t n = loop.Ids.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& a = wall.Points[loop.Ids[i]];
      const Point3& b = wall.Points[loop.Ids[(i + 1) % n]];
      volume += Dot(loop.Centre, Cross(b, a));
    }
  }
  volume /= 6.0;
  if (!(std::abs(volume) > 1e-9 * wall.Diagonal * wall.Diagonal * wall.Diagonal))
  {
    return Fail(result, "surface encloses no volume (flat or a single sheet): no lumen");
  }
  const double orientation = volume > 0 ? 1.0 : -1.0;
  wall.Normals.assign(wall.Points.size(), Point3{ { 0, 0, 0 } });
  for (const auto& t : wall.Triangles)
  {
    const Point3 n = Scale(
      Cross(Sub(wall.Points[t[1]], wall.Points[t[0]]), Sub(wall.Points[t[2]], wall.Points[t[0]])),
      orientation);
    for (int k = 0; k < 3; ++k)
    {
      wall.Normals[t[k]] = Add(wall.Normals[t[k]], n);
    }
  }
  for (auto& n : wall.Normals)
  {
    n = Normalized(n);
  }
  for (auto& loop : wall.Loops)
  {
    loop.CapNormal = Scale(loop.CapNormal, orientation);
  }
  {
    auto surfaceCopy = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    pts->SetNumberOfPoints(static_cast<vtkIdType>(wall.Points.size()));
    for (std::size_t i = 0; i < wall.Points.size(); ++i)
    {
      pts->SetPoint(static_cast<vtkIdType>(i), wall.Points[i].data());
    }
    vtkNew<vtkCellArray> tris;
    for (const auto& t : wall.Triangles)
    {
      const vtkIdType ids[3] = {
        t[0], orientation > 0 ? t[1] : t[2], orientation > 0 ? t[2] : t[1]
      };
      tris->InsertNextCell(3, ids);
    }
    surfaceCopy->SetPoints(pts);
    surfaceCopy->SetPolys(tris);
    wall.Surface = surfaceCopy;
  }

  // Delaunay points: the wall's points, then points on flat caps over every loop (so that no
  // empty sphere bulges out of an open end), each with its outward normal.
  std::vector<Point3> samples;
  std::vector<Point3> sampleNormals;
  for (vtkIdType id : ThinWall(wall, DelaunaySpacing))
  {
    samples.push_back(wall.Points[id]);
    sampleNormals.push_back(wall.Normals[id]);
  }
  for (auto& loop : wall.Loops)
  {
    loop.CentreSampleId = static_cast<vtkIdType>(samples.size());
    samples.push_back(loop.Centre);
    sampleNormals.push_back(loop.CapNormal);
    const int rings = std::max(1, static_cast<int>(std::lround(loop.MeanRadius / wall.MeanEdge)));
    const std::size_t n = loop.Ids.size();
    for (int k = 1; k < rings; ++k)
    {
      const double t = static_cast<double>(k) / rings;
      const std::size_t count = std::max<std::size_t>(3, static_cast<std::size_t>(n * t));
      for (std::size_t j = 0; j < count; ++j)
      {
        const Point3& q = wall.Points[loop.Ids[j * n / count]];
        samples.push_back(Add(loop.Centre, Scale(Sub(q, loop.Centre), t)));
        sampleNormals.push_back(loop.CapNormal);
      }
    }
  }
  result.Times.Preparation = Seconds(clock);

  // 2. Delaunay tetrahedralisation of the (slightly jittered, for robustness against the
  // co-spherical points of regular meshes) samples.
  clock = std::chrono::steady_clock::now();
  {
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> jitter(-1.0, 1.0);
    const double amplitude = 1e-4 * wall.MeanEdge;
    for (auto& p : samples)
    {
      for (int c = 0; c < 3; ++c)
      {
        p[c] += amplitude * jitter(random);
      }
    }
  }
  result.NumberOfDelaunayPoints = static_cast<int>(samples.size());
  std::vector<Tetra> tetras, across;
  std::string delaunayError;
  std::string delaunayWarning;
  if (!Tetrahedralise(samples, tetras, across, delaunayError, delaunayWarning))
  {
    result.Times.Delaunay = Seconds(clock);
    return Fail(result, "surface points cannot be tetrahedralised (" + delaunayError + ")");
  }
  if (!delaunayWarning.empty())
  {
    result.Warnings.push_back(delaunayWarning);
  }
  result.Times.Delaunay = Seconds(clock);

  // 3. Internal Voronoi vertices: circumcentres on the inner side of all four vertex normals.
  clock = std::chrono::steady_clock::now();
  Graph graph;
  std::vector<double> loopStartRadius(wall.Loops.size(), -1.0);
  std::vector<int> loopStartNode(wall.Loops.size(), -1);
  std::unordered_map<vtkIdType, int> centreToLoop;
  for (std::size_t l = 0; l < wall.Loops.size(); ++l)
  {
    centreToLoop[wall.Loops[l].CentreSampleId] = static_cast<int>(l);
  }
  // The graph's node of each tetrahedron (-1: its circumcentre is not an internal vertex).
  std::vector<int> nodeOf(tetras.size(), -1);
  {
    for (std::size_t t = 0; t < tetras.size(); ++t)
    {
      const Tetra& tetra = tetras[t];
      vtkIdType v[4] = { tetra[0], tetra[1], tetra[2], tetra[3] };
      if (std::min({ v[0], v[1], v[2], v[3] }) < 0 ||
        std::max({ v[0], v[1], v[2], v[3] }) >= static_cast<vtkIdType>(samples.size()))
      {
        continue;
      }
      // Circumcentre relative to v0: solve 2 (pk - p0) . x = |pk - p0|^2.
      const Point3& p0 = samples[v[0]];
      const Point3 a = Sub(samples[v[1]], p0);
      const Point3 b = Sub(samples[v[2]], p0);
      const Point3 e = Sub(samples[v[3]], p0);
      const double det = 2.0 * Dot(a, Cross(b, e));
      const double scale3 = Norm(a) * Norm(b) * Norm(e);
      if (!(std::abs(det) > 1e-12 * scale3))
      {
        continue;
      }
      const Point3 x = Scale(Add(Add(Scale(Cross(b, e), Dot(a, a)), Scale(Cross(e, a), Dot(b, b))),
                               Scale(Cross(a, b), Dot(e, e))),
        1.0 / det);
      const Point3 centre = Add(p0, x);
      const double radius = Norm(x);
      if (!(radius > 0) || radius > wall.Diagonal)
      {
        continue;
      }
      bool inside = true;
      for (int k = 0; k < 4 && inside; ++k)
      {
        const Point3& n = sampleNormals[v[k]];
        inside = Norm(n) > 0 && Dot(n, Sub(centre, samples[v[k]])) < 0.0;
      }
      if (!inside)
      {
        continue;
      }
      const int node = graph.Size();
      graph.Centres.push_back(centre);
      graph.Radii.push_back(radius);
      nodeOf[t] = node;
      for (int k = 0; k < 4; ++k)
      {
        auto found = centreToLoop.find(v[k]);
        if (found != centreToLoop.end() && radius > loopStartRadius[found->second])
        {
          loopStartRadius[found->second] = radius;
          loopStartNode[found->second] = node;
        }
      }
    }
  }
  result.NumberOfVoronoiVertices = graph.Size();
  if (graph.Size() < 2)
  {
    result.Times.Voronoi = Seconds(clock);
    return Fail(result,
      "surface has no interior: no internal Voronoi vertex (is it a closed or "
      "open tube of triangles?)");
  }
  {
    // Two internal vertices are joined when their tetrahedra share a face.
    std::vector<std::pair<int, int>> edges;
    for (std::size_t t = 0; t < tetras.size(); ++t)
    {
      for (int k = 0; nodeOf[t] >= 0 && k < 4; ++k)
      {
        const vtkIdType u = across[t][k];
        if (u > static_cast<vtkIdType>(t) && nodeOf[u] >= 0)
        {
          edges.emplace_back(nodeOf[t], nodeOf[u]);
        }
      }
    }
    graph.Offsets.assign(graph.Size() + 1, 0);
    for (const auto& e : edges)
    {
      ++graph.Offsets[e.first + 1];
      ++graph.Offsets[e.second + 1];
    }
    for (int i = 0; i < graph.Size(); ++i)
    {
      graph.Offsets[i + 1] += graph.Offsets[i];
    }
    graph.Neighbours.resize(graph.Offsets.back());
    std::vector<int> fill(graph.Offsets.begin(), graph.Offsets.end() - 1);
    for (const auto& e : edges)
    {
      graph.Neighbours[fill[e.first]++] = e.second;
      graph.Neighbours[fill[e.second]++] = e.first;
    }
    graph.Lengths.resize(graph.Neighbours.size());
    for (int u = 0; u < graph.Size(); ++u)
    {
      for (int k = graph.Offsets[u]; k < graph.Offsets[u + 1]; ++k)
      {
        graph.Lengths[k] = Distance(graph.Centres[u], graph.Centres[graph.Neighbours[k]]);
      }
    }
  }
  result.Times.Voronoi = Seconds(clock);

  // 4. Endpoints: nodes of the graph, with their positions.
  clock = std::chrono::steady_clock::now();
  struct EndNode
  {
    int Node = -1;
    CenterlineEndpoint Endpoint;
    bool PrependPosition = false; // the path starts/ends at Endpoint.Position, off the graph
  };
  std::vector<EndNode> ends;
  // The largest inscribed sphere that contains x (enlarged by 5 %), else the nearest centre.
  auto nodeFor = [&graph](const Point3& x)
  {
    int best = -1, nearest = 0;
    double bestRadius = -1.0, nearestDistance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < graph.Size(); ++i)
    {
      const double d = Distance(graph.Centres[i], x);
      if (d <= 1.05 * graph.Radii[i] && graph.Radii[i] > bestRadius)
      {
        bestRadius = graph.Radii[i];
        best = i;
      }
      if (d < nearestDistance)
      {
        nearestDistance = d;
        nearest = i;
      }
    }
    return best >= 0 ? best : nearest;
  };
  if (!options.Seeds.empty())
  {
    for (std::size_t s = 0; s < options.Seeds.size(); ++s)
    {
      EndNode end;
      end.Endpoint.Kind = EndpointKind::Seed;
      end.Endpoint.Inlet = (s == 0);
      const Point3& seed = options.Seeds[s];
      int snapped = -1;
      for (std::size_t l = 0; l < wall.Loops.size(); ++l)
      {
        const auto& loop = wall.Loops[l];
        if (loop.IsEnd && loopStartNode[l] >= 0 &&
          Distance(seed, loop.Centre) <= 1.5 * loop.MeanRadius &&
          (snapped < 0 || Distance(seed, loop.Centre) < Distance(seed, wall.Loops[snapped].Centre)))
        {
          snapped = static_cast<int>(l);
        }
      }
      if (snapped >= 0)
      {
        end.Node = loopStartNode[snapped];
        end.Endpoint.Position = wall.Loops[snapped].Centre;
        end.Endpoint.Radius = wall.Loops[snapped].MeanRadius;
        end.PrependPosition = true;
      }
      else
      {
        end.Node = nodeFor(seed);
        end.Endpoint.Position = graph.Centres[end.Node];
        end.Endpoint.Radius = graph.Radii[end.Node];
      }
      ends.push_back(end);
    }
  }
  else
  {
    int holes = 0;
    for (std::size_t l = 0; l < wall.Loops.size(); ++l)
    {
      const auto& loop = wall.Loops[l];
      // A hole in the wall is flat too, but the lumen's sphere that touches its centre is much
      // larger than the hole; at a vessel end it is about the end's radius.
      if (!loop.IsEnd || (loopStartNode[l] >= 0 && loopStartRadius[l] > 2.0 * loop.MeanRadius))
      {
        ++holes;
        continue;
      }
      if (loopStartNode[l] < 0)
      {
        result.Warnings.push_back("open end at " + FormatPoint(loop.Centre) +
          " touches no internal Voronoi vertex; ignored");
        continue;
      }
      EndNode end;
      end.Node = loopStartNode[l];
      end.Endpoint.Kind = EndpointKind::OpenEnd;
      end.Endpoint.Position = loop.Centre;
      end.Endpoint.Radius = loop.MeanRadius;
      end.PrependPosition = true;
      ends.push_back(end);
    }
    if (holes > 0)
    {
      result.Warnings.push_back(std::to_string(holes) +
        " boundary loop(s) taken for holes in the wall, not vessel ends (not planar, or much "
        "smaller than the lumen behind them)");
    }
    if (!wall.Loops.empty() && ends.size() == 1)
    {
      return Fail(result,
        "surface has a single open end and no other: give seeds for the "
        "other end(s)");
    }
    if (ends.empty())
    {
      // Closed surface: tips of the long branches of the Voronoi graph's largest component.
      std::vector<int> component(graph.Size(), -1);
      int largest = -1, largestSize = 0;
      for (int s = 0, label = 0; s < graph.Size(); ++s)
      {
        if (component[s] >= 0)
        {
          continue;
        }
        std::vector<int> stack{ s };
        component[s] = label;
        int size = 0;
        while (!stack.empty())
        {
          const int u = stack.back();
          stack.pop_back();
          ++size;
          for (int k = graph.Offsets[u]; k < graph.Offsets[u + 1]; ++k)
          {
            if (component[graph.Neighbours[k]] < 0)
            {
              component[graph.Neighbours[k]] = label;
              stack.push_back(graph.Neighbours[k]);
            }
          }
        }
        if (size > largestSize)
        {
          largestSize = size;
          largest = label;
        }
        ++label;
      }
      int root = -1;
      for (int i = 0; i < graph.Size(); ++i)
      {
        if (component[i] == largest && (root < 0 || graph.Radii[i] > graph.Radii[root]))
        {
          root = i;
        }
      }
      auto farthest = [&graph](const ShortestPaths& sp)
      {
        int best = -1;
        for (int i = 0; i < graph.Size(); ++i)
        {
          if (std::isfinite(sp.Cost[i]) && (best < 0 || sp.Cost[i] > sp.Cost[best]))
          {
            best = i;
          }
        }
        return best;
      };
      const int tipA = farthest(Dijkstra(graph, { root }, Weight::Length));
      const ShortestPaths fromA = Dijkstra(graph, { tipA }, Weight::Length);
      const int tipB = farthest(fromA);
      const std::vector<int> trunk = Backtrace(fromA, tipB);
      double trunkMaxRadius = 0.0;
      for (int v : trunk)
      {
        trunkMaxRadius = std::max(trunkMaxRadius, graph.Radii[v]);
      }
      const double k = options.BranchLengthToRadius;
      if (!(fromA.Cost[tipB] >= k * trunkMaxRadius))
      {
        std::ostringstream m;
        m << "closed surface has no elongated part: its longest internal path (" << fromA.Cost[tipB]
          << " mm) is shorter than " << k << " times its largest inscribed radius ("
          << trunkMaxRadius << " mm); a sphere or a blob, not a vessel";
        return Fail(result, m.str());
      }
      // Tips and the path from each towards the vessels already found (tip first).
      std::vector<std::vector<int>> tipPaths;
      tipPaths.push_back(trunk);
      tipPaths.push_back(std::vector<int>(trunk.rbegin(), trunk.rend()));
      std::vector<int> sources = trunk;
      std::vector<double> trunkRadii;
      for (int v : trunk)
      {
        trunkRadii.push_back(graph.Radii[v]);
      }
      std::sort(trunkRadii.begin(), trunkRadii.end());
      const double stopRadius = trunkRadii[trunkRadii.size() / 10];
      int rejected = 0;
      // Distances to the vessels found so far, updated as each branch is added.
      ShortestPaths sp = Dijkstra(graph, sources, Weight::Length);
      for (int iteration = 0; iteration < 64; ++iteration)
      {
        const int tip = farthest(sp);
        if (tip < 0 || !(sp.Cost[tip] >= k * stopRadius))
        {
          break;
        }
        std::vector<int> branch = Backtrace(sp, tip);
        // Length beyond the junction's sphere over the largest radius beyond it: the junction
        // region of a bifurcation is wide and says nothing about the branch itself.
        const int junction = branch.front();
        const double junctionRadius = graph.Radii[junction];
        double maxRadius = 0.0;
        for (int v : branch)
        {
          if (Distance(graph.Centres[v], graph.Centres[junction]) > junctionRadius)
          {
            maxRadius = std::max(maxRadius, graph.Radii[v]);
          }
        }
        const double length = sp.Cost[tip] - junctionRadius;
        if (maxRadius >= 0.25 * junctionRadius && length >= k * maxRadius)
        {
          tipPaths.push_back(std::vector<int>(branch.rbegin(), branch.rend()));
        }
        else
        {
          ++rejected;
        }
        AddSources(graph, sp, branch, Weight::Length);
      }
      if (rejected > 0)
      {
        std::ostringstream m;
        m << rejected << " short branch(es) of the Voronoi graph (shorter than " << k
          << " inscribed radii: bumps, an aneurysm dome) not taken for vessels";
        result.Warnings.push_back(m.str());
      }
      for (const auto& path : tipPaths)
      {
        // Trim: the centre of the last sphere on the way in that, enlarged, contains the tip.
        const Point3& tipPosition = graph.Centres[path.front()];
        std::size_t keep = 0;
        for (std::size_t m = 0; m < path.size(); ++m)
        {
          if (Distance(graph.Centres[path[m]], tipPosition) <=
            options.EndTrimFactor * graph.Radii[path[m]])
          {
            keep = m;
          }
        }
        EndNode end;
        end.Node = path[keep];
        end.Endpoint.Kind = EndpointKind::VoronoiTip;
        end.Endpoint.Position = graph.Centres[end.Node];
        end.Endpoint.Radius = graph.Radii[end.Node];
        ends.push_back(end);
      }
    }
    // The inlet: the largest end.
    std::size_t inlet = 0;
    for (std::size_t i = 1; i < ends.size(); ++i)
    {
      if (ends[i].Endpoint.Radius > ends[inlet].Endpoint.Radius)
      {
        inlet = i;
      }
    }
    if (!ends.empty())
    {
      std::rotate(ends.begin(),
        ends.begin() + static_cast<std::ptrdiff_t>(inlet),
        ends.begin() + static_cast<std::ptrdiff_t>(inlet) + 1);
      ends[0].Endpoint.Inlet = true;
    }
  }
  for (const auto& end : ends)
  {
    result.Endpoints.push_back(end.Endpoint);
  }
  result.Times.Endpoints = Seconds(clock);
  if (ends.size() < 2)
  {
    return Fail(result, "fewer than two vessel ends found: give seeds");
  }

  // 5. Minimal paths of the integral of 1/R from the inlet to every outlet.
  clock = std::chrono::steady_clock::now();
  for (double& r : graph.Radii)
  {
    r = std::max(r, 1e-9 * wall.Diagonal);
  }
  const ShortestPaths fromInlet = Dijkstra(graph, { ends[0].Node }, Weight::LengthOverRadius);
  std::vector<std::vector<Point3>> rawPaths;
  std::vector<int> rawOutlets;
  std::vector<double> pathRadii;
  for (std::size_t e = 1; e < ends.size(); ++e)
  {
    if (!std::isfinite(fromInlet.Cost[ends[e].Node]))
    {
      result.Warnings.push_back("outlet at " + FormatPoint(ends[e].Endpoint.Position) +
        " cannot be reached from the inlet through the lumen; no centerline to it");
      continue;
    }
    std::vector<Point3> path;
    if (ends[0].PrependPosition)
    {
      path.push_back(ends[0].Endpoint.Position);
    }
    for (int v : Backtrace(fromInlet, ends[e].Node))
    {
      path.push_back(graph.Centres[v]);
      pathRadii.push_back(graph.Radii[v]);
    }
    if (ends[e].PrependPosition)
    {
      path.push_back(ends[e].Endpoint.Position);
    }
    if (Length(path) <= 0.0 || path.size() < 2)
    {
      result.Warnings.push_back("outlet at " + FormatPoint(ends[e].Endpoint.Position) +
        " coincides with the inlet; no centerline to it");
      continue;
    }
    rawPaths.push_back(std::move(path));
    rawOutlets.push_back(static_cast<int>(e));
  }
  result.Times.Paths = Seconds(clock);
  if (rawPaths.empty())
  {
    return Fail(result, "no outlet can be reached from the inlet through the lumen");
  }

  // 6. Resample, smooth, re-centre, resample; radius and frames.
  clock = std::chrono::steady_clock::now();
  std::sort(pathRadii.begin(), pathRadii.end());
  const double medianRadius = pathRadii[pathRadii.size() / 2];
  const double step = options.Step > 0 ? options.Step : 0.05 * medianRadius;
  result.Step = step;
  WallDistance distance(wall.Surface);
  const EdgeTriangles edgeTriangles = BuildEdgeTriangles(wall.Surface);
  std::vector<PathSamples> paths;
  for (std::size_t p = 0; p < rawPaths.size(); ++p)
  {
    std::vector<Point3> points = Resample(rawPaths[p], step);
    Smooth(points, 0.5 * medianRadius / step);
    if (options.Recenter && points.size() > 2)
    {
      // Centroids of the lumen's cross-sections every quarter radius, weighted by their
      // roundness, and a smoothing spline through them (fixed at open ends, free at the tips
      // of a closed surface, whose position comes from the Voronoi graph). Twice: the second
      // time the planes are normal to the re-centred line.
      const std::size_t half =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.5 * medianRadius / step)));
      const std::size_t erosion =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.25 * medianRadius / step)));
      const bool fixFirst = ends[0].PrependPosition;
      const bool fixLast = ends[static_cast<std::size_t>(rawOutlets[p])].PrependPosition;
      // Two smoothing splines (continuous functionals: integral of w |x - c|^2 + ell^(2k)
      // |x^(k)|^2 over the arc length, the sums scaled by the step so that the result does not
      // depend on it): a stiff one of second order (half a radius), which bridges the runs of
      // sections that are not trusted with a cubic that depends on the trusted sections on
      // either side only, and a light one of third order (a quarter radius) through the
      // centroids where they are trusted and the bridge elsewhere, which keeps curvature and
      // torsion up to the ends.
      // Sections every tenth of a radius (or every sample).
      const std::size_t stride =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(0.1 * medianRadius / step)));
      const double lambdaBridge =
        std::pow(BridgeLength * medianRadius / step, 4.0) / static_cast<double>(stride);
      const double lambdaLine =
        std::pow(SplineLength * medianRadius / step, 6.0) / static_cast<double>(stride);
      std::vector<double> eroding(points.size(), 1.0);
      for (int pass = 0; pass < 2; ++pass)
      {
        std::vector<Point3> targets(points.size(), Point3{ { 0, 0, 0 } });
        std::vector<double> weights(points.size(), 0.0);
        for (std::size_t i = stride; i + 1 < points.size(); i += stride)
        {
          const std::size_t lo = i > half ? i - half : 0;
          const std::size_t hi = std::min(points.size() - 1, i + half);
          const Point3 t = Normalized(Sub(points[hi], points[lo]));
          if (Norm(t) < 0.5)
          {
            eroding[i] = 0.0;
            continue;
          }
          const double reach = 6.0 * medianRadius;
          const Section s = CutSection(
            distance, edgeTriangles, points[i], t, reach, 2.0 * 3.14159265358979323846 * reach);
          weights[i] = SectionWeight(s, points[i]);
          if (weights[i] > 0)
          {
            // The section's width against the inscribed sphere at its centroid.
            bool centroidInside = true;
            Point3 closest;
            const double inscribed = distance.Query(s.Centroid, centroidInside, closest);
            weights[i] *= WidthWeight(s, centroidInside ? inscribed : 0.0);
          }
          targets[i] = s.Centroid;
          // Sections running out through an open end are not trusted but do not make their
          // neighbours suspect.
          eroding[i] = s.Kind == SectionKind::Escaped ? 1.0 : weights[i];
        }
        // A section within a quarter radius of one that is not trusted is not trusted more
        // than it (a soft erosion): an isolated round-looking section in a bifurcation region,
        // or the first ones past it, already deformed, would pull the line towards the other
        // vessel.
        for (std::size_t i = 1; i + 1 < points.size(); ++i)
        {
          const std::size_t lo = std::max<std::size_t>(1, i > erosion ? i - erosion : 0);
          const std::size_t hi = std::min(points.size() - 2, i + erosion);
          for (std::size_t j = lo; j <= hi; ++j)
          {
            weights[i] = std::min(weights[i], eroding[j]);
          }
        }
        if (!(std::accumulate(weights.begin(), weights.end(), 0.0) > 0))
        {
          break;
        }
        std::vector<Point3> bridge(points);
        SmoothingSpline(bridge, targets, weights, 2, lambdaBridge, fixFirst, fixLast);
        for (std::size_t i = 0; i < points.size(); ++i)
        {
          targets[i] = Add(Scale(targets[i], weights[i]), Scale(bridge[i], 1.0 - weights[i]));
        }
        // The light spline sees the samples that were cut only (the others would pull it
        // towards the stiff bridge, which straightens at the ends).
        std::vector<double> cut(points.size(), 0.0);
        for (std::size_t i = stride; i + 1 < points.size(); i += stride)
        {
          cut[i] = 1.0;
        }
        points = bridge;
        SmoothingSpline(points, targets, cut, 3, lambdaLine, fixFirst, fixLast);
      }
      points = Resample(points, step);
    }
    PathSamples samplesOut;
    samplesOut.Points = points;
    samplesOut.Outlet = rawOutlets[p];
    samplesOut.Radius.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      bool inside = true;
      Point3 closest;
      samplesOut.Radius[i] = distance.Query(points[i], inside, closest);
    }
    samplesOut.Frames = ComputeCurveFrames(points, medianRadius);
    paths.push_back(std::move(samplesOut));
  }
  for (auto& end : result.Endpoints)
  {
    end.Reached = end.Inlet;
  }
  for (const auto& path : paths)
  {
    result.Endpoints[path.Outlet].Reached = true;
  }
  result.Times.Smoothing = Seconds(clock);

  // 7. Branches: split where the centerlines of different outlets separate by more than the
  // local inscribed radius.
  clock = std::chrono::steady_clock::now();
  const std::size_t npaths = paths.size();
  // separation[i][j]: first sample index of i (and j) where they are more than one radius apart.
  std::vector<std::vector<std::size_t>> separation(npaths, std::vector<std::size_t>(npaths, 0));
  auto separate = [&](std::size_t i, std::size_t j)
  {
    const auto& a = paths[i];
    const auto& b = paths[j];
    const std::size_t window = static_cast<std::size_t>(std::ceil(4.0 * medianRadius / step)) + 2;
    for (std::size_t k = 0; k < a.Points.size(); ++k)
    {
      const std::size_t lo = k > window ? k - window : 0;
      const std::size_t hi = std::min(b.Points.size() - 1, k + window);
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t m = lo; m <= hi && lo < b.Points.size(); ++m)
      {
        d = std::min(d, Distance(a.Points[k], b.Points[m]));
      }
      if (d > a.Radius[k])
      {
        return k;
      }
    }
    return a.Points.size() - 1;
  };
  for (std::size_t i = 0; i < npaths; ++i)
  {
    for (std::size_t j = i + 1; j < npaths; ++j)
    {
      separation[i][j] = separation[j][i] = std::min(separate(i, j), separate(j, i));
    }
  }
  PointArrays branchArrays;
  auto branchId = MakeIntArray(VesselArrays::BranchId);
  auto parentId = MakeIntArray(VesselArrays::ParentBranchId);
  auto startBif = MakeIntArray(VesselArrays::StartBifurcationId);
  auto endBif = MakeIntArray(VesselArrays::EndBifurcationId);
  auto endpointId = MakeIntArray(VesselArrays::EndpointId);
  std::function<void(std::vector<std::size_t>, std::size_t, int, int)> build =
    [&](std::vector<std::size_t> group, std::size_t from, int parent, int bifurcation)
  {
    const int id = static_cast<int>(branchId->GetNumberOfTuples());
    const auto& first = paths[group[0]];
    if (group.size() == 1)
    {
      if (first.Points.size() - from < 2)
      {
        result.Warnings.push_back("the centerline to outlet " +
          FormatPoint(result.Endpoints[first.Outlet].Position) +
          " ends where it leaves the others; no branch of its own");
        return;
      }
      branchArrays.Add(first, from, first.Points.size() - 1);
      branchId->InsertNextValue(id);
      parentId->InsertNextValue(parent);
      startBif->InsertNextValue(bifurcation);
      endBif->InsertNextValue(-1);
      endpointId->InsertNextValue(first.Outlet);
      return;
    }
    std::size_t split = std::numeric_limits<std::size_t>::max();
    for (std::size_t a = 0; a < group.size(); ++a)
    {
      for (std::size_t b = a + 1; b < group.size(); ++b)
      {
        split = std::min(split, separation[group[a]][group[b]]);
      }
    }
    split = std::max(split, from + 1);
    split = std::min(split, first.Points.size() - 1);
    const int bif = static_cast<int>(result.Bifurcations.size());
    Point3 centre{ { 0, 0, 0 } };
    for (std::size_t g : group)
    {
      centre = Add(centre, paths[g].Points[std::min(split, paths[g].Points.size() - 1)]);
    }
    result.Bifurcations.push_back(Scale(centre, 1.0 / static_cast<double>(group.size())));
    branchArrays.Add(first, from, split);
    branchId->InsertNextValue(id);
    parentId->InsertNextValue(parent);
    startBif->InsertNextValue(bifurcation);
    endBif->InsertNextValue(bif);
    endpointId->InsertNextValue(-1);
    // Children: paths that stay together beyond the split go on as one group.
    std::vector<std::size_t> label(group.size());
    std::iota(label.begin(), label.end(), 0);
    std::function<std::size_t(std::size_t)> findRoot = [&](std::size_t x)
    { return label[x] == x ? x : (label[x] = findRoot(label[x])); };
    for (std::size_t a = 0; a < group.size(); ++a)
    {
      for (std::size_t b = a + 1; b < group.size(); ++b)
      {
        if (separation[group[a]][group[b]] > split)
        {
          label[findRoot(a)] = findRoot(b);
        }
      }
    }
    std::vector<std::vector<std::size_t>> children;
    std::vector<std::size_t> rootOf;
    for (std::size_t a = 0; a < group.size(); ++a)
    {
      const std::size_t r = findRoot(a);
      auto it = std::find(rootOf.begin(), rootOf.end(), r);
      if (it == rootOf.end())
      {
        rootOf.push_back(r);
        children.push_back({ group[a] });
      }
      else
      {
        children[static_cast<std::size_t>(it - rootOf.begin())].push_back(group[a]);
      }
    }
    for (auto& child : children)
    {
      build(child, split, id, bif);
    }
  };
  std::vector<std::size_t> all(npaths);
  std::iota(all.begin(), all.end(), 0);
  build(all, 0, -1, -1);
  result.Branches = branchArrays.Build();
  result.Branches->GetCellData()->AddArray(branchId);
  result.Branches->GetCellData()->AddArray(parentId);
  result.Branches->GetCellData()->AddArray(startBif);
  result.Branches->GetCellData()->AddArray(endBif);
  result.Branches->GetCellData()->AddArray(endpointId);
  vtkNew<vtkDoubleArray> bifurcationPoints;
  bifurcationPoints->SetName(VesselArrays::BifurcationPoints);
  bifurcationPoints->SetNumberOfComponents(3);
  for (const auto& b : result.Bifurcations)
  {
    bifurcationPoints->InsertNextTuple(b.data());
  }
  result.Branches->GetFieldData()->AddArray(bifurcationPoints);

  PointArrays pathArrays;
  auto centerlineId = MakeIntArray(VesselArrays::CenterlineId);
  for (const auto& path : paths)
  {
    pathArrays.Add(path, 0, path.Points.size() - 1);
    centerlineId->InsertNextValue(path.Outlet);
  }
  result.Paths = pathArrays.Build();
  result.Paths->GetCellData()->AddArray(centerlineId);
  result.Times.Branches = Seconds(clock);
  result.Ok = true;
  return result;
}

} // namespace bender
