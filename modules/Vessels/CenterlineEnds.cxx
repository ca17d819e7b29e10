#include "VesselClipPasses.h"

#include "BenderErrors.h"
#include "VesselArrayNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace bender
{
namespace clip
{
namespace
{

std::vector<Profile> Polylines(vtkPolyData* centerlines, std::string& problem)
{
  std::vector<Profile> lines;
  vtkDataArray* radius = centerlines
    ? centerlines->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius)
    : nullptr;
  if (!centerlines || !centerlines->GetLines() || centerlines->GetNumberOfLines() == 0)
  {
    problem = "the centerlines have no polyline";
    return {};
  }
  if (!radius || radius->GetNumberOfTuples() != centerlines->GetNumberOfPoints())
  {
    problem = std::string("the centerlines have no point array ") +
      VesselArrays::MaximumInscribedSphereRadius;
    return {};
  }
  vtkCellArray* cells = centerlines->GetLines();
  vtkIdType npts;
  const vtkIdType* pts;
  // Branches (ComputeCenterlines' Branches output) say which of their ends are bifurcations.
  vtkDataArray* startBifurcation =
    centerlines->GetCellData()->GetArray(VesselArrays::StartBifurcationId);
  vtkDataArray* endBifurcation =
    centerlines->GetCellData()->GetArray(VesselArrays::EndBifurcationId);
  const vtkIdType firstLine = centerlines->GetNumberOfVerts();
  vtkIdType cell = firstLine;
  for (cells->InitTraversal(); cells->GetNextCell(npts, pts); ++cell)
  {
    Profile p;
    if (startBifurcation && startBifurcation->GetNumberOfTuples() > cell)
    {
      p.atBifurcation = startBifurcation->GetTuple1(cell) >= 0;
    }
    if (endBifurcation && endBifurcation->GetNumberOfTuples() > cell)
    {
      p.endAtBifurcation = endBifurcation->GetTuple1(cell) >= 0;
    }
    for (vtkIdType k = 0; k < npts; ++k)
    {
      V3 x;
      centerlines->GetPoint(pts[k], x.data());
      const double r = radius->GetTuple1(pts[k]);
      if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]) ||
        !std::isfinite(r) || r <= 0)
      {
        problem = "the centerlines have a non-finite point or a radius <= 0";
        return {};
      }
      if (!p.x.empty() && Distance(x, p.x.back()) == 0.0)
      {
        continue;
      }
      p.s.push_back(p.x.empty() ? 0.0 : p.s.back() + Distance(x, p.x.back()));
      p.x.push_back(x);
      p.r.push_back(r);
    }
    if (p.x.size() >= 2)
    {
      lines.push_back(std::move(p));
    }
  }
  if (lines.empty())
  {
    problem = "the centerlines have no polyline of two points or more";
  }
  return lines;
}

Profile Reversed(const Profile& p)
{
  Profile q;
  q.atBifurcation = p.endAtBifurcation;
  q.endAtBifurcation = p.atBifurcation;
  q.x.assign(p.x.rbegin(), p.x.rend());
  q.r.assign(p.r.rbegin(), p.r.rend());
  for (std::size_t i = 0; i < q.x.size(); ++i)
  {
    q.s.push_back(i == 0 ? 0.0 : q.s.back() + Distance(q.x[i], q.x[i - 1]));
  }
  return q;
}
} // namespace

std::vector<EndGroup> EndGroups(vtkPolyData* centerlines)
{
  std::string problem;
  const std::vector<Profile> lines = Polylines(centerlines, problem);
  if (lines.empty())
  {
    throw InputError(problem);
  }
  // Candidates: both ends of every polyline, walked inwards.
  std::vector<Profile> candidates;
  for (const Profile& p : lines)
  {
    candidates.push_back(p);
    candidates.push_back(Reversed(p));
  }
  std::vector<int> group(candidates.size(), -1);
  std::vector<EndGroup> groups;
  std::vector<std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    if (group[i] >= 0)
    {
      continue;
    }
    group[i] = static_cast<int>(members.size());
    members.push_back({ i });
    for (std::size_t j = i + 1; j < candidates.size(); ++j)
    {
      if (group[j] < 0 &&
        Distance(candidates[i].x[0], candidates[j].x[0]) <=
          0.25 * std::min(candidates[i].r[0], candidates[j].r[0]))
      {
        group[j] = group[i];
        members.back().push_back(j);
      }
    }
  }
  for (const auto& m : members)
  {
    bool bifurcation = false;
    for (std::size_t k : m)
    {
      bifurcation = bifurcation || candidates[k].atBifurcation;
    }
    for (std::size_t a = 0; a < m.size() && !bifurcation; ++a)
    {
      for (std::size_t b = a + 1; b < m.size() && !bifurcation; ++b)
      {
        const Profile& p = candidates[m[a]];
        const Profile& q = candidates[m[b]];
        const double w = std::min({ p.r[0], p.Length(), q.Length() });
        bifurcation = Dot(Sub(p.At(w), p.x[0]), Sub(q.At(w), q.x[0])) < 0.0;
      }
    }
    // A polyline end near another polyline that does not start or end with it (a branch
    // starting at its parent's end or on its interior) is not a vessel end either.
    const Profile& first = candidates[m[0]];
    std::set<std::size_t> own;
    for (std::size_t k : m)
    {
      own.insert(k / 2);
    }
    for (std::size_t l = 0; l < lines.size() && !bifurcation; ++l)
    {
      if (own.count(l))
      {
        continue;
      }
      for (const V3& x : lines[l].x)
      {
        if (Distance(x, first.x[0]) <= first.r[0])
        {
          bifurcation = true;
          break;
        }
      }
    }
    if (bifurcation)
    {
      continue;
    }
    EndGroup g;
    g.position = first.x[0];
    g.radius = first.r[0];
    for (std::size_t k : m)
    {
      g.profiles.push_back(candidates[k]);
      if (candidates[k].Length() > g.longest.Length())
      {
        g.longest = candidates[k];
      }
    }
    groups.push_back(std::move(g));
  }
  if (groups.empty())
  {
    throw InputError("the centerlines have no vessel end");
  }
  return groups;
}

