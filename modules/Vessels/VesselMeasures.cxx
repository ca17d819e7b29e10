#include "VesselMeasures.h"

#include "Vec3.h"
#include "VesselArrayNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStaticPointLocator.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace bender
{
namespace
{

int CellValue(vtkPolyData* data, const char* name, vtkIdType cell, int fallback)
{
  vtkDataArray* a = data->GetCellData()->GetArray(name);
  return a ? static_cast<int>(a->GetComponent(cell, 0)) : fallback;
}

std::vector<double> ArcLengths(const std::vector<Point3>& p)
{
  std::vector<double> s(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i)
  {
    s[i] = s[i - 1] + Norm(Sub(p[i], p[i - 1]));
  }
  return s;
}

// Direction of the polyline at its start (forward) or end, over `span` of arc length: the
// chord from the end point to the first point at least `span` away.
Point3 ChordDirection(const std::vector<Point3>& p,
  const std::vector<double>& s,
  double span,
  bool atStart)
{
  const std::size_t n = p.size();
  if (atStart)
  {
    std::size_t k = 1;
    while (k + 1 < n && s[k] - s[0] < span)
    {
      ++k;
    }
    return Normalized(Sub(p[k], p[0]));
  }
  std::size_t k = n - 2;
  while (k > 0 && s[n - 1] - s[k] < span)
  {
    --k;
  }
  return Normalized(Sub(p[n - 1], p[k]));
}

} // namespace

double AngleDegrees(const Point3& a, const Point3& b)
{
  const double na = Norm(a), nb = Norm(b);
  if (na <= 0 || nb <= 0)
  {
    return 0.0;
  }
  const double c = std::max(-1.0, std::min(1.0, Dot(a, b) / (na * nb)));
  return std::acos(c) * 180.0 / 3.14159265358979323846;
}

double EndWindow(const std::vector<Point3>& points, const std::vector<double>& radii)
{
  if (points.size() < 2 || radii.empty())
  {
    return 0.0;
  }
  double meanR = 0.0;
  for (double r : radii)
  {
    meanR += r;
  }
  meanR /= static_cast<double>(radii.size());
  return std::min(meanR, ArcLengths(points).back() / 3.0);
}

std::array<Point3, 2> EndDirections(const std::vector<Point3>& points,
  const std::vector<double>& radii)
{
  if (points.size() < 2)
  {
    return { { Point3{ { 0, 0, 0 } }, Point3{ { 0, 0, 0 } } } };
  }
  if (points.size() < 3)
  {
    const Point3 chord = Normalized(Sub(points[1], points[0]));
    return { { chord, chord } };
  }
  const auto frames = ComputeCurveFrames(points, std::max(EndWindow(points, radii), 1e-9));
  return { { frames.front().tangent, frames.back().tangent } };
}

BranchMeasures MeasureStretch(const std::vector<Point3>& p,
  const std::vector<double>& r,
  const std::vector<double>& curvatureIn)
{
  BranchMeasures m;
  if (p.size() < 2 || r.size() != p.size())
  {
    return m;
  }
  const std::vector<double> s = ArcLengths(p);
  double meanR = 0.0;
  for (double v : r)
  {
    meanR += v;
  }
  meanR /= static_cast<double>(r.size());
  // Curvature as given, else from local cubic fits over the mean radius.
  std::vector<double> curvature = curvatureIn;
  if (curvature.size() != p.size())
  {
    const auto frames = ComputeCurveFrames(p, std::max(meanR, 1e-9));
    curvature.assign(p.size(), 0.0);
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      curvature[i] = frames[i].curvature;
    }
  }
  m.length = s.back();
  m.start = p.front();
  m.end = p.back();
  m.chord = Norm(Sub(p.back(), p.front()));
  m.tortuosity = m.chord > 0 ? m.length / m.chord : 0.0;
  m.minRadius = r[0];
  m.maxRadius = r[0];
  double weightedR = 0.0, weightedK = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    if (r[i] < m.minRadius)
    {
      m.minRadius = r[i];
      m.minRadiusPosition = p[i];
      m.minRadiusAbscissa = s[i];
    }
    if (i == 0)
    {
      m.minRadiusPosition = p[0];
    }
    m.maxRadius = std::max(m.maxRadius, r[i]);
    m.maxCurvature = std::max(m.maxCurvature, curvature[i]);
    if (i > 0)
    {
      const double ds = s[i] - s[i - 1];
      weightedR += 0.5 * (r[i] + r[i - 1]) * ds;
      weightedK += 0.5 * (curvature[i] + curvature[i - 1]) * ds;
    }
  }
  m.meanRadius = m.length > 0 ? weightedR / m.length : r[0];
  m.meanCurvature = m.length > 0 ? weightedK / m.length : 0.0;
  const std::array<Point3, 2> ends = EndDirections(p, r);
  m.startTangent = ends[0];
  m.endTangent = ends[1];
  m.bendAngle = AngleDegrees(m.startTangent, m.endTangent);
  return m;
}

