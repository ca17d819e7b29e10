#ifndef bender_CenterlinePasses_h
#define bender_CenterlinePasses_h

// The named passes of ComputeCenterlines (VesselCenterlines.h describes the method), one file
// each, in the order the workflow runs them:
//   CenterlineWall.cxx       1. the oriented wall, its boundary loops and the Delaunay samples
//   CenterlineVoronoi.cxx    2-3. the Delaunay, the internal Voronoi graph, Dijkstra on it
//   CenterlineEndpoints.cxx  4. the vessel ends: open loops, seeds or the graph's long tips
//   CenterlinePolylines.cxx  resampling, smoothing and the smoothing spline of a polyline
//   CenterlineSections.cxx   6. distance to the wall, cross-sections and the re-centring
//   CurveFrames.cxx          frames, curvature and torsion of a polyline
//   CenterlineBranches.cxx   7. branches split where the paths separate, the output arrays
//   VesselCenterlines.cxx    the workflow (and 5. the minimal paths)
// Internal to bender_vessels. Coordinates and units of the input surface.

#include "VesselCenterlines.h"

#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>
#include <vtkType.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

class vtkPolyData;

namespace bender
{
namespace centerline
{

/// a * (1 / |a|); the zero vector stays zero. The passes scale by the reciprocal where Vec3.h's
/// Normalized divides: the centerlines they write are compared bit for bit between versions.
inline Point3 UnitVector(const Point3& a)
{
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(n > 0))
  {
    return { { 0.0, 0.0, 0.0 } };
  }
  const double s = 1.0 / n;
  return { { a[0] * s, a[1] * s, a[2] * s } };
}

/// Key of the undirected edge (a, b).
inline std::uint64_t EdgeKey(vtkIdType a, vtkIdType b)
{
  const auto lo = static_cast<std::uint64_t>(a < b ? a : b);
  const auto hi = static_cast<std::uint64_t>(a < b ? b : a);
  return (hi << 32) | lo;
}

// ---- 1. the oriented wall (CenterlineWall.cxx) ----------------------------------------------
struct BoundaryLoop
{
  std::vector<vtkIdType> ids; // loop vertices in boundary-edge order
  Point3 centre{ { 0, 0, 0 } };
  Point3 capNormal{ { 0, 0, 0 } }; // outward when the wall's normals point outward
  double meanRadius = 0.0;
  bool isEnd = false;            // planar-ish: a vessel end, not a hole
  vtkIdType centreSampleId = -1; // id of the centre among the Delaunay points
};

struct Wall
{
  std::vector<Point3> points;
  std::vector<std::array<vtkIdType, 3>> triangles;
  std::vector<Point3> normals; // per point, outward, unit (zero for unused points)
  std::vector<BoundaryLoop> loops;
  double meanEdge = 0.0;
  double diagonal = 0.0;
  vtkSmartPointer<vtkPolyData> surface; // oriented outward, for distance queries
};

/// The surface's triangles with merged points, consistently oriented outward (by the signed
/// volume closed by flat fans over its loops), its point normals and boundary loops. False and
/// `failure` (one line) for a surface without a lumen; remarks go to `warnings`.
bool BuildWall(vtkPolyData* surface,
  Wall& wall,
  std::vector<std::string>& warnings,
  std::string& failure);

/// The Delaunay's points: the wall's points, then points on flat caps over every loop (so that
/// no empty sphere bulges out of an open end), each with its outward normal. Sets each loop's
/// centreSampleId.
void DelaunaySamples(Wall& wall, std::vector<Point3>& samples, std::vector<Point3>& normals);

// ---- 2-3. the Delaunay and the internal Voronoi graph (CenterlineVoronoi.cxx) ----------------
using Tetra = std::array<vtkIdType, 4>;

/// Our incremental Delaunay (DelaunayTetrahedra.h: exact predicates, three to six times faster
/// than Qhull on vessel surfaces, see bench_centerlines); Qhull, where the system has it, only
/// should the incremental one report an internal inconsistency. The points are snapped to the
/// triangulation's grid. `neighbours`: the tetrahedron across the face opposite each vertex.
/// `warning`: set when Qhull had to step in.
bool Tetrahedralise(std::vector<Point3>& points,
  std::vector<Tetra>& tets,
  std::vector<Tetra>& neighbours,
  std::string& error,
  std::string& warning);

struct Graph
{
  std::vector<Point3> centres;
  std::vector<double> radii;
  std::vector<int> offsets; // CSR
  std::vector<int> neighbours;
  std::vector<double> lengths; // of the edges, as neighbours