/// The default clip distance of an end (see the header).
double SettledDistance(const Profile& p)
{
  // The vessel's typical radius near the end: the median radius within four median radii
  // of the profile (a rounded or cornered closed end has a small radius at its tip).
  auto median = [](std::vector<double> v)
  {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double whole = median(p.r);
  std::vector<double> near;
  for (std::size_t i = 0; i < p.x.size() && p.s[i] <= std::min(0.5 * p.Length(), 4.0 * whole); ++i)
  {
    near.push_back(p.r[i]);
  }
  const double typical = near.empty() ? whole : median(near);
  const double r0 = std::max(p.r[0], typical);
  const double start = std::min(r0, 0.5 * p.Length());
  const double limit = std::max(start, std::min(0.5 * p.Length(), 10.0 * r0));
  double best = start, bestVariation = std::numeric_limits<double>::infinity();
  double firstSettled = -1.0;
  for (std::size_t i = 0; i < p.x.size(); ++i)
  {
    if (p.s[i] < start)
    {
      continue;
    }
    if (p.s[i] > limit)
    {
      break;
    }
    const double r = p.r[i];
    double variation = 0.0;
    for (std::size_t j = i; j < p.x.size() && p.s[j] <= p.s[i] + 2.0 * r; ++j)
    {
      variation = std::max(variation, std::abs(p.r[j] - r));
    }
    // The direction has settled too: the tangent turns by less than 5 degrees over the window
    // (a closed end's centerline veers towards the end's corner or tip).
    const V3 t0 = p.Tangent(p.s[i]);
    const V3 t1 = p.Tangent(std::min(p.s[i] + 2.0 * r, p.Length()));
    const bool straight = Dot(t0, t1) >= std::cos(5.0 * M_PI / 180.0);
    if (variation <= 0.1 * r && straight)
    {
      return p.s[i];
    }
    if (variation <= 0.1 * r && firstSettled < 0)
    {
      firstSettled = p.s[i];
    }
    if (variation / r < bestVariation)
    {
      bestVariation = variation / r;
      best = p.s[i];
    }
  }
  return firstSettled >= 0 ? firstSettled : best;
}

} // namespace clip

using namespace clip;

std::vector<CenterlineEnd> FindCenterlineEnds(vtkPolyData* centerlines)
{
  std::vector<CenterlineEnd> ends;
  for (const EndGroup& g : EndGroups(centerlines))
  {
    ends.push_back({ g.position, g.radius });
  }
  return ends;
}

namespace
{
Profile ProfileOf(const CenterlineEndPath& path)
{
  Profile p;
  p.x = path.points;
  p.s = path.arcLengths;
  p.r = path.radii;
  return p;
}
} // namespace

std::vector<CenterlineEndPath> FindCenterlineEndPaths(vtkPolyData* centerlines)
{
  std::vector<CenterlineEndPath> paths;
  for (const EndGroup& g : EndGroups(centerlines))
  {
    CenterlineEndPath path;
    path.position = g.position;
    path.radius = g.radius;
    path.points = g.longest.x;
    path.arcLengths = g.longest.s;
    path.radii = g.longest.r;
    path.defaultDistance = SettledDistance(g.longest);
    path.maximumDistance = 0.5 * g.longest.Length();
    paths.push_back(std::move(path));
  }
  return paths;
}

ClipPlane ClipPlaneAt(const CenterlineEndPath& path, double distance)
{
  ClipPlane plane;
  if (path.points.size() < 2 || path.arcLengths.size() != path.points.size() ||
    path.radii.size() != path.points.size())
  {
    return plane;
  }
  const Profile p = ProfileOf(path);
  const double s = std::clamp(std::isfinite(distance) ? distance : 0.0, 0.0, p.Length());
  plane.centre = p.At(s, &plane.radius);
  const V3 t = p.Tangent(s);
  plane.normal = { { -t[0], -t[1], -t[2] } };
  return plane;
}

double NearestDistanceOnPath(const CenterlineEndPath& path, const ClipPoint& point)
{
  double best = 0.0, bestD = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < path.points.size() && i + 1 < path.arcLengths.size(); ++i)
  {
    if (path.arcLengths[i] > path.maximumDistance)
    {
      break;
    }
    const V3 d = Sub(path.points[i + 1], path.points[i]);
    const double dd = Dot(d, d);
    const double t = dd > 0 ? std::clamp(Dot(Sub(point, path.points[i]), d) / dd, 0.0, 1.0) : 0.0;
    const double distance = Distance(Lerp(path.points[i], path.points[i + 1], t), point);
    if (distance < bestD)
    {
      bestD = distance;
      best = path.arcLengths[i] + t * (path.arcLengths[i + 1] - path.arcLengths[i]);
    }
  }
  return std::clamp(best, 0.0, path.maximumDistance);
}

} // namespace bender
