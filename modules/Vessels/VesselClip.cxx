#include "VesselClip.h"

#include "ArrayVector.h"
#include "BenderErrors.h"
#include "MeshTopology.h"
#include "VesselArrayNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <sstream>

namespace bender
{
namespace
{
using vessel_detail::Cross;
using vessel_detail::Distance;
using vessel_detail::Dot;
using vessel_detail::Lerp;
using vessel_detail::Norm;
using vessel_detail::Sub;
using vessel_detail::Unit;
using vessel_detail::V3;
using Tri = std::array<std::int64_t, 3>;

std::string Format(const V3& p)
{
  std::ostringstream s;
  s.precision(4);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

/// A centerline walked from a vessel end inwards: positions, arc length, inscribed radius.
struct Profile
{
  std::vector<V3> X;
  std::vector<double> S;
  std::vector<double> R;
  bool AtBifurcation = false;    ///< X[0] is a bifurcation (cell data of the branches)
  bool EndAtBifurcation = false; ///< X.back() is a bifurcation

  double Length() const { return S.empty() ? 0.0 : S.back(); }
  /// Position and radius at arc length s (clamped).
  V3 At(double s, double* radius = nullptr) const
  {
    s = std::clamp(s, 0.0, this->Length());
    auto it = std::upper_bound(S.begin(), S.end(), s);
    std::size_t i = it == S.begin() ? 0 : static_cast<std::size_t>(it - S.begin()) - 1;
    if (i + 1 >= S.size())
    {
      if (radius)
      {
        *radius = R.back();
      }
      return X.back();
    }
    const double t = S[i + 1] > S[i] ? (s - S[i]) / (S[i + 1] - S[i]) : 0.0;
    if (radius)
    {
      *radius = R[i] + t * (R[i + 1] - R[i]);
    }
    return Lerp(X[i], X[i + 1], t);
  }
  /// Unit tangent pointing inwards (away from the end) at s, over a window of one radius.
  V3 Tangent(double s) const
  {
    double r = 0;
    this->At(s, &r);
    const double h = std::max(0.5 * r, 1e-9);
    V3 t = Sub(this->At(s + h), this->At(s - h));
    if (Norm(t) == 0.0)
    {
      t = Sub(X.back(), X.front());
    }
    return Unit(t);
  }
};

struct EndGroup
{
  V3 Position;
  double Radius = 0;
  Profile Longest;
  std::vector<Profile> Profiles;
};

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
      p.AtBifurcation = startBifurcation->GetTuple1(cell) >= 0;
    }
    if (endBifurcation && endBifurcation->GetNumberOfTuples() > cell)
    {
      p.EndAtBifurcation = endBifurcation->GetTuple1(cell) >= 0;
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
      if (!p.X.empty() && Distance(x, p.X.back()) == 0.0)
      {
        continue;
      }
      p.S.push_back(p.X.empty() ? 0.0 : p.S.back() + Distance(x, p.X.back()));
      p.X.push_back(x);
      p.R.push_back(r);
    }
    if (p.X.size() >= 2)
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
  q.AtBifurcation = p.EndAtBifurcation;
  q.EndAtBifurcation = p.AtBifurcation;
  q.X.assign(p.X.rbegin(), p.X.rend());
  q.R.assign(p.R.rbegin(), p.R.rend());
  for (std::size_t i = 0; i < q.X.size(); ++i)
  {
    q.S.push_back(i == 0 ? 0.0 : q.S.back() + Distance(q.X[i], q.X[i - 1]));
  }
  return q;
}

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
        Distance(candidates[i].X[0], candidates[j].X[0]) <=
          0.25 * std::min(candidates[i].R[0], candidates[j].R[0]))
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
      bifurcation = bifurcation || candidates[k].AtBifurcation;
    }
    for (std::size_t a = 0; a < m.size() && !bifurcation; ++a)
    {
      for (std::size_t b = a + 1; b < m.size() && !bifurcation; ++b)
      {
        const Profile& p = candidates[m[a]];
        const Profile& q = candidates[m[b]];
        const double w = std::min({ p.R[0], p.Length(), q.Length() });
        bifurcation = Dot(Sub(p.At(w), p.X[0]), Sub(q.At(w), q.X[0])) < 0.0;
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
      for (const V3& x : lines[l].X)
      {
        if (Distance(x, first.X[0]) <= first.R[0])
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
    g.Position = first.X[0];
    g.Radius = first.R[0];
    for (std::size_t k : m)
    {
      g.Profiles.push_back(candidates[k]);
      if (candidates[k].Length() > g.Longest.Length())
      {
        g.Longest = candidates[k];
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
  const double whole = median(p.R);
  std::vector<double> near;
  for (std::size_t i = 0; i < p.X.size() && p.S[i] <= std::min(0.5 * p.Length(), 4.0 * whole); ++i)
  {
    near.push_back(p.R[i]);
  }
  const double typical = near.empty() ? whole : median(near);
  const double r0 = std::max(p.R[0], typical);
  const double start = std::min(r0, 0.5 * p.Length());
  const double limit = std::max(start, std::min(0.5 * p.Length(), 10.0 * r0));
  double best = start, bestVariation = std::numeric_limits<double>::infinity();
  double firstSettled = -1.0;
  for (std::size_t i = 0; i < p.X.size(); ++i)
  {
    if (p.S[i] < start)
    {
      continue;
    }
    if (p.S[i] > limit)
    {
      break;
    }
    const double r = p.R[i];
    double variation = 0.0;
    for (std::size_t j = i; j < p.X.size() && p.S[j] <= p.S[i] + 2.0 * r; ++j)
    {
      variation = std::max(variation, std::abs(p.R[j] - r));
    }
    // The direction has settled too: the tangent turns by less than 5 degrees over the window
    // (a closed end's centerline veers towards the end's corner or tip).
    const V3 t0 = p.Tangent(p.S[i]);
    const V3 t1 = p.Tangent(std::min(p.S[i] + 2.0 * r, p.Length()));
    const bool straight = Dot(t0, t1) >= std::cos(5.0 * M_PI / 180.0);
    if (variation <= 0.1 * r && straight)
    {
      return p.S[i];
    }
    if (variation <= 0.1 * r && firstSettled < 0)
    {
      firstSettled = p.S[i];
    }
    if (variation / r < bestVariation)
    {
      bestVariation = variation / r;
      best = p.S[i];
    }
  }
  return firstSettled >= 0 ? firstSettled : best;
}

struct Mesh
{
  std::vector<V3> X;
  std::vector<Tri> T;
};

/// Cuts the mesh by the plane (c, n) within the ball (c, rho); removes the side f > 0 beyond
/// the ring. False (mesh unchanged) when the ring is not closed around the vessel.
bool CutOnce(Mesh& mesh,
  const V3& c,
  const V3& n,
  double inscribed,
  double rho,
  std::vector<std::int64_t>& rimOut)
{
  const std::size_t nv = mesh.X.size();
  std::vector<V3> X = mesh.X;
  std::vector<double> f(nv);
  auto computeF = [&]()
  {
    for (std::size_t v = 0; v < nv; ++v)
    {
      f[v] = Dot(Sub(X[v], c), n);
    }
  };
  computeF();
  // Crossing triangles within the ball, and their component nearest c.
  auto crossingRing = [&](std::vector<std::size_t>& ring)
  {
    ring.clear();
    std::vector<std::size_t> crossing;
    std::vector<double> nearness;
    for (std::size_t t = 0; t < mesh.T.size(); ++t)
    {
      const Tri& tri = mesh.T[t];
      bool pos = false, neg = false;
      for (std::int64_t v : tri)
      {
        (f[v] > 0 ? pos : neg) = true;
      }
      if (!pos || !neg)
      {
        continue;
      }
      // The segment's points: on edges (pos, neg).
      double worst = 0.0;
      V3 mid{ { 0, 0, 0 } };
      int count = 0;
      for (int k = 0; k < 3; ++k)
      {
        const std::int64_t a = tri[k], b = tri[(k + 1) % 3];
        if ((f[a] > 0) == (f[b] > 0))
        {
          continue;
        }
        const double t0 = f[a] / (f[a] - f[b]);
        const V3 p = Lerp(X[a], X[b], t0);
        worst = std::max(worst, Distance(p, c));
        for (int e = 0; e < 3; ++e)
        {
          mid[e] += p[e];
        }
        ++count;
      }
      if (worst <= rho)
      {
        crossing.push_back(t);
        nearness.push_back(Distance({ { mid[0] / count, mid[1] / count, mid[2] / count } }, c));
      }
    }
    if (crossing.empty())
    {
      return;
    }
    // Components through shared edges.
    std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> edgeTris;
    for (std::size_t k = 0; k < crossing.size(); ++k)
    {
      const Tri& tri = mesh.T[crossing[k]];
      for (int e = 0; e < 3; ++e)
      {
        edgeTris[{ std::min(tri[e], tri[(e + 1) % 3]), std::max(tri[e], tri[(e + 1) % 3]) }]
          .push_back(k);
      }
    }
    UnionFind uf(crossing.size());
    for (const auto& [edge, ts] : edgeTris)
    {
      for (std::size_t k = 1; k < ts.size(); ++k)
      {
        uf.Join(ts[0], ts[k]);
      }
    }
    std::size_t best = 0;
    for (std::size_t k = 1; k < crossing.size(); ++k)
    {
      if (nearness[k] < nearness[best])
      {
        best = k;
      }
    }
    const std::size_t root = uf.Find(best);
    for (std::size_t k = 0; k < crossing.size(); ++k)
    {
      if (uf.Find(k) == root)
      {
        ring.push_back(crossing[k]);
      }
    }
  };
  std::vector<std::size_t> ring;
  crossingRing(ring);
  if (ring.empty())
  {
    return false;
  }
  // Snap the ring's vertices that lie very near the plane onto it (no sliver at the rim).
  {
    double h = 0.0;
    int edges = 0;
    for (std::size_t t : ring)
    {
      for (int k = 0; k < 3; ++k)
      {
        h += Distance(X[mesh.T[t][k]], X[mesh.T[t][(k + 1) % 3]]);
        ++edges;
      }
    }
    h /= edges;
    bool snapped = false;
    for (std::size_t t : ring)
    {
      for (std::int64_t v : mesh.T[t])
      {
        if (f[v] != 0.0 && std::abs(f[v]) < 0.2 * h)
        {
          for (int a = 0; a < 3; ++a)
          {
            X[v][a] -= f[v] * n[a];
          }
          f[v] = 0.0;
          snapped = true;
        }
      }
    }
    if (snapped)
    {
      computeF();
      for (std::size_t t : ring)
      {
        for (std::int64_t v : mesh.T[t])
        {
          if (std::abs(f[v]) < 1e-12 * std::max(1.0, h))
          {
            f[v] = 0.0;
          }
        }
      }
      crossingRing(ring);
      if (ring.empty())
      {
        return false;
      }
    }
  }
  // The part beyond the ring: positive vertices reachable from the ring's over positive edges.
  std::vector<std::vector<std::int64_t>> adjacency(nv);
  std::vector<std::vector<std::size_t>> vertexTris(nv);
  for (std::size_t t = 0; t < mesh.T.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      adjacency[mesh.T[t][k]].push_back(mesh.T[t][(k + 1) % 3]);
      adjacency[mesh.T[t][(k + 1) % 3]].push_back(mesh.T[t][k]);
      vertexTris[mesh.T[t][k]].push_back(t);
    }
  }
  std::vector<char> removed(nv, 0);
  std::queue<std::int64_t> queue;
  for (std::size_t t : ring)
  {
    for (std::int64_t v : mesh.T[t])
    {
      if (f[v] > 0 && !removed[v])
      {
        removed[v] = 1;
        queue.push(v);
      }
    }
  }
  while (!queue.empty())
  {
    const std::int64_t v = queue.front();
    queue.pop();
    for (std::int64_t w : adjacency[v])
    {
      if (f[w] > 0 && !removed[w])
      {
        removed[w] = 1;
        queue.push(w);
      }
    }
  }
  std::vector<char> inRing(mesh.T.size(), 0);
  for (std::size_t t : ring)
  {
    inRing[t] = 1;
  }
  double removedArea = 0.0, keptArea = 0.0;
  for (std::size_t t = 0; t < mesh.T.size(); ++t)
  {
    const Tri& tri = mesh.T[t];
    bool touchesRemoved = false, hasNeg = false;
    for (std::int64_t v : tri)
    {
      touchesRemoved = touchesRemoved || removed[v];
      hasNeg = hasNeg || f[v] <= 0;
    }
    if (touchesRemoved && hasNeg && !inRing[t])
    {
      return false; // the part beyond leaks past the ring: not closed around the vessel
    }
    const double area = 0.5 * Norm(Cross(Sub(X[tri[1]], X[tri[0]]), Sub(X[tri[2]], X[tri[0]])));
    (touchesRemoved ? removedArea : keptArea) += area;
  }
  if (removedArea >= keptArea)
  {
    return false;
  }
  // Rebuild: cut points on (neg, pos) edges of the ring (the neg vertex itself when on the
  // plane), kept polygons triangulated.
  std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> cutPoint;
  auto cut = [&](std::int64_t a, std::int64_t b) -> std::int64_t
  {
    // a kept (f <= 0), b removed (f > 0)
    if (f[a] == 0.0)
    {
      return a;
    }
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = cutPoint.find(key);
    if (it != cutPoint.end())
    {
      return it->second;
    }
    const double t0 = f[a] / (f[a] - f[b]);
    V3 p = Lerp(X[a], X[b], t0);
    const double off = Dot(Sub(p, c), n);
    for (int e = 0; e < 3; ++e)
    {
      p[e] -= off * n[e];
    }
    X.push_back(p);
    const auto id = static_cast<std::int64_t>(X.size()) - 1;
    cutPoint.emplace(key, id);
    return id;
  };
  std::vector<Tri> T;
  std::set<std::int64_t> onPlane;
  for (std::size_t t = 0; t < mesh.T.size(); ++t)
  {
    const Tri& tri = mesh.T[t];
    if (!inRing[t])
    {
      if (!(removed[tri[0]] || removed[tri[1]] || removed[tri[2]]))
      {
        T.push_back(tri);
      }
      continue;
    }
    std::vector<std::int64_t> poly;
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = tri[k], b = tri[(k + 1) % 3];
      if (f[a] <= 0)
      {
        poly.push_back(a);
        if (f[a] == 0.0)
        {
          onPlane.insert(a);
        }
      }
      if ((f[a] <= 0) != (f[b] <= 0))
      {
        const std::int64_t p = f[a] <= 0 ? cut(a, b) : cut(b, a);
        onPlane.insert(p);
        poly.push_back(p);
      }
    }
    poly.erase(std::unique(poly.begin(), poly.end()), poly.end());
    while (poly.size() > 1 && poly.front() == poly.back())
    {
      poly.pop_back();
    }
    if (poly.size() == 3)
    {
      T.push_back({ { poly[0], poly[1], poly[2] } });
    }
    else if (poly.size() == 4)
    {
      // The shorter diagonal.
      if (Distance(X[poly[0]], X[poly[2]]) <= Distance(X[poly[1]], X[poly[3]]))
      {
        T.push_back({ { poly[0], poly[1], poly[2] } });
        T.push_back({ { poly[0], poly[2], poly[3] } });
      }
      else
      {
        T.push_back({ { poly[1], poly[2], poly[3] } });
        T.push_back({ { poly[1], poly[3], poly[0] } });
      }
    }
  }
  // The new rim: a closed boundary loop on the plane around c.
  std::vector<std::int64_t> flat;
  for (const Tri& t : T)
  {
    flat.insert(flat.end(), t.begin(), t.end());
  }
  const double tolerance = 1e-9 * std::max(1.0, inscribed);
  bool found = false;
  for (const BoundaryChain& chain : BoundaryLoops(flat, static_cast<std::int64_t>(X.size())))
  {
    bool planar = chain.closed && chain.vertices.size() >= 3;
    V3 mean{ { 0, 0, 0 } };
    for (std::int64_t v : chain.vertices)
    {
      planar = planar && std::abs(Dot(Sub(X[v], c), n)) <= tolerance;
      for (int e = 0; e < 3; ++e)
      {
        mean[e] += X[v][e] / static_cast<double>(chain.vertices.size());
      }
    }
    if (planar && Distance(mean, c) <= inscribed)
    {
      if (found)
      {
        return false; // two loops: ambiguous
      }
      found = true;
      rimOut.assign(chain.vertices.begin(), chain.vertices.end());
    }
  }
  if (!found)
  {
    return false;
  }
  mesh.X = std::move(X);
  mesh.T = std::move(T);
  return true;
}

bool Cut(Mesh& mesh, const V3& c, const V3& n, double inscribed, std::vector<std::int64_t>& rim)
{
  for (const double factor : { 1.5, 2.2, 3.0, 4.0 })
  {
    if (CutOnce(mesh, c, n, inscribed, factor * inscribed, rim))
    {
      return true;
    }
  }
  return false;
}

/// Removes unused points and keeps the largest edge-connected component; maps rim ids.
void Compact(Mesh& mesh, std::vector<ClippedEnd>& ends, std::vector<std::string>& warnings)
{
  std::vector<std::int64_t> flat;
  for (const Tri& t : mesh.T)
  {
    flat.insert(flat.end(), t.begin(), t.end());
  }
  std::size_t count = 0;
  const std::vector<std::int64_t> component = TriangleComponents(flat, count);
  std::vector<std::size_t> size(count, 0);
  for (std::int64_t k : component)
  {
    ++size[static_cast<std::size_t>(k)];
  }
  const auto largest =
    static_cast<std::int64_t>(std::max_element(size.begin(), size.end()) - size.begin());
  if (count > 1)
  {
    warnings.push_back(std::to_string(count - 1) +
      " piece(s) of the surface not connected to the vessel were dropped");
  }
  std::vector<std::int64_t> map(mesh.X.size(), -1);
  Mesh out;
  for (std::size_t t = 0; t < mesh.T.size(); ++t)
  {
    if (component[t] != largest)
    {
      continue;
    }
    Tri tri;
    for (int k = 0; k < 3; ++k)
    {
      std::int64_t& m = map[mesh.T[t][k]];
      if (m < 0)
      {
        m = static_cast<std::int64_t>(out.X.size());
        out.X.push_back(mesh.X[mesh.T[t][k]]);
      }
      tri[k] = m;
    }
    out.T.push_back(tri);
  }
  for (ClippedEnd& end : ends)
  {
    for (long long& v : end.Rim)
    {
      v = map[v];
    }
  }
  mesh = std::move(out);
}
} // namespace

std::vector<CenterlineEnd> FindCenterlineEnds(vtkPolyData* centerlines)
{
  std::vector<CenterlineEnd> ends;
  for (const EndGroup& g : EndGroups(centerlines))
  {
    ends.push_back({ g.Position, g.Radius });
  }
  return ends;
}

namespace
{
Profile ProfileOf(const CenterlineEndPath& path)
{
  Profile p;
  p.X = path.Points;
  p.S = path.ArcLengths;
  p.R = path.Radii;
  return p;
}
} // namespace

std::vector<CenterlineEndPath> FindCenterlineEndPaths(vtkPolyData* centerlines)
{
  std::vector<CenterlineEndPath> paths;
  for (const EndGroup& g : EndGroups(centerlines))
  {
    CenterlineEndPath path;
    path.Position = g.Position;
    path.Radius = g.Radius;
    path.Points = g.Longest.X;
    path.ArcLengths = g.Longest.S;
    path.Radii = g.Longest.R;
    path.DefaultDistance = SettledDistance(g.Longest);
    path.MaximumDistance = 0.5 * g.Longest.Length();
    paths.push_back(std::move(path));
  }
  return paths;
}

ClipPlane ClipPlaneAt(const CenterlineEndPath& path, double distance)
{
  ClipPlane plane;
  if (path.Points.size() < 2 || path.ArcLengths.size() != path.Points.size() ||
    path.Radii.size() != path.Points.size())
  {
    return plane;
  }
  const Profile p = ProfileOf(path);
  const double s = std::clamp(std::isfinite(distance) ? distance : 0.0, 0.0, p.Length());
  plane.Centre = p.At(s, &plane.Radius);
  const V3 t = p.Tangent(s);
  plane.Normal = { { -t[0], -t[1], -t[2] } };
  return plane;
}

double NearestDistanceOnPath(const CenterlineEndPath& path, const ClipPoint& point)
{
  double best = 0.0, bestD = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < path.Points.size() && i + 1 < path.ArcLengths.size(); ++i)
  {
    if (path.ArcLengths[i] > path.MaximumDistance)
    {
      break;
    }
    const V3 d = Sub(path.Points[i + 1], path.Points[i]);
    const double dd = Dot(d, d);
    const double t = dd > 0 ? std::clamp(Dot(Sub(point, path.Points[i]), d) / dd, 0.0, 1.0) : 0.0;
    const double distance = Distance(Lerp(path.Points[i], path.Points[i + 1], t), point);
    if (distance < bestD)
    {
      bestD = distance;
      best = path.ArcLengths[i] + t * (path.ArcLengths[i + 1] - path.ArcLengths[i]);
    }
  }
  return std::clamp(best, 0.0, path.MaximumDistance);
}

