#include "VesselClipPasses.h"

#include "MeshTopology.h"
#include "UnionFind.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <queue>
#include <set>

namespace bender
{
namespace clip
{
namespace
{

/// Cuts the mesh by the plane (c, n) within the ball (c, rho); removes the side f > 0 beyond
/// the ring. False (mesh unchanged) when the ring is not closed around the vessel.
bool CutOnce(Mesh& mesh,
  const V3& c,
  const V3& n,
  double inscribed,
  double rho,
  std::vector<std::int64_t>& rimOut)
{
  const std::size_t nv = mesh.x.size();
  std::vector<V3> X = mesh.x;
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
    for (std::size_t t = 0; t < mesh.t.size(); ++t)
    {
      const Tri& tri = mesh.t[t];
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
      const Tri& tri = mesh.t[crossing[k]];
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
        h += Distance(X[mesh.t[t][k]], X[mesh.t[t][(k + 1) % 3]]);
        ++edges;
      }
    }
    h /= edges;
    bool snapped = false;
    for (std::size_t t : ring)
    {
      for (std::int64_t v : mesh.t[t])
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
        for (std::int64_t v : mesh.t[t])
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
  for (std::size_t t = 0; t < mesh.t.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      adjacency[mesh.t[t][k]].push_back(mesh.t[t][(k + 1) % 3]);
      adjacency[mesh.t[t][(k + 1) % 3]].push_back(mesh.t[t][k]);
      vertexTris[mesh.t[t][k]].push_back(t);
    }
  }
  std::vector<char> removed(nv, 0);
  std::queue<std::int64_t> queue;
  for (std::size_t t : ring)
  {
    for (std::int64_t v : mesh.t[t])
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
  std::vector<char> inRing(mesh.t.size(), 0);
  for (std::size_t t : ring)
  {
    inRing[t] = 1;
  }
  double removedArea = 0.0, keptArea = 0.0;
  for (std::size_t t = 0; t < mesh.t.size(); ++t)
  {
    const Tri& tri = mesh.t[t];
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
  for (std::size_t t = 0; t < mesh.t.size(); ++t)
  {
    const Tri& tri = mesh.t[t];
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
  mesh.x = std::move(X);
  mesh.t = std::move(T);
  return true;
}

} // namespace

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
  for (const Tri& t : mesh.t)
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
  std::vector<std::int64_t> map(mesh.x.size(), -1);
  Mesh out;
  for (std::size_t t = 0; t < mesh.t.size(); ++t)
  {
    if (component[t] != largest)
    {
      continue;
    }
    Tri tri;
    for (int k = 0; k < 3; ++k)
    {
      std::int64_t& m = map[mesh.t[t][k]];
      if (m < 0)
      {
        m = static_cast<std::int64_t>(out.x.size());
        out.x.push_back(mesh.x[mesh.t[t][k]]);
      }
      tri[k] = m;
    }
    out.t.push_back(tri);
  }
  for (ClippedEnd& end : ends)
  {
    for (long long& v : end.rim)
    {
      v = map[v];
    }
  }
  mesh = std::move(out);
}

} // namespace clip
} // namespace bender
