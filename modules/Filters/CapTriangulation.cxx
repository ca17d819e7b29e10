#include "CapTriangulation.h"

#include "vtkCellArray.h"
#include "vtkDelaunay2D.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace bender
{
namespace cap_detail
{

namespace
{

bool InsidePolygon(const std::vector<P2>& poly, const P2& p)
{
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
  {
    const P2& a = poly[i];
    const P2& b = poly[j];
    if ((a[1] > p[1]) != (b[1] > p[1]) &&
      p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0])
    {
      inside = !inside;
    }
  }
  return inside;
}

double SegmentDistance(const P2& p, const P2& a, const P2& b)
{
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = a[0] + t * dx - p[0], ey = a[1] + t * dy - p[1];
  return std::sqrt(ex * ex + ey * ey);
}

// Orientation of c about the line a-b: 1 left, -1 right, 0 on it.
int Side(const P2& a, const P2& b, const P2& c)
{
  const double cross = Cross2(a, b, c);
  return cross > 0 ? 1 : (cross < 0 ? -1 : 0);
}

// p on the segment a-b, given that the three are collinear.
bool OnSegment(const P2& a, const P2& b, const P2& p)
{
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
    std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

// The closed segments a-b and c-d share a point.
bool SegmentsMeet(const P2& a, const P2& b, const P2& c, const P2& d)
{
  const int s1 = Side(a, b, c), s2 = Side(a, b, d), s3 = Side(c, d, a), s4 = Side(c, d, b);
  if (s1 * s2 < 0 && s3 * s4 < 0)
  {
    return true;
  }
  return (s1 == 0 && OnSegment(a, b, c)) || (s2 == 0 && OnSegment(a, b, d)) ||
    (s3 == 0 && OnSegment(c, d, a)) || (s4 == 0 && OnSegment(c, d, b));
}

std::string EdgeName(std::size_t i, std::size_t m)
{
  return std::to_string(i) + "-" + std::to_string((i + 1) % m);
}

/// Constrained Delaunay triangulation of the counter-clockwise rim polygon (ids 0..m-1) and
/// the interior points (ids m..), counter-clockwise triangles. Empty when the triangulation
/// does not cover the polygon exactly (a rim edge missing, a triangle outside, a point unused).
std::vector<Tri> ConstrainedDelaunay(const std::vector<P2>& rim, const std::vector<P2>& interior)
{
  const int m = static_cast<int>(rim.size());
  const int n = m + static_cast<int>(interior.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const P2& p : rim)
  {
    points->InsertNextPoint(p[0], p[1], 0.0);
  }
  for (const P2& p : interior)
  {
    points->InsertNextPoint(p[0], p[1], 0.0);
  }
  vtkNew<vtkPolyData> input;
  input->SetPoints(points);
  vtkNew<vtkCellArray> boundary;
  boundary->InsertNextCell(m);
  for (int i = 0; i < m; ++i)
  {
    boundary->InsertCellPoint(i);
  }
  vtkNew<vtkPolyData> source;
  source->SetPoints(points);
  source->SetPolys(boundary);
  vtkNew<vtkDelaunay2D> delaunay;
  delaunay->SetInputData(input);
  delaunay->SetSourceData(source);
  delaunay->SetTolerance(1e-12);
  delaunay->SetProjectionPlaneMode(VTK_DELAUNAY_XY_PLANE);
  delaunay->BoundingTriangulationOff();
  delaunay->Update();
  vtkPolyData* out = delaunay->GetOutput();
  std::vector<Tri> tris;
  if (out->GetNumberOfPoints() != n)
  {
    return {};
  }
  std::vector<P2> all(rim);
  all.insert(all.end(), interior.begin(), interior.end());
  std::set<std::pair<int, int>> edges;
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  vtkIdType npts;
  const vtkIdType* pts;
  vtkCellArray* polys = out->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    if (npts != 3)
    {
      return {};
    }
    Tri t{ { static_cast<int>(pts[0]), static_cast<int>(pts[1]), static_cast<int>(pts[2]) } };
    const double area = Cross2(all[t[0]], all[t[1]], all[t[2]]);
    if (area == 0.0)
    {
      return {};
    }
    if (area < 0)
    {
      std::swap(t[1], t[2]);
    }
    const P2 centroid{ { (all[t[0]][0] + all[t[1]][0] + all[t[2]][0]) / 3.0,
      (all[t[0]][1] + all[t[1]][1] + all[t[2]][1]) / 3.0 } };
    if (!InsidePolygon(rim, centroid))
    {
      return {};
    }
    for (int k = 0; k < 3; ++k)
    {
      edges.insert({ t[k], t[(k + 1) % 3] });
      used[static_cast<std::size_t>(t[k])] = 1;
    }
    tris.push_back(t);
  }
  // A triangulation of a polygon with m rim and k interior points has m + 2k - 2 triangles.
  if (static_cast<int>(tris.size()) != m + 2 * (n - m) - 2 ||
    std::count(used.begin(), used.end(), 0) != 0)
  {
    return {};
  }
  for (int i = 0; i < m; ++i)
  {
    if (!edges.count({ i, (i + 1) % m }))
    {
      return {};
    }
  }
  return tris;
}

} // namespace

double Cross2(const P2& o, const P2& a, const P2& b)
{
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

double MinAngle2(const P2& a, const P2& b, const P2& c)
{
  const P2* v[3] = { &a, &b, &c };
  double best = 180.0;
  for (int k = 0; k < 3; ++k)
  {
    const P2& o = *v[k];
    const P2& p = *v[(k + 1) % 3];
    const P2& q = *v[(k + 2) % 3];
    const double ux = p[0] - o[0], uy = p[1] - o[1], wx = q[0] - o[0], wy = q[1] - o[1];
    const double nu = std::hypot(ux, uy), nw = std::hypot(wx, wy);
    if (nu <= 0 || nw <= 0)
    {
      return 0.0;
    }
    const double cosine = std::clamp((ux * wx + uy * wy) / (nu * nw), -1.0, 1.0);
    best = std::min(best, std::acos(cosine) * 180.0 / M_PI);
  }
  return best;
}

std::string RimProblem(const std::vector<P2>& rim)
{
  const std::size_t m = rim.size();
  if (m < 3)
  {
    return "it has " + std::to_string(m) + " vertices";
  }
  double lo[2] = { rim[0][0], rim[0][1] }, hi[2] = { rim[0][0], rim[0][1] };
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < m; ++i)
  {
    const P2& a = rim[i];
    const P2& b = rim[(i + 1) % m];
    if (!std::isfinite(a[0]) || !std::isfinite(a[1]))
    {
      return "vertex " + std::to_string(i) + " is not finite in the rim's plane";
    }
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], a[k]);
      hi[k] = std::max(hi[k], a[k]);
    }
    twiceArea += a[0] * b[1] - a[1] * b[0];
  }
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const double shortest = 1e-9 * extent;
  if (!(extent > 0.0) || !std::isfinite(extent))
  {
    return "all its vertices are at one point";
  }
  for (std::size_t i = 0; i < m; ++i)
  {
    const P2& a = rim[i];
    const P2& b = rim[(i + 1) % m];
    const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (!(length > shortest))
    {
      std::ostringstream text;
      text << "edge " << EdgeName(i, m) << " is " << length << " long in a rim " << extent
           << " across (coincident vertices)";
      return text.str();
    }
  }
  if (!(std::abs(0.5 * twiceArea) > 1e-9 * extent * extent))
  {
    return "it encloses no area (its vertices lie on a line)";
  }
  for (std::size_t i = 0; i < m; ++i)
  {
    const P2& before = rim[(i + m - 1) % m];
    const P2& at = rim[i];
    const P2& after = rim[(i + 1) % m];
    const double dot =
      (before[0] - at[0]) * (after[0] - at[0]) + (before[1] - at[1]) * (after[1] - at[1]);
    if (Side(before, at, after) == 0 && dot > 0)
    {
      return "it turns straight back at vertex " + std::to_string(i);
    }
  }
  // Edges in order of their smallest x: an edge can only meet the ones that start before it
  // ends.
  std::vector<std::size_t> order(m);
  for (std::size_t i = 0; i < m; ++i)
  {
    order[i] = i;
  }
  const auto minX = [&](std::size_t i) { return std::min(rim[i][0], rim[(i + 1) % m][0]); };
  const auto maxX = [&](std::size_t i) { return std::max(rim[i][0], rim[(i + 1) % m][0]); };
  std::sort(
    order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return minX(a) < minX(b); });
  for (std::size_t u = 0; u < m; ++u)
  {
    const std::size_t i = order[u];
    for (std::size_t w = u + 1; w < m && minX(order[w]) <= maxX(i); ++w)
    {
      const std::size_t j = order[w];
      const bool neighbours = (i + 1) % m == j || (j + 1) % m == i;
      if (neighbours)
      {
        continue; // their shared vertex; a fold there is the straight-back test above
      }
      if (SegmentsMeet(rim[i], rim[(i + 1) % m], rim[j], rim[(j + 1) % m]))
      {
        return "its edges " + EdgeName(std::min(i, j), m) + " and " + EdgeName(std::max(i, j), m) +
          " cross (vertices counted along the rim from that point)";
      }
    }
  }
  return {};
}

