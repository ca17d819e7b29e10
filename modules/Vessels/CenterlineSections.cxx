#include "CenterlinePasses.h"

#include "Vec3.h"

#include <vtkMath.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace bender
{
namespace centerline
{
namespace
{
// The normal of triangle (a, b, c), not normalised.
void TriangleNormal(const double a[3], const double b[3], const double c[3], double n[3])
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  vtkMath::Cross(u, v, n);
}

enum class SectionKind
{
  Closed,  ///< the section closes around the point
  Escaped, ///< it runs out through an open end of the wall
  Failed   ///< too long, not around the point, a non-manifold edge, a degenerate cut
};

struct Section
{
  SectionKind kind = SectionKind::Failed;
  Point3 centroid{ { 0, 0, 0 } };
  double roundness = 0;  ///< largest over smallest distance from the centroid to the loop
  double meanRadius = 0; ///< sqrt(area / pi)
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
  const Point3& p,
  const Point3& t,
  double reach,
  double maxLength)
{
  Section section;
  vtkPolyData* wall = distance.GetWall();
  const EdgeTriangles& edges = distance.GetEdges();
  const Point3 axis = std::abs(t[0]) < 0.9 ? Point3{ { 1, 0, 0 } } : Point3{ { 0, 1, 0 } };
  const Point3 e1 = UnitVector(Cross(t, axis));
  const Point3 e2 = Cross(t, e1);
  Point3 hit;
  vtkIdType start = -1;
  if (!distance.Ray(p, e1, reach, hit, start) || start < 0)
  {
    section.kind = SectionKind::Escaped;
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
      section.kind = SectionKind::Escaped;
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
  section.kind = SectionKind::Closed;
  section.centroid = Add(p, Add(Scale(e1, cx), Scale(e2, cy)));
  section.roundness = nearest > 0 ? farthest / nearest : std::numeric_limits<double>::infinity();
  section.meanRadius = std::sqrt(0.5 * std::abs(area) / 3.14159265358979323846);
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
  if (s.kind != SectionKind::Closed || !(s.meanRadius > 0))
  {
    return 0.0;
  }
  const double round =
    std::clamp((NotRoundSection - s.roundness) / (NotRoundSection - RoundSection), 0.0, 1.0);
  const double move = Distance(s.centroid, p) / s.meanRadius;
  const double near = std::clamp((0.65 - move) / 0.2, 0.0, 1.0);
  return round * near;
}

double WidthWeight(const Section& s, double inscribed)
{
  return inscribed > 0 ? std::clamp((1.6 - s.meanRadius / inscribed) / 0.25, 0.0, 1.0) : 0.0;
}

// The edge table of WallDistance.
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

} // namespace

WallDistance::WallDistance(vtkPolyData* wall)
  : Wall(wall)
  , Edges(BuildEdgeTriangles(wall))
{
  this->Locator->SetDataSet(wall);
  this->Locator->BuildLocator();
}

double WallDistance::Query(const Point3& p, bool& inside, Point3& closest)
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
    TriangleNormal(a, b, e, n);
    inside = (x[0] - c[0]) * n[0] + (x[1] - c[1]) * n[1] + (x[2] - c[2]) * n[2] <= 0.0;
  }
  return std::sqrt(d2);
}

bool WallDistance::Ray(const Point3& p,
  const Point3& u,
  double length,
  Point3& hit,
  vtkIdType& cellId)
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

std::vector<Point3> RecentrePath(std::vector<Point3> points,
  WallDistance& distance,
  double medianRadius,
  double step,
  FixedEnds fixed)
{
  if (points.size() <= 2)
  {
    return points;
  }
  // Centroids of the lumen's cross-sections every quarter radius, weighted by their
  // roundness, and a smoothing spline through them (fixed at open ends, free at the tips
  // of a closed surface, whose position comes from the Voronoi graph). Twice: the second
  // time the planes are normal to the re-centred line.
  const std::size_t half =
    std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.5 * medianRadius / step)));
  const std::size_t erosion =
    std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.25 * medianRadius / step)));
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
      const Point3 t = UnitVector(Sub(points[hi], points[lo]));
      if (Norm(t) < 0.5)
      {
        eroding[i] = 0.0;
        continue;
      }
      const double reach = 6.0 * medianRadius;
      const Section s =
        CutSection(distance, points[i], t, reach, 2.0 * 3.14159265358979323846 * reach);
      weights[i] = SectionWeight(s, points[i]);
      if (weights[i] > 0)
      {
        // The section's width against the inscribed sphere at its centroid.
        bool centroidInside = true;
        Point3 closest;
        const double inscribed = distance.Query(s.centroid, centroidInside, closest);
        weights[i] *= WidthWeight(s, centroidInside ? inscribed : 0.0);
      }
      targets[i] = s.centroid;
      // Sections running out through an open end are not trusted but do not make their
      // neighbours suspect.
      eroding[i] = s.kind == SectionKind::Escaped ? 1.0 : weights[i];
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
    SmoothingSpline(bridge, targets, weights, SplineTerms{ 2, lambdaBridge, fixed });
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
    SmoothingSpline(points, targets, cut, SplineTerms{ 3, lambdaLine, fixed });
  }
  return Resample(points, step);
}

} // namespace centerline
} // namespace bender