ClipResult ClipVesselEnds(vtkPolyData* surface,
  vtkPolyData* centerlines,
  const ClipOptions& options)
{
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    throw InputError("the surface is empty");
  }
  Mesh mesh;
  mesh.X.resize(static_cast<std::size_t>(surface->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    surface->GetPoint(i, mesh.X[i].data());
    if (!std::isfinite(mesh.X[i][0]) || !std::isfinite(mesh.X[i][1]) ||
      !std::isfinite(mesh.X[i][2]))
    {
      throw InputError("the surface has non-finite (NaN or infinite) point coordinates");
    }
  }
  {
    const std::vector<std::int64_t> flat = CollectTriangles(surface);
    for (std::size_t t = 0; t + 2 < flat.size(); t += 3)
    {
      if (flat[t] != flat[t + 1] && flat[t + 1] != flat[t + 2] && flat[t] != flat[t + 2])
      {
        mesh.T.push_back({ { flat[t], flat[t + 1], flat[t + 2] } });
      }
    }
  }
  if (mesh.T.empty())
  {
    throw InputError("the surface has no triangles");
  }
  const std::vector<EndGroup> groups = EndGroups(centerlines);

  // What to cut at each end: (end group, distance, user chosen).
  struct Plan
  {
    std::size_t Group;
    const Profile* Along;
    double Distance;
    bool User;
  };
  std::vector<Plan> plans;
  for (std::size_t g = 0; g < groups.size(); ++g)
  {
    plans.push_back({ g, &groups[g].Longest, SettledDistance(groups[g].Longest), false });
  }
  for (const ClipEndRequest& request : options.Ends)
  {
    const V3 q = request.Position;
    if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2]))
    {
      throw InputError("a clip position is not finite");
    }
    std::size_t best = 0;
    double bestS = 0.0;
    const Profile* along = nullptr;
    if (request.Distance >= 0)
    {
      for (std::size_t g = 1; g < groups.size(); ++g)
      {
        if (Distance(groups[g].Position, q) < Distance(groups[best].Position, q))
        {
          best = g;
        }
      }
      along = &groups[best].Longest;
      bestS = request.Distance;
      if (bestS > 0.5 * along->Length())
      {
        throw InputError("the clip distance " + std::to_string(request.Distance) + " at the end " +
          Format(groups[best].Position) + " is more than half the centerline's length (" +
          std::to_string(along->Length()) + ")");
      }
    }
    else
    {
      // The nearest centerline point over every end's profiles, within half a profile.
      double bestD = std::numeric_limits<double>::infinity();
      for (std::size_t g = 0; g < groups.size(); ++g)
      {
        for (const Profile& p : groups[g].Profiles)
        {
          for (std::size_t i = 0; i < p.X.size() && p.S[i] <= 0.5 * p.Length(); ++i)
          {
            const double d = Distance(p.X[i], q);
            if (d < bestD)
            {
              bestD = d;
              best = g;
              bestS = p.S[i];
              along = &p;
            }
          }
        }
      }
      double r = 0;
      along->At(bestS, &r);
      if (bestD > 3.0 * r)
      {
        throw InputError("the clip position " + Format(q) +
          " is not on a vessel: the nearest centerline point is " + std::to_string(bestD) +
          " away (radius " + std::to_string(r) + ")");
      }
    }
    if (plans[best].User)
    {
      throw InputError(
        "two clip positions choose the same vessel end " + Format(groups[best].Position));
    }
    plans[best] = { best, along, bestS, true };
  }

  ClipResult result;
  for (const Plan& plan : plans)
  {
    const Profile& p = *plan.Along;
    double s = plan.Distance;
    bool done = false;
    std::vector<std::int64_t> rim;
    V3 c{}, n{};
    double r = 0;
    for (int attempt = 0; attempt < (plan.User ? 1 : 12) && !done; ++attempt)
    {
      c = p.At(s, &r);
      const V3 t = p.Tangent(s);
      n = { { -t[0], -t[1], -t[2] } };
      done = Cut(mesh, c, n, r, rim);
      if (!done)
      {
        s += 0.25 * r; // inwards, past an oblique old rim
        if (s > 0.5 * p.Length())
        {
          break;
        }
      }
    }
    if (!done)
    {
      throw InputError("the clip plane at " + Format(c) + " (" + std::to_string(s) +
        " from the vessel end " + Format(groups[plan.Group].Position) +
        ") cuts no vessel cleanly: the cut does not close around the vessel");
    }
    ClippedEnd end;
    end.Normal = n;
    end.InscribedRadius = r;
    end.CenterlineEnd = groups[plan.Group].Position;
    end.Distance = s;
    end.UserChosen = plan.User;
    end.Rim.assign(rim.begin(), rim.end());
    result.Ends.push_back(std::move(end));
  }
  Compact(mesh, result.Ends, result.Warnings);
  // Rim measures: area and centroid of the planar polygon (fan from the first vertex).
  for (ClippedEnd& end : result.Ends)
  {
    V3 area{ { 0, 0, 0 } }, centroid{ { 0, 0, 0 } };
    double total = 0.0;
    for (std::size_t k = 1; k + 1 < end.Rim.size(); ++k)
    {
      const V3& a = mesh.X[end.Rim[0]];
      const V3& b = mesh.X[end.Rim[k]];
      const V3& cc = mesh.X[end.Rim[k + 1]];
      const V3 cr = Cross(Sub(b, a), Sub(cc, a));
      const double w = 0.5 * Dot(cr, end.Normal);
      total += w;
      for (int e = 0; e < 3; ++e)
      {
        area[e] += 0.5 * cr[e];
        centroid[e] += w * (a[e] + b[e] + cc[e]) / 3.0;
      }
    }
    end.Area = std::abs(total);
    end.Radius = std::sqrt(end.Area / M_PI);
    for (int e = 0; e < 3; ++e)
    {
      end.Centre[e] = total != 0.0 ? centroid[e] / total : mesh.X[end.Rim[0]][e];
    }
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const V3& x : mesh.X)
  {
    points->InsertNextPoint(x.data());
  }
  vtkNew<vtkCellArray> polys;
  for (const Tri& t : mesh.T)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    polys->InsertNextCell(3, ids);
  }
  result.Surface = vtkSmartPointer<vtkPolyData>::New();
  result.Surface->SetPoints(points);
  result.Surface->SetPolys(polys);
  return result;
}

} // namespace bender