VesselMeasurements MeasureBranches(vtkPolyData* branches)
{
  if (!branches)
  {
    throw std::invalid_argument("MeasureBranches: the centerlines are null");
  }
  VesselMeasurements out;
  vtkDataArray* radius =
    branches->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius);
  if (!radius)
  {
    out.message = std::string("centerlines have no point data '") +
      VesselArrays::MaximumInscribedSphereRadius + "'";
    return out;
  }
  vtkCellArray* lines = branches->GetLines();
  if (!lines)
  {
    return out;
  }
  std::vector<std::vector<Point3>> allPoints;
  lines->InitTraversal();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType cell = branches->GetNumberOfVerts();
  while (lines->GetNextCell(npts, ids))
  {
    const vtkIdType cellId = cell++;
    if (npts < 2)
    {
      continue;
    }
    std::vector<Point3> p(static_cast<std::size_t>(npts));
    std::vector<double> r(p.size());
    for (vtkIdType i = 0; i < npts; ++i)
    {
      branches->GetPoint(ids[i], p[i].data());
      r[i] = radius->GetComponent(ids[i], 0);
    }
    // Curvature from the arrays when present, else from local cubic fits.
    std::vector<double> curvature;
    if (vtkDataArray* k = branches->GetPointData()->GetArray(VesselArrays::Curvature))
    {
      curvature.resize(p.size());
      for (std::size_t i = 0; i < p.size(); ++i)
      {
        curvature[i] = k->GetComponent(ids[i], 0);
      }
    }
    BranchMeasures m = MeasureStretch(p, r, curvature);
    m.branchId = CellValue(branches, VesselArrays::BranchId, cellId, static_cast<int>(cellId));
    m.parentBranchId = CellValue(branches, VesselArrays::ParentBranchId, cellId, -1);
    m.startBifurcationId = CellValue(branches, VesselArrays::StartBifurcationId, cellId, -1);
    m.endBifurcationId = CellValue(branches, VesselArrays::EndBifurcationId, cellId, -1);
    m.endpointId = CellValue(branches, VesselArrays::EndpointId, cellId, -1);
    out.branches.push_back(m);
    allPoints.push_back(p);
  }

  // Outlets under each branch, leaves first.
  std::map<int, std::size_t> byId;
  for (std::size_t i = 0; i < out.branches.size(); ++i)
  {
    byId[out.branches[i].branchId] = i;
  }
  for (std::size_t i = 0; i < out.branches.size(); ++i)
  {
    if (out.branches[i].endpointId < 0)
    {
      continue;
    }
    // Walk up to the root adding the outlet (guarding against cycles in foreign data).
    std::size_t current = i;
    for (std::size_t guard = 0; guard <= out.branches.size(); ++guard)
    {
      out.branches[current].outlets.insert(out.branches[i].endpointId);
      auto parent = byId.find(out.branches[current].parentBranchId);
      if (parent == byId.end())
      {
        break;
      }
      current = parent->second;
    }
  }

  // Bifurcations: parent's direction into it, each child's direction out of it, over twice
  // the child's mean radius.
  std::map<int, BifurcationMeasures> bifurcations;
  for (std::size_t i = 0; i < out.branches.size(); ++i)
  {
    const auto& b = out.branches[i];
    if (b.endBifurcationId >= 0)
    {
      bifurcations[b.endBifurcationId].parentBranchId = b.branchId;
    }
    if (b.startBifurcationId >= 0)
    {
      bifurcations[b.startBifurcationId].childBranchIds.push_back(b.branchId);
    }
  }
  vtkDataArray* bifPoints = branches->GetFieldData()->GetArray(VesselArrays::BifurcationPoints);
  for (auto& [id, bif] : bifurcations)
  {
    bif.id = id;
    if (bifPoints && id < bifPoints->GetNumberOfTuples() && bifPoints->GetNumberOfComponents() == 3)
    {
      bifPoints->GetTuple(id, bif.position.data());
    }
    Point3 parentDirection{ { 0, 0, 0 } };
    auto parent = byId.find(bif.parentBranchId);
    if (parent != byId.end())
    {
      const auto& p = allPoints[parent->second];
      const std::vector<double> s = ArcLengths(p);
      parentDirection = ChordDirection(p, s, 2.0 * out.branches[parent->second].meanRadius, false);
      if (bifPoints == nullptr)
      {
        bif.position = p.back();
      }
    }
    std::vector<Point3> childDirections;
    for (int child : bif.childBranchIds)
    {
      const std::size_t c = byId[child];
      const auto& p = allPoints[c];
      const std::vector<double> s = ArcLengths(p);
      const Point3 d = ChordDirection(p, s, 2.0 * out.branches[c].meanRadius, true);
      childDirections.push_back(d);
      bif.parentChildAngles.push_back(AngleDegrees(parentDirection, d));
    }
    if (childDirections.size() >= 2)
    {
      bif.childrenAngle = AngleDegrees(childDirections[0], childDirections[1]);
    }
    out.bifurcations.push_back(bif);
  }
  return out;
}

