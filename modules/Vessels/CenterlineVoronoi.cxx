#include "CenterlinePasses.h"

#include "DelaunayTetrahedra.h"
#include "Vec3.h"

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

void AddSources(const Graph& g, ShortestPaths& sp, const std::vector<int>& sources, Weight weight)
{
  const int n = g.Size();
  if (sp.cost.empty())
  {
    sp.cost.assign(n, std::numeric_limits<double>::infinity());
    sp.previous.assign(n, -1);
    sp.origin.assign(n, -1);
  }
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int s : sources)
  {
    sp.cost[s] = 0.0;
    sp.previous[s] = -1;
    sp.origin[s] = s;
    queue.emplace(0.0, s);
  }
  while (!queue.empty())
  {
    const auto [cost, u] = queue.top();
    queue.pop();
    if (cost > sp.cost[u])
    {
      continue;
    }
    for (int k = g.offsets[u]; k < g.offsets[u + 1]; ++k)
    {
      const int v = g.neighbours[k];
      double w = g.lengths[k];
      if (weight == Weight::LengthOverRadius)
      {
        w *= 0.5 * (1.0 / g.radii[u] + 1.0 / g.radii[v]);
      }
      if (cost + w < sp.cost[v])
      {
        sp.cost[v] = cost + w;
        sp.previous[v] = u;
        sp.origin[v] = sp.origin[u];
        queue.emplace(sp.cost[v], v);
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
  for (int v = target; v >= 0; v = sp.previous[v])
  {
    nodes.push_back(v);
  }
  std::reverse(nodes.begin(), nodes.end());
  return nodes;
}

VoronoiGraph BuildVoronoiGraph(const Wall& wall,
  const std::vector<Point3>& samples,
  const std::vector<Point3>& sampleNormals,
  const std::vector<Tetra>& tetras,
  const std::vector<Tetra>& across)
{
  VoronoiGraph voronoi;
  Graph& graph = voronoi.nodes;
  std::vector<double> loopStartRadius(wall.loops.size(), -1.0);
  std::vector<int> loopStartNode(wall.loops.size(), -1);
  std::unordered_map<vtkIdType, int> centreToLoop;
  for (std::size_t l = 0; l < wall.loops.size(); ++l)
  {
    centreToLoop[wall.loops[l].centreSampleId] = static_cast<int>(l);
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
      if (!(radius > 0) || radius > wall.diagonal)
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
      graph.centres.push_back(centre);
      graph.radii.push_back(radius);
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
    graph.offsets.assign(graph.Size() + 1, 0);
    for (const auto& e : edges)
    {
      ++graph.offsets[e.first + 1];
      ++graph.offsets[e.second + 1];
    }
    for (int i = 0; i < graph.Size(); ++i)
    {
      graph.offsets[i + 1] += graph.offsets[i];
    }
    graph.neighbours.resize(graph.offsets.back());
    std::vector<int> fill(graph.offsets.begin(), graph.offsets.end() - 1);
    for (const auto& e : edges)
    {
      graph.neighbours[fill[e.first]++] = e.second;
      graph.neighbours[fill[e.second]++] = e.first;
    }
    graph.lengths.resize(graph.neighbours.size());
    for (int u = 0; u < graph.Size(); ++u)
    {
      for (int k = graph.offsets[u]; k < graph.offsets[u + 1]; ++k)
      {
        graph.lengths[k] = Distance(graph.centres[u], graph.centres[graph.neighbours[k]]);
      }
    }
  }
  voronoi.loopStartRadius = std::move(loopStartRadius);
  voronoi.loopStartNode = std::move(loopStartNode);
  return voronoi;
}

} // namespace centerline
} // namespace bender
