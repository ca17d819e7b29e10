#include "VesselCenterlines.h"

#include "CenterlinePasses.h"
#include "StringUtil.h"
#include "Vec3.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

namespace bender
{
namespace
{
double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// A centerline point on the outer side of the wall by more than this fraction of the median
// inscribed radius is outside the surface (closer to the wall, the side is a matter of the
// wall's triangles, not of the shape).
constexpr double OutsideTolerance = 0.05;
// More than this fraction of the centerline points outside (away from the paths' ends): the
// shape is not tubular (the cow: 60 of 3761). Fewer are a crease's few points where the wall's
// side is uncertain (a Y bifurcation's carina), said in a warning.
constexpr double OutsideShare = 0.01;
// The stretch at each end of a path, in median radii, that the count leaves out.
constexpr double EndReach = 1.0;

CenterlineResult Fail(CenterlineResult result, const std::string& message)
{
  result.ok = false;
  result.message = message;
  result.branches = vtkSmartPointer<vtkPolyData>::New();
  result.paths = vtkSmartPointer<vtkPolyData>::New();
  return result;
}

} // namespace

// ---- the workflow ---------------------------------------------------------------------------
CenterlineResult ComputeCenterlines(vtkPolyData* surface, const CenterlineOptions& options)
{
  using namespace centerline;
  if (!surface)
  {
    throw std::invalid_argument("ComputeCenterlines: the surface is null");
  }
  if (!(options.step >= 0) ||
    !(options.branchLengthToRadius >= 1 && options.branchLengthToRadius <= 20) ||
    !(options.endTrimFactor >= 1 && options.endTrimFactor <= 3))
  {
    throw std::invalid_argument("ComputeCenterlines: an option is out of range (Step >= 0, "
                                "BranchLengthToRadius in [1, 20], EndTrimFactor in [1, 3])");
  }
  for (const auto& seed : options.seeds)
  {
    if (!std::isfinite(seed[0]) || !std::isfinite(seed[1]) || !std::isfinite(seed[2]))
    {
      throw std::invalid_argument("ComputeCenterlines: a seed has a non-finite coordinate");
    }
  }
  if (options.seeds.size() == 1)
  {
    throw std::invalid_argument("ComputeCenterlines: give at least two seeds (the inlet first), "
                                "or none");
  }

  CenterlineResult result;
  auto clock = std::chrono::steady_clock::now();

  // 1. The wall: triangles, merged points, consistent orientation.
  Wall wall;
  std::string failure;
  if (!BuildWall(surface, wall, result.warnings, failure))
  {
    return Fail(result, failure);
  }
  std::vector<Point3> samples;
  std::vector<Point3> sampleNormals;
  DelaunaySamples(wall, samples, sampleNormals);
  result.times.preparation = Seconds(clock);

  // 2. Delaunay tetrahedralisation of the (slightly jittered, for robustness against the
  // co-spherical points of regular meshes) samples.
  clock = std::chrono::steady_clock::now();
  {
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> jitter(-1.0, 1.0);
    const double amplitude = 1e-4 * wall.meanEdge;
    for (auto& p : samples)
    {
      for (int c = 0; c < 3; ++c)
      {
        p[c] += amplitude * jitter(random);
      }
    }
  }
  result.numberOfDelaunayPoints = static_cast<int>(samples.size());
  std::vector<Tetra> tetras, across;
  std::string delaunayError;
  std::string delaunayWarning;
  if (!Tetrahedralise(samples, tetras, across, delaunayError, delaunayWarning))
  {
    result.times.delaunay = Seconds(clock);
    return Fail(result, "surface points cannot be tetrahedralised (" + delaunayError + ")");
  }
  if (!delaunayWarning.empty())
  {
    result.warnings.push_back(delaunayWarning);
  }
  result.times.delaunay = Seconds(clock);

  // 3. Internal Voronoi vertices: circumcentres on the inner side of all four vertex normals.
  clock = std::chrono::steady_clock::now();
  VoronoiGraph voronoi = BuildVoronoiGraph(wall, samples, sampleNormals, tetras, across);
  Graph& graph = voronoi.nodes;
  result.numberOfVoronoiVertices = graph.Size();
  if (graph.Size() < 2)
  {
    result.times.voronoi = Seconds(clock);
    return Fail(result,
      "surface has no interior: no internal Voronoi vertex (is it a closed or "
      "open tube of triangles?)");
  }
  result.times.voronoi = Seconds(clock);

  // 4. Endpoints: nodes of the graph, with their positions.
  clock = std::chrono::steady_clock::now();
  std::vector<EndNode> ends;
  if (!FindEndpoints(wall, voronoi, options, ends, result.warnings, failure))
  {
    return Fail(result, failure);
  }
  for (const auto& end : ends)
  {
    result.endpoints.push_back(end.endpoint);
  }
  result.times.endpoints = Seconds(clock);
  if (ends.size() < 2)
  {
    return Fail(result, "fewer than two vessel ends found: give seeds");
  }

  // 5. Minimal paths of the integral of 1/R from the inlet to every outlet.
  clock = std::chrono::steady_clock::now();
  for (double& r : graph.radii)
  {
    r = std::max(r, 1e-9 * wall.diagonal);
  }
  const ShortestPaths fromInlet = Dijkstra(graph, { ends[0].node }, Weight::LengthOverRadius);
  std::vector<std::vector<Point3>> rawPaths;
  std::vector<int> rawOutlets;
  std::vector<double> pathRadii;
  for (std::size_t e = 1; e < ends.size(); ++e)
  {
    if (!std::isfinite(fromInlet.cost[ends[e].node]))
    {
      result.warnings.push_back("outlet at " + FormatPoint(ends[e].endpoint.position) +
        " cannot be reached from the inlet through the lumen; no centerline to it");
      continue;
    }
    std::vector<Point3> path;
    if (ends[0].prependPosition)
    {
      path.push_back(ends[0].endpoint.position);
    }
    for (int v : Backtrace(fromInlet, ends[e].node))
    {
      path.push_back(graph.centres[v]);
      pathRadii.push_back(graph.radii[v]);
    }
    if (ends[e].prependPosition)
    {
      path.push_back(ends[e].endpoint.position);
    }
    if (Length(path) <= 0.0 || path.size() < 2)
    {
      result.warnings.push_back("outlet at " + FormatPoint(ends[e].endpoint.position) +
        " coincides with the inlet; no centerline to it");
      continue;
    }
    rawPaths.push_back(std::move(path));
    rawOutlets.push_back(static_cast<int>(e));
  }
  result.times.paths = Seconds(clock);
  if (rawPaths.empty())
  {
    return Fail(result, "no outlet can be reached from the inlet through the lumen");
  }

  // 6. Resample, smooth, re-centre, resample; radius and frames.
  clock = std::chrono::steady_clock::now();
  std::sort(pathRadii.begin(), pathRadii.end());
  const double medianRadius = pathRadii[pathRadii.size() / 2];
  const double step = options.step > 0 ? options.step : 0.05 * medianRadius;
  result.step = step;
  WallDistance distance(wall.surface);
  std::vector<PathSamples> paths;
  std::size_t outside = 0, sampled = 0;
  for (std::size_t p = 0; p < rawPaths.size(); ++p)
  {
    std::vector<Point3> points = Resample(rawPaths[p], step);
    Smooth(points, 0.5 * medianRadius / step);
    if (options.recenter)
    {
      // Fixed at open ends, free at the tips of a closed surface, whose position comes from
      // the Voronoi graph.
      points = RecentrePath(std::move(points),
        distance,
        medianRadius,
        step,
        FixedEnds{
          ends[0].prependPosition, ends[static_cast<std::size_t>(rawOutlets[p])].prependPosition });
    }
    PathSamples samplesOut;
    samplesOut.points = points;
    samplesOut.outlet = rawOutlets[p];
    samplesOut.radius.resize(points.size());
    // Within EndReach median radii of a path's ends the centerline meets an opening or a tip,
    // where the wall's side says nothing of the shape (an oblique cut, a cap): not counted.
    const std::size_t reach = static_cast<std::size_t>(std::ceil(EndReach * medianRadius / step));
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      bool inside = true;
      Point3 closest;
      samplesOut.radius[i] = distance.Query(points[i], inside, closest);
      if (i < reach || i + reach >= points.size())
      {
        continue;
      }
      ++sampled;
      if (!inside && samplesOut.radius[i] > OutsideTolerance * medianRadius)
      {
        ++outside;
      }
    }
    samplesOut.frames = ComputeCurveFrames(points, medianRadius);
    paths.push_back(std::move(samplesOut));
  }
  for (auto& end : result.endpoints)
  {
    end.reached = end.inlet;
  }
  for (const auto& path : paths)
  {
    result.endpoints[path.outlet].reached = true;
  }
  result.times.smoothing = Seconds(clock);
  const std::string outsideCount =
    std::to_string(outside) + " of " + std::to_string(sampled) + " points outside";
  if (static_cast<double>(outside) > OutsideShare * static_cast<double>(sampled))
  {
    // A centerline outside the surface measures nothing of a lumen: the shape is no tube (a
    // closed blob, an animal), whose Voronoi graph's shortest paths and their smoothing cut
    // through its wall.
    return Fail(
      result, "the centerlines leave the surface (" + outsideCount + "): the shape is not tubular");
  }
  if (outside > 0)
  {
    result.warnings.push_back("a few centerline points lie outside the wall (" + outsideCount +
      " by more than " + FormatNumber(100.0 * OutsideTolerance) + " % of the median radius)");
  }

  // 7. Branches: split where the centerlines of different outlets separate by more than the
  // local inscribed radius.
  clock = std::chrono::steady_clock::now();
  BuildBranches(paths, medianRadius, step, result);
  result.times.branches = Seconds(clock);
  result.ok = true;
  return result;
}

} // namespace bender
