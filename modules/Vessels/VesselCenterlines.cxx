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

CenterlineResult Fail(CenterlineResult result, const std::string& message)
{
  result.Ok = false;
  result.Message = message;
  result.Branches = vtkSmartPointer<vtkPolyData>::New();
  result.Paths = vtkSmartPointer<vtkPolyData>::New();
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
  if (!(options.Step >= 0) ||
    !(options.BranchLengthToRadius >= 1 && options.BranchLengthToRadius <= 20) ||
    !(options.EndTrimFactor >= 1 && options.EndTrimFactor <= 3))
  {
    throw std::invalid_argument("ComputeCenterlines: an option is out of range (Step >= 0, "
                                "BranchLengthToRadius in [1, 20], EndTrimFactor in [1, 3])");
  }
  for (const auto& seed : options.Seeds)
  {
    if (!std::isfinite(seed[0]) || !std::isfinite(seed[1]) || !std::isfinite(seed[2]))
    {
      throw std::invalid_argument("ComputeCenterlines: a seed has a non-finite coordinate");
    }
  }
  if (options.Seeds.size() == 1)
  {
    throw std::invalid_argument("ComputeCenterlines: give at least two seeds (the inlet first), "
                                "or none");
  }

  CenterlineResult result;
  auto clock = std::chrono::steady_clock::now();

  // 1. The wall: triangles, merged points, consistent orientation.
  Wall wall;
  std::string failure;
  if (!BuildWall(surface, wall, result.Warnings, failure))
  {
    return Fail(result, failure);
  }
  std::vector<Point3> samples;
  std::vector<Point3> sampleNormals;
  DelaunaySamples(wall, samples, sampleNormals);
  result.Times.Preparation = Seconds(clock);

  // 2. Delaunay tetrahedralisation of the (slightly jittered, for robustness against the
  // co-spherical points of regular meshes) samples.
  clock = std::chrono::steady_clock::now();
  {
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> jitter(-1.0, 1.0);
    const double amplitude = 1e-4 * wall.MeanEdge;
    for (auto& p : samples)
    {
      for (int c = 0; c < 3; ++c)
      {
        p[c] += amplitude * jitter(random);
      }
    }
  }
  result.NumberOfDelaunayPoints = static_cast<int>(samples.size());
  std::vector<Tetra> tetras, across;
  std::string delaunayError;
  std::string delaunayWarning;
  if (!Tetrahedralise(samples, tetras, across, delaunayError, delaunayWarning))
  {
    result.Times.Delaunay = Seconds(clock);
    return Fail(result, "surface points cannot be tetrahedralised (" + delaunayError + ")");
  }
  if (!delaunayWarning.empty())
  {
    result.Warnings.push_back(delaunayWarning);
  }
  result.Times.Delaunay = Seconds(clock);

  // 3. Internal Voronoi vertices: circumcentres on the inner side of all four vertex normals.
  clock = std::chrono::steady_clock::now();
  VoronoiGraph voronoi = BuildVoronoiGraph(wall, samples, sampleNormals, tetras, across);
  Graph& graph = voronoi.Nodes;
  result.NumberOfVoronoiVertices = graph.Size();
  if (graph.Size() < 2)
  {
    result.Times.Voronoi = Seconds(clock);
    return Fail(result,
      "surface has no interior: no internal Voronoi vertex (is it a closed or "
      "open tube of triangles?)");
  }
  result.Times.Voronoi = Seconds(clock);

  // 4. Endpoints: nodes of the graph, with their positions.
  clock = std::chrono::steady_clock::now();
  std::vector<EndNode> ends;
  if (!FindEndpoints(wall, voronoi, options, ends, result.Warnings, failure))
  {
    return Fail(result, failure);
  }
  for (const auto& end : ends)
  {
    result.Endpoints.push_back(end.Endpoint);
  }
  result.Times.Endpoints = Seconds(clock);
  if (ends.size() < 2)
  {
    return Fail(result, "fewer than two vessel ends found: give seeds");
  }

  // 5. Minimal paths of the integral of 1/R from the inlet to every outlet.
  clock = std::chrono::steady_clock::now();
  for (double& r : graph.Radii)
  {
    r = std::max(r, 1e-9 * wall.Diagonal);
  }
  const ShortestPaths fromInlet = Dijkstra(graph, { ends[0].Node }, Weight::LengthOverRadius);
  std::vector<std::vector<Point3>> rawPaths;
  std::vector<int> rawOutlets;
  std::vector<double> pathRadii;
  for (std::size_t e = 1; e < ends.size(); ++e)
  {
    if (!std::isfinite(fromInlet.Cost[ends[e].Node]))
    {
      result.Warnings.push_back("outlet at " + FormatPoint(ends[e].Endpoint.Position) +
        " cannot be reached from the inlet through the lumen; no centerline to it");
      continue;
    }
    std::vector<Point3> path;
    if (ends[0].PrependPosition)
    {
      path.push_back(ends[0].Endpoint.Position);
    }
    for (int v : Backtrace(fromInlet, ends[e].Node))
    {
      path.push_back(graph.Centres[v]);
      pathRadii.push_back(graph.Radii[v]);
    }
    if (ends[e].PrependPosition)
    {
      path.push_back(ends[e].Endpoint.Position);
    }
    if (Length(path) <= 0.0 || path.size() < 2)
    {
      result.Warnings.push_back("outlet at " + FormatPoint(ends[e].Endpoint.Position) +
        " coincides with the inlet; no centerline to it");
      continue;
    }
    rawPaths.push_back(std::move(path));
    rawOutlets.push_back(static_cast<int>(e));
  }
  result.Times.Paths = Seconds(clock);
  if (rawPaths.empty())
  {
    return Fail(result, "no outlet can be reached from the inlet through the lumen");
  }

  // 6. Resample, smooth, re-centre, resample; radius and frames.
  clock = std::chrono::steady_clock::now();
  std::sort(pathRadii.begin(), pathRadii.end());
  const double medianRadius = pathRadii[pathRadii.size() / 2];
  const double step = options.Step > 0 ? options.Step : 0.05 * medianRadius;
  result.Step = step;
  WallDistance distance(wall.Surface);
  const EdgeTriangles edgeTriangles = BuildEdgeTriangles(wall.Surface);
  std::vector<PathSamples> paths;
  for (std::size_t p = 0; p < rawPaths.size(); ++p)
  {
    std::vector<Point3> points = Resample(rawPaths[p], step);
    Smooth(points, 0.5 * medianRadius / step);
    if (options.Recenter)
    {
      // Fixed at open ends, free at the tips of a closed surface, whose position comes from
      // the Voronoi graph.
      points = RecentrePath(std::move(points),
        distance,
        edgeTriangles,
        medianRadius,
        step,
        ends[0].PrependPosition,
        ends[static_cast<std::size_t>(rawOutlets[p])].PrependPosition);
    }
    PathSamples samplesOut;
    samplesOut.Points = points;
    samplesOut.Outlet = rawOutlets[p];
    samplesOut.Radius.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      bool inside = true;
      Point3 closest;
      samplesOut.Radius[i] = distance.Query(points[i], inside, closest);
    }
    samplesOut.Frames = ComputeCurveFrames(points, medianRadius);
    paths.push_back(std::move(samplesOut));
  }
  for (auto& end : result.Endpoints)
  {
    end.Reached = end.Inlet;
  }
  for (const auto& path : paths)
  {
    result.Endpoints[path.Outlet].Reached = true;
  }
  result.Times.Smoothing = Seconds(clock);

  // 7. Branches: split where the centerlines of different outlets separate by more than the
  // local inscribed radius.
  clock = std::chrono::steady_clock::now();
  BuildBranches(paths, medianRadius, step, result);
  result.Times.Branches = Seconds(clock);
  result.Ok = true;
  return result;
}

} // namespace bender