  int Size() const { return static_cast<int>(this->centres.size()); }
};

/// The internal Voronoi graph and, for each boundary loop, its largest sphere touching the
/// loop's centre sample (-1: none) and that sphere's node.
struct VoronoiGraph
{
  Graph nodes;
  std::vector<double> loopStartRadius;
  std::vector<int> loopStartNode;
};

/// Internal Voronoi vertices: circumcentres on the inner side of all four vertex normals, two
/// joined when their tetrahedra share a face.
VoronoiGraph BuildVoronoiGraph(const Wall& wall,
  const std::vector<Point3>& samples,
  const std::vector<Point3>& normals,
  const std::vector<Tetra>& tetras,
  const std::vector<Tetra>& across);

struct ShortestPaths
{
  std::vector<double> cost;
  std::vector<int> previous;
  std::vector<int> origin; // the source each node was reached from
};

enum class Weight
{
  Length,
  LengthOverRadius
};

/// Makes `sources` sources of sp (cost 0) and relaxes from them: on an empty sp, Dijkstra from
/// the sources; on the result of an earlier call, the same as Dijkstra from the old and the new
/// sources together (costs only decrease), for the cost of the nodes that change only.
void AddSources(const Graph& g, ShortestPaths& sp, const std::vector<int>& sources, Weight weight);
ShortestPaths Dijkstra(const Graph& g, const std::vector<int>& sources, Weight weight);
/// The nodes from the source to `target`.
std::vector<int> Backtrace(const ShortestPaths& sp, int target);

// ---- 4. endpoints (CenterlineEndpoints.cxx) --------------------------------------------------
struct EndNode
{
  int node = -1;
  CenterlineEndpoint endpoint;
  bool prependPosition = false; // the path starts/ends at endpoint.position, off the graph
};

/// The vessel ends as nodes of the graph, the inlet first: the user's seeds, else the open
/// ends, else (a closed surface) the tips of the graph's long branches. False and `failure`
/// (one line) when the ends cannot be found; remarks go to `warnings`.
bool FindEndpoints(const Wall& wall,
  const VoronoiGraph& voronoi,
  const CenterlineOptions& options,
  std::vector<EndNode>& ends,
  std::vector<std::string>& warnings,
  std::string& failure);

// ---- polylines (CenterlinePolylines.cxx) -----------------------------------------------------
double Length(const std::vector<Point3>& p);
/// Samples at abscissae 0, h, 2h, ... from the first point, and the last point.
std::vector<Point3> Resample(const std::vector<Point3>& p, double h);
/// Laplacian smoothing with fixed ends; the kernel's standard deviation is about sigmaSamples.
void Smooth(std::vector<Point3>& p, double sigmaSamples);
/// Which ends of a curve stay where they are (open ends of the surface); the others are free.
struct FixedEnds
{
  bool first = false;
  bool last = false;
};

/// The terms of a smoothing spline: the order of the differences penalised (2 or 3), their
/// weight lambda, and the ends held at their current values.
struct SplineTerms
{
  int order = 2;
  double lambda = 0.0;
  FixedEnds fixed;
};

/// Smoothing spline through weighted targets: minimises
///   sum_i w_i |x_i - c_i|^2 + lambda sum_i |order-th difference of x at i|^2   (order 2 or 3)
/// with x_0 and x_{n-1} fixed where terms.fixed says (to their current values), else free.
/// Runs of zero weight are bridged by cubic (order 2) or quintic (order 3) curves. The ends of
/// a second-difference spline straighten (its natural end condition is zero curvature), those
/// of a third-difference spline keep their curvature. The system is symmetric positive definite
/// and banded; solved by banded Gaussian elimination without pivoting.
void SmoothingSpline(std::vector<Point3>& x,
  const std::vector<Point3>& targets,
  const std::vector<double>& weights,
  const SplineTerms& terms);

// ---- 6. cross-sections and re-centring (CenterlineSections.cxx) ------------------------------
/// The triangles on either side of every edge of the wall (-1: none; an edge of three or more
/// triangles keeps its first two and is marked by a third entry of -2).
using EdgeTriangles = std::unordered_map<std::uint64_t, std::array<vtkIdType, 3>>;

/// Distance queries against the oriented wall, and its edge table (for tracing cross-sections
/// triangle by triangle).
class WallDistance
{
public:
  explicit WallDistance(vtkPolyData* wall);

  /// Unsigned distance to the wall and whether p is on the inner side of the closest triangle.
  double Query(const Point3& p, bool& inside, Point3& closest);

  /// First wall hit from p along the unit direction u within length; false when none.
  bool Ray(const Point3& p, const Point3& u, double length, Point3& hit, vtkIdType& cellId);

  vtkPolyData* GetWall() const { return this->Wall; }
  const EdgeTriangles& GetEdges() const { return this->Edges; }

private:
  vtkPolyData* Wall;
  vtkNew<vtkStaticCellLocator> Locator;
  vtkNew<vtkGenericCell> Cell;
  EdgeTriangles Edges;
};

/// The path's samples moved onto the centroids of the lumen's cross-sections (see
/// VesselCenterlines.h, step 4), resampled at `step`. The ends stay where they are when fixed.
std::vector<Point3> RecentrePath(std::vector<Point3> points,
  WallDistance& distance,
  double medianRadius,
  double step,
  FixedEnds fixed);

// ---- 7. branches (CenterlineBranches.cxx) ----------------------------------------------------
struct PathSamples
{
  std::vector<Point3> points;
  std::vector<double> radius;
  std::vector<CurveSample> frames;
  int outlet = -1;
};

/// Splits the paths into branches where they separate by more than the local inscribed radius
/// and fills result.branches, result.paths and result.bifurcations (remarks to its warnings).
void BuildBranches(const std::vector<PathSamples>& paths,
  double medianRadius,
  double step,
  CenterlineResult& result);

} // namespace centerline
} // namespace bender

#endif