bool TriangulateCap(const std::vector<P2>& rim, std::vector<P2>& interior, std::vector<Tri>& tris)
{
  const std::size_t m = rim.size();
  double h = 0.0;
  double lo[2] = { rim[0][0], rim[0][1] }, hi[2] = { rim[0][0], rim[0][1] };
  for (std::size_t i = 0; i < m; ++i)
  {
    h += std::hypot(rim[(i + 1) % m][0] - rim[i][0], rim[(i + 1) % m][1] - rim[i][1]);
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], rim[i][a]);
      hi[a] = std::max(hi[a], rim[i][a]);
    }
  }
  h /= static_cast<double>(m);
  for (const double margin : { 0.6, 0.9 })
  {
    // A triangular lattice of spacing h through the origin (the rim's centroid).
    interior.clear();
    const double dy = h * std::sqrt(3.0) / 2.0;
    const long j0 = static_cast<long>(std::floor(lo[1] / dy)) - 1;
    const long j1 = static_cast<long>(std::ceil(hi[1] / dy)) + 1;
    const long i0 = static_cast<long>(std::floor(lo[0] / h)) - 1;
    const long i1 = static_cast<long>(std::ceil(hi[0] / h)) + 1;
    for (long j = j0; j <= j1; ++j)
    {
      for (long i = i0; i <= i1; ++i)
      {
        const P2 p{ { (static_cast<double>(i) + ((j % 2) != 0 ? 0.5 : 0.0)) * h,
          static_cast<double>(j) * dy } };
        if (!InsidePolygon(rim, p))
        {
          continue;
        }
        bool farEnough = true;
        for (std::size_t k = 0; k < m && farEnough; ++k)
        {
          farEnough = SegmentDistance(p, rim[k], rim[(k + 1) % m]) >= margin * h;
        }
        if (farEnough)
        {
          interior.push_back(p);
        }
      }
    }
    tris = ConstrainedDelaunay(rim, interior);
    if (tris.empty())
    {
      continue;
    }
    // Laplacian smoothing of the interior points, each pass followed by a new triangulation;
    // a pass whose triangulation fails is dropped.
    for (int pass = 0; pass < 3; ++pass)
    {
      std::vector<std::set<int>> neighbours(m + interior.size());
      for (const Tri& t : tris)
      {
        for (int k = 0; k < 3; ++k)
        {
          neighbours[t[k]].insert(t[(k + 1) % 3]);
          neighbours[t[k]].insert(t[(k + 2) % 3]);
        }
      }
      std::vector<P2> moved(interior);
      for (std::size_t q = 0; q < interior.size(); ++q)
      {
        const auto& around = neighbours[m + q];
        P2 mean{ { 0, 0 } };
        for (int v : around)
        {
          const P2& p = v < static_cast<int>(m) ? rim[v] : interior[v - m];
          mean[0] += p[0] / static_cast<double>(around.size());
          mean[1] += p[1] / static_cast<double>(around.size());
        }
        if (!around.empty() && InsidePolygon(rim, mean))
        {
          moved[q] = mean;
        }
      }
      std::vector<Tri> retriangulated = ConstrainedDelaunay(rim, moved);
      if (retriangulated.empty())
      {
        break;
      }
      interior = moved;
      tris = retriangulated;
    }
    return true;
  }
  // Last resort: the rim alone.
  interior.clear();
  tris = ConstrainedDelaunay(rim, interior);
  return !tris.empty();
}

} // namespace cap_detail
} // namespace bender
