#include "CenterlinePasses.h"

#include "StringUtil.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace bender
{
namespace centerline
{
namespace
{

// Closed surface: the tips of the long branches of the Voronoi graph's largest component.
bool AddVoronoiTips(const Graph& graph,
  const CenterlineOptions& options,
  std::vector<EndNode>& ends,
  std::vector<std::string>& warnings,
  std::string& failure)
{
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
      for (int k = graph.offsets[u]; k < graph.offsets[u + 1]; ++k)
      {
        if (component[graph.neighbours[k]] < 0)
        {
          component[graph.neighbours[k]] = label;
          stack.push_back(graph.neighbours[k]);
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
    if (component[i] == largest && (root < 0 || graph.radii[i] > graph.radii[root]))
    {
      root = i;
    }
  }
  auto farthest = [&graph](const ShortestPaths& sp)
  {
    int best = -1;
    for (int i = 0; i < graph.Size(); ++i)
    {
      if (std::isfinite(sp.cost[i]) && (best < 0 || sp.cost[i] > sp.cost[best]))
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
    trunkMaxRadius = std::max(trunkMaxRadius, graph.radii[v]);
  }
  const double k = options.branchLengthToRadius;
  if (!(fromA.cost[tipB] >= k * trunkMaxRadius))
  {
    std::ostringstream m;
    m << "closed surface has no elongated part: its longest internal path (" << fromA.cost[tipB]
      << " mm) is shorter than " << k << " times its largest inscribed radius (" << trunkMaxRadius
      << " mm); a sphere or a blob, not a vessel";
    failure = m.str();
    return false;
  }
  // Tips and the path from each towards the vessels already found (tip first).
  std::vector<std::vector<int>> tipPaths;
  tipPaths.push_back(trunk);
  tipPaths.push_back(std::vector<int>(trunk.rbegin(), trunk.rend()));
  std::vector<int> sources = trunk;
  std::vector<double> trunkRadii;
  for (int v : trunk)
  {
    trunkRadii.push_back(graph.radii[v]);
  }
  std::sort(trunkRadii.begin(), trunkRadii.end());
  const double stopRadius = trunkRadii[trunkRadii.size() / 10];
  int rejected = 0;
  // Distances to the vessels found so far, updated as each branch is added.
  ShortestPaths sp = Dijkstra(graph, sources, Weight::Length);
  for (int iteration = 0; iteration < 64; ++iteration)
  {
    const int tip = farthest(sp);
    if (tip < 0 || !(sp.cost[tip] >= k * stopRadius))
    {
      break;
    }
    std::vector<int> branch = Backtrace(sp, tip);
    // Length beyond the junction's sphere over the largest radius beyond it: the junction
    // region of a bifurcation is wide and says nothing about the branch itself.
    const int junction = branch.front();
    const double junctionRadius = graph.radii[junction];
    double maxRadius = 0.0;
    for (int v : branch)
    {
      if (Distance(graph.centres[v], graph.centres[junction]) > junctionRadius)
      {
        maxRadius = std::max(maxRadius, graph.radii[v]);
      }
    }
    const double length = sp.cost[tip] - junctionRadius;
    // A thinner branch is a vessel when it reaches beyond the junction's sphere by more than
    // that sphere's radius: a spike of the diagram towards the wall ends at the wall.
    const bool thick = maxRadius >= 0.25 * junctionRadius;
    const bool protruding = maxRadius > 0.0 && length >= junctionRadius;
    if ((thick || protruding) && length >= k * maxRadius)
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
    warnings.push_back(m.str());
  }
  for (const auto& path : tipPaths)
  {
    // Trim: the centre of the last sphere on the way in that, enlarged, contains the tip.
    const Point3& tipPosition = graph.centres[path.front()];
    std::size_t keep = 0;
    for (std::size_t m = 0; m < path.size(); ++m)
    {
      if (Distance(graph.centres[path[m]], tipPosition) <=
        options.endTrimFactor * graph.radii[path[m]])
      {
        keep = m;
      }
    }
    EndNode end;
    end.node = path[keep];
    end.endpoint.kind = EndpointKind::VoronoiTip;
    end.endpoint.position = graph.centres[end.node];
    end.endpoint.radius = graph.radii[end.node];
    ends.push_back(end);
  }
  return true;
}

} // namespace

bool FindEndpoints(const Wall& wall,
  const VoronoiGraph& voronoi,
  const CenterlineOptions& options,
  std::vector<EndNode>& ends,
  std::vector<std::string>& warnings,
  std::string& failure)
{
  const Graph& graph = voronoi.nodes;
  const std::vector<double>& loopStartRadius = voronoi.loopStartRadius;
  const std::vector<int>& loopStartNode = voronoi.loopStartNode;
  // The largest inscribed sphere that contains x (enlarged by 5 %), else the nearest centre.
  auto nodeFor = [&graph](const Point3& x)
  {
    int best = -1, nearest = 0;
    double bestRadius = -1.0, nearestDistance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < graph.Size(); ++i)
    {
      const double d = Distance(graph.centres[i], x);
      if (d <= 1.05 * graph.radii[i] && graph.radii[i] > bestRadius)
      {
        bestRadius = graph.radii[i];
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
  if (!options.seeds.empty())
  {
    for (std::size_t s = 0; s < options.seeds.size(); ++s)
    {
      EndNode end;
      end.endpoint.kind = EndpointKind::Seed;
      end.endpoint.inlet = (s == 0);
      const Point3& seed = options.seeds[s];
      int snapped = -1;
      for (std::size_t l = 0; l < wall.loops.size(); ++l)
      {
        const auto& loop = wall.loops[l];
        if (loop.isEnd && loopStartNode[l] >= 0 &&
          Distance(seed, loop.centre) <= 1.5 * loop.meanRadius &&
          (snapped < 0 || Distance(seed, loop.centre) < Distance(seed, wall.loops[snapped].centre)))
        {
          snapped = static_cast<int>(l);
        }
      }
      if (snapped >= 0)
      {
        end.node = loopStartNode[snapped];
        end.endpoint.position = wall.loops[snapped].centre;
        end.endpoint.radius = wall.loops[snapped].meanRadius;
        end.prependPosition = true;
      }
      else
      {
        end.node = nodeFor(seed);
        end.endpoint.position = graph.centres[end.node];
        end.endpoint.radius = graph.radii[end.node];
      }
      ends.push_back(end);
    }
  }
  else
  {
    int holes = 0;
    for (std::size_t l = 0; l < wall.loops.size(); ++l)
    {
      const auto& loop = wall.loops[l];
      // A hole in the wall is flat too, but the lumen's sphere that touches its centre is much
      // larger than the hole; at a vessel end it is about the end's radius.
      if (!loop.isEnd || (loopStartNode[l] >= 0 && loopStartRadius[l] > 2.0 * loop.meanRadius))
      {
        ++holes;
        continue;
      }
      if (loopStartNode[l] < 0)
      {
        warnings.push_back("open end at " + FormatPoint(loop.centre) +
          " touches no internal Voronoi vertex; ignored");
        continue;
      }
      EndNode end;
      end.node = loopStartNode[l];
      end.endpoint.kind = EndpointKind::OpenEnd;
      end.endpoint.position = loop.centre;
      end.endpoint.radius = loop.meanRadius;
      end.prependPosition = true;
      ends.push_back(end);
    }
    if (holes > 0)
    {
      warnings.push_back(std::to_string(holes) +
        " boundary loop(s) taken for holes in the wall, not vessel ends (not planar, or much "
        "smaller than the lumen behind them)");
    }
    if (!wall.loops.empty() && ends.size() == 1)
    {
      failure = "surface has a single open end and no other: give seeds for the "
                "other end(s)";
      return false;
    }
    if (ends.empty() && !AddVoronoiTips(graph, options, ends, warnings, failure))
    {
      return false;
    }
    // The inlet: the largest end.
    std::size_t inlet = 0;
    for (std::size_t i = 1; i < ends.size(); ++i)
    {
      if (ends[i].endpoint.radius > ends[inlet].endpoint.radius)
      {
        inlet = i;
      }
    }
    if (!ends.empty())
    {
      std::rotate(ends.begin(),
        ends.begin() + static_cast<std::ptrdiff_t>(inlet),
        ends.begin() + static_cast<std::ptrdiff_t>(inlet) + 1);
      ends[0].endpoint.inlet = true;
    }
  }
  return true;
}

} // namespace centerline
} // namespace bender
