#include "CenterlineRibbonPlacement.h"

#include "VesselArrayNames.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace bender
{
namespace
{
struct Nearest
{
  std::size_t index = 0;
  double distance = std::numeric_limits<double>::infinity();
};

Nearest NearestOnLine(const std::vector<Vec3>& line, const Vec3& p)
{
  Nearest n;
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const double d = Distance(line[i], p);
    if (d < n.distance)
    {
      n.distance = d;
      n.index = i;
    }
  }
  return n;
}

std::string Format(const Vec3& p)
{
  std::ostringstream s;
  s.precision(4);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}
} // namespace

RibbonPlacement PlaceRibbonOnCenterline(vtkPolyData* paths,
  const Vec3& first,
  const Vec3& second,
  const CenterlineRibbonOptions& options)
{
  if (!paths || paths->GetNumberOfLines() == 0)
  {
    throw RibbonPlacementError("no centerline to place the ribbon on: compute the centerlines");
  }
  if (!IsFinite(first) || !IsFinite(second))
  {
    throw RibbonPlacementError("a picked point has a non-finite coordinate");
  }
  if (!(options.radiusFactor >= 1.1 && options.radiusFactor <= 10) ||
    !(options.pickToleranceFactor >= 1 && options.pickToleranceFactor <= 3))
  {
    throw RibbonPlacementError("centerline ribbon options out of range");
  }
  vtkDataArray* radius =
    paths->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius);
  vtkDataArray* tangent = paths->GetPointData()->GetArray(VesselArrays::FrenetTangent);
  vtkDataArray* normal = paths->GetPointData()->GetArray(VesselArrays::FrenetNormal);
  if (!radius || !tangent || !normal || tangent->GetNumberOfComponents() != 3 ||
    normal->GetNumberOfComponents() != 3)
  {
    throw RibbonPlacementError("the centerlines lack MaximumInscribedSphereRadius, FrenetTangent "
                               "or FrenetNormal");
  }
  // The path on which both picks are nearest, by the sum of their distances over the radius.
  struct Candidate
  {
    std::vector<vtkIdType> ids;
    std::vector<Vec3> points;
    Nearest a, b;
    double score = std::numeric_limits<double>::infinity();
  };
  Candidate best;
  vtkCellArray* lines = paths->GetLines();
  lines->InitTraversal();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  while (lines->GetNextCell(n, ids))
  {
    Candidate c;
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      paths->GetPoint(ids[i], p);
      c.ids.push_back(ids[i]);
      c.points.push_back(Vec3{ p[0], p[1], p[2] });
    }
    if (c.points.size() < 2)
    {
      continue;
    }
    c.a = NearestOnLine(c.points, first);
    c.b = NearestOnLine(c.points, second);
    c.score = c.a.distance / radius->GetComponent(c.ids[c.a.index], 0) +
      c.b.distance / radius->GetComponent(c.ids[c.b.index], 0);
    if (c.score < best.score)
    {
      best = c;
    }
  }
  if (best.points.empty())
  {
    throw RibbonPlacementError("no centerline to place the ribbon on: compute the centerlines");
  }
  for (const auto& [pick, nearest] :
    { std::make_pair(first, best.a), std::make_pair(second, best.b) })
  {
    const double r = radius->GetComponent(best.ids[nearest.index], 0);
    if (nearest.distance > options.pickToleranceFactor * r)
    {
      std::ostringstream m;
      m.precision(3);
      m << "the point picked at " << Format(pick) << " is " << nearest.distance
        << " mm from the nearest centerline, whose inscribed radius there is " << r
        << " mm: not on a vessel's wall (an aneurysm's sac?); pick on the vessel to bend";
      throw RibbonPlacementError(m.str());
    }
  }
  const std::size_t i0 = best.a.index, i1 = best.b.index;
  const std::size_t lo = std::min(i0, i1), hi = std::max(i0, i1);
  double length = 0.0, largest = 0.0;
  for (std::size_t i = lo; i <= hi; ++i)
  {
    largest = std::max(largest, radius->GetComponent(best.ids[i], 0));
    if (i > lo)
    {
      length += Distance(best.points[i], best.points[i - 1]);
    }
  }
  if (length < radius->GetComponent(best.ids[i0], 0))
  {
    throw RibbonPlacementError("the two picked points are less than one vessel radius apart "
                               "along the centerline: pick the two ends of the part to bend");
  }
  // Direction of travel from the first pick to the second.
  const double sign = i1 > i0 ? 1.0 : -1.0;
  auto tangentAt = [&](std::size_t i)
  {
    double t[3];
    tangent->GetTuple(best.ids[i], t);
    return Normalized(Vec3{ t[0], t[1], t[2] } * sign);
  };
  double n0[3];
  normal->GetTuple(best.ids[i0], n0);
  const Vec3 t0 = tangentAt(i0);
  Vec3 startNormal = Vec3{ n0[0], n0[1], n0[2] } - t0 * Dot(Vec3{ n0[0], n0[1], n0[2] }, t0);
  if (Norm(startNormal) < 0.5)
  {
    // No Frenet normal there (a straight stretch): any direction across the vessel.
    const Vec3 axis = std::abs(t0.x) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
    startNormal = axis - t0 * Dot(axis, t0);
  }
  startNormal = Normalized(startNormal);
  Vec3 carried = startNormal;
  // Carry the start normal to the end without twist (projection onto each normal plane).
  const int stepDir = i1 > i0 ? 1 : -1;
  for (std::size_t i = i0; i != i1;)
  {
    i = static_cast<std::size_t>(static_cast<long long>(i) + stepDir);
    const Vec3 t = tangentAt(i);
    carried = Normalized(carried - t * Dot(carried, t));
  }
  RibbonPlacement placement;
  placement.ribbon.start.position = best.points[i0];
  placement.ribbon.start.tangent = t0;
  placement.ribbon.start.normal = startNormal;
  placement.ribbon.end.position = best.points[i1];
  placement.ribbon.end.tangent = tangentAt(i1);
  placement.ribbon.end.normal = carried;
  placement.vesselRadius = largest;
  placement.suggestedRadius = options.radiusFactor * largest;
  return placement;
}

} // namespace bender