VesselComparison CompareVessels(vtkPolyData* beforeBranches, vtkPolyData* afterBranches)
{
  VesselComparison c;
  c.before = MeasureBranches(beforeBranches);
  c.after = MeasureBranches(afterBranches);
  std::vector<bool> used(c.after.branches.size(), false);
  for (std::size_t i = 0; i < c.before.branches.size(); ++i)
  {
    BranchChange change;
    change.beforeIndex = static_cast<int>(i);
    for (std::size_t j = 0; j < c.after.branches.size(); ++j)
    {
      if (!used[j] && !c.before.branches[i].outlets.empty() &&
        c.after.branches[j].outlets == c.before.branches[i].outlets)
      {
        change.afterIndex = static_cast<int>(j);
        used[j] = true;
        break;
      }
    }
    c.pairs.push_back(change);
  }
  for (std::size_t j = 0; j < c.after.branches.size(); ++j)
  {
    if (!used[j])
    {
      c.pairs.push_back({ -1, static_cast<int>(j) });
    }
  }
  return c;
}

std::vector<Point3> MatchedSeeds(vtkPolyData* beforeSurface,
  vtkPolyData* afterSurface,
  const std::vector<CenterlineEndpoint>& beforeEndpoints)
{
  if (!beforeSurface || !afterSurface || beforeSurface->GetNumberOfPoints() == 0 ||
    afterSurface->GetNumberOfPoints() == 0)
  {
    throw std::invalid_argument("MatchedSeeds: a surface is null or has no points");
  }
  std::vector<Point3> seeds;
  const bool sameIds = beforeSurface->GetNumberOfPoints() == afterSurface->GetNumberOfPoints();
  vtkNew<vtkStaticPointLocator> beforeLocator;
  beforeLocator->SetDataSet(beforeSurface);
  beforeLocator->BuildLocator();
  vtkNew<vtkIdList> near;
  for (const auto& end : beforeEndpoints)
  {
    Point3 seed = end.position;
    if (sameIds)
    {
      beforeLocator->FindPointsWithinRadius(2.0 * end.radius, end.position.data(), near);
      if (near->GetNumberOfIds() == 0)
      {
        near->InsertNextId(beforeLocator->FindClosestPoint(end.position.data()));
      }
      Point3 shift{ { 0, 0, 0 } };
      for (vtkIdType k = 0; k < near->GetNumberOfIds(); ++k)
      {
        double a[3], b[3];
        beforeSurface->GetPoint(near->GetId(k), a);
        afterSurface->GetPoint(near->GetId(k), b);
        for (int c = 0; c < 3; ++c)
        {
          shift[c] += (b[c] - a[c]) / static_cast<double>(near->GetNumberOfIds());
        }
      }
      for (int c = 0; c < 3; ++c)
      {
        seed[c] += shift[c];
      }
    }
    seeds.push_back(seed);
  }
  return seeds;
}

} // namespace bender
