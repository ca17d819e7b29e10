#ifndef bender_VesselCenterlines_h
#define bender_VesselCenterlines_h

// Centerlines of a vessel lumen with the maximal-inscribed-sphere radius.
//
// Method (the one described by Antiga et al., IEEE TMI 2004, and VMTK's documentation; this
// is an independent implementation):
//  1. The surface's points (plus points sampled on temporary flat caps over its open ends)
//     are tetrahedralised (3D Delaunay, DelaunayTetrahedra.h). The circumcentre of a
//     tetrahedron is a vertex of the Voronoi diagram of the points; its circumradius is the
//     radius of an empty sphere.
//     Tetrahedra whose circumcentre lies inside the lumen (on the inner side of the surface
//     normals at all four of its vertices) form the internal Voronoi graph, two of them being
//     connected when they share a face.
//  2. Endpoints: the centres of the open boundary loops (the largest loop is the inlet), or on
//     a closed surface the tips of the Voronoi graph's long branches (see
//     CenterlineOptions::branchLengthToRadius), or the user's seeds.
//  3. From the inlet, Dijkstra on the Voronoi graph with the cost integral of 1/R along the
//     path gives the minimal path to every outlet, backtraced.
//  4. Each path is resampled at a fixed step and smoothed; then, twice, the lumen's
//     cross-section in the plane normal to the line is cut at every sample (the exact polygon
//     of the wall's intersection with that plane) and the line is fitted to the sections' area
//     centroids with a smoothing spline (third differences, a quarter radius). Sections that
//     are not a tube's (not round, much wider than the inscribed sphere at their centroid, or
//     whose centroid is far from the line: a bifurcation, an aneurysm's neck) weigh less, down
//     to nothing, and the line is bridged across them by a stiffer spline (second differences,
//     half a radius) through the trusted sections on either side. The centroids depend on the
//     wall only, not on where its points are, so the centerline moves with the surface and
//     hardly with its meshing. Open ends stay at their loop centres. The radius is the
//     distance to the input surface.
//  5. Tangent, normal, curvature and torsion come from local cubic fits over a window of one
//     local radius; the abscissa is the arc length from the inlet.
//  6. Branches: centerlines from different outlets share their path up to where they separate
//     by more than the local inscribed radius; there they are split into a parent branch and
//     child branches, and the split is a bifurcation.
//
// Coordinates and units are those of the input (LPS millimetres for Bender's surfaces).

#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

using Point3 = std::array<double, 3>;

struct CenterlineOptions
{
  /// Seeds (mm). Empty: endpoints found automatically. Otherwise the first seed is the inlet
  /// and the others the outlets; each snaps to the nearest open end within 1.5 loop radii,
  /// else to the largest inscribed sphere that contains it (or the nearest one).
  std::vector<Point3> seeds;
  /// Resampling step (mm), > 0; 0 (default) = 0.05 x the median inscribed radius on the paths.
  double step = 0.0;
  /// Closed surfaces: a branch of the Voronoi graph (from where it joins the vessels already
  /// found to its tip) is taken for a vessel when, beyond the inscribed sphere at the junction,
  /// it is at least this many times as long as the largest inscribed radius along it, and that
  /// radius is at least a quarter of the junction's (thinner branches are spikes of the Voronoi
  /// diagram towards the wall). Bumps measure about 1 to 2 by this rule, the elongated sac of
  /// the gmsh aneurysm 3.5, its shortest vessel 7. [1, 20], default 4.
  double branchLengthToRadius = 4.0;
  /// Closed surfaces: the centerline stops at the centre of the last inscribed sphere that,
  /// enlarged by this factor, still contains the Voronoi tip (a flat end's corner or a
  /// rounded end's centre), i.e. about one radius before the end. [1, 3], default 1.5.
  double endTrimFactor = 1.5;
  /// Place the smoothed paths on the centroids of the cross-sections (default on; off: the
  /// smoothed Voronoi paths).
  bool recenter = true;
};

enum class EndpointKind
{
  OpenEnd,    ///< centre of an open boundary loop
  VoronoiTip, ///< tip of a long branch of the Voronoi graph (closed surface)
  Seed        ///< given by the user
};

struct CenterlineEndpoint
{
  Point3 position{ { 0, 0, 0 } };
  double radius = 0.0; ///< mm: loop mean radius or inscribed radius
  EndpointKind kind = EndpointKind::OpenEnd;
  bool inlet = false;
  bool reached = false; ///< a centerline ends here (the inlet: true when any path exists)
};

struct CenterlineStageTimes
{
  double preparation = 0; ///< seconds: cleaning, normals, loops, caps
  double delaunay = 0;
  double voronoi = 0; ///< circumcentres, inside test, graph
  double endpoints = 0;
  double paths = 0;     ///< Dijkstra and backtracing
  double smoothing = 0; ///< resampling, smoothing, re-centring, frames
  double branches = 0;
};

struct CenterlineResult
{
  /// True when at least one centerline was computed. False: message says why (one line).
  bool ok = false;
  std::string message;
  /// Non-fatal remarks (an unreachable outlet, a loop taken for a hole...).
  std::vector<std::string> warnings;
  /// Branches: one polyline cell per branch, point data MaximumInscribedSphereRadius,
  /// Abscissa, FrenetTangent, FrenetNormal, Curvature, Torsion; cell data BranchId,
  /// ParentBranchId, StartBifurcationId, EndBifurcationId, EndpointId; field data
  /// BifurcationPoints. Empty (not null) on failure.
  vtkSmartPointer<vtkPolyData> branches;
  /// One polyline per reached outlet from the inlet, same point data; cell data CenterlineIds
  /// (the outlet's endpoint index). Empty (not null) on failure.
  vtkSmartPointer<vtkPolyData> paths;
  std::vector<CenterlineEndpoint> endpoints;
  std::vector<Point3> bifurcations;
  double step = 0.0; ///< the resampling step used (mm)
  CenterlineStageTimes times;
  int numberOfDelaunayPoints = 0; ///< surface samples tetrahedralised (wall and caps)
  int numberOfVoronoiVertices = 0;
};

/// Computes the centerlines of a triangulated lumen surface (polygons are triangulated;
/// lines, vertices and strips ignored). Never throws for bad geometry: a surface without
/// interior, a sphere, unreachable endpoints... give Ok = false and a one-line Message.
/// Throws std::invalid_argument only for a null surface or options out of range.
CenterlineResult ComputeCenterlines(vtkPolyData* surface, const CenterlineOptions& options = {});

/// Recomputes the point data of a polyline (frames, curvature, torsion, abscissa starting at
/// startAbscissa) from its points with local cubic fits over a window of `window` mm (at
/// least 3 samples each side). radius (optional) is copied. Used by ComputeCenterlines and by
/// the tests; exposed for callers that build their own polylines.
struct CurveSample
{
  Point3 position{ { 0, 0, 0 } };
  Point3 tangent{ { 1, 0, 0 } };
  Point3 normal{ { 0, 1, 0 } };
  double curvature = 0;
  double torsion = 0;
  double abscissa = 0;
};
std::vector<CurveSample> ComputeCurveFrames(const std::vector<Point3>& points,
  double window,
  double startAbscissa = 0.0);

} // namespace bender

#endif
