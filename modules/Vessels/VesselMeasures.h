#ifndef bender_VesselMeasures_h
#define bender_VesselMeasures_h

// Per-branch measurements of centerlines (the branch output of ComputeCenterlines, or any
// polylines with the same arrays) and the before/after comparison of two such sets.
// Lengths in the centerlines' unit (mm), angles in degrees, curvature in 1/mm.

#include "VesselCenterlines.h"

#include <array>
#include <set>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

struct BranchMeasures
{
  int branchId = -1;
  int parentBranchId = -1;
  int startBifurcationId = -1;
  int endBifurcationId = -1;
  int endpointId = -1;   ///< the outlet the branch ends at, -1 at a bifurcation
  std::set<int> outlets; ///< outlets reached through this branch (its identity)
  double length = 0;     ///< arc length
  double chord = 0;      ///< distance between the branch's end points
  double tortuosity = 1; ///< length / chord (1 for a straight branch)
  double maxCurvature = 0;
  double meanCurvature = 0; ///< arc-length weighted
  double bendAngle = 0;     ///< degrees between the start and end tangents
  double minRadius = 0, meanRadius = 0, maxRadius = 0;
  Point3 minRadiusPosition{ { 0, 0, 0 } };
  double minRadiusAbscissa = 0; ///< arc length from the branch's start to its narrowest point
  Point3 start{ { 0, 0, 0 } }, end{ { 0, 0, 0 } };
  Point3 startTangent{ { 0, 0, 0 } }, endTangent{ { 0, 0, 0 } };
};

struct BifurcationMeasures
{
  int id = -1;
  Point3 position{ { 0, 0, 0 } };
  int parentBranchId = -1;
  std::vector<int> childBranchIds;
  /// Angle (degrees) between the parent's direction and each child's, same order as the ids.
  std::vector<double> parentChildAngles;
  /// Angle (degrees) between the first two children's directions (the bifurcation angle).
  double childrenAngle = 0;
};

struct VesselMeasurements
{
  std::vector<BranchMeasures> branches;
  std::vector<BifurcationMeasures> bifurcations;
  /// Empty when the input had the arrays needed; otherwise says which one is missing.
  std::string message;
};

/// Angle in degrees between two directions; 0 when either is the zero vector.
double AngleDegrees(const Point3& a, const Point3& b);

///@{ The end-window rule: the one way every branch length, end tangent and bend angle is
/// measured, by MeasureBranches (the plan's table, `bender-cli measure`, the JSON) and by the
/// live measures of the branch held under the ribbon (VesselSession::MeasureHeld), so that the
/// live panel and the plan's table agree on the same stretch. The direction at each end of a
/// centerline stretch is the unit tangent at its end sample of the least-squares cubic fit over
/// one window of arc length (ComputeCurveFrames: at least seven samples), pointing from the
/// start towards the end; the window is the stretch's mean inscribed radius (the plain mean of
/// `radii`), at most a third of its length. A stretch of two samples takes its chord at both
/// ends. The bend angle is the angle between the start and end directions.
double EndWindow(const std::vector<Point3>& points, const std::vector<double>& radii);
std::array<Point3, 2> EndDirections(const std::vector<Point3>& points,
  const std::vector<double>& radii);
///@}

/// The measures of one centerline stretch: `points` from its start to its end (at least two),
/// `radii` the inscribed radius at each (mm), `curvature` at each (1/mm; empty: from local
/// cubic fits over the mean radius). Length, chord, tortuosity, radii, curvature, end tangents
/// and bend angle (the end-window rule above); ids are left at -1, outlets empty. Too few
/// points or radii of another count give the default (zero) measures.
BranchMeasures MeasureStretch(const std::vector<Point3>& points,
  const std::vector<double>& radii,
  const std::vector<double>& curvature = {});

/// Measures every polyline cell of `branches` with MeasureStretch. Needs point data
/// MaximumInscribedSphereRadius; uses Curvature when present (recomputed from the points
/// otherwise) and the cell data of ComputeCenterlines' branch output when present (each cell
/// its own branch otherwise). The directions of the branches at a bifurcation (its angles) are
/// chords over twice each branch's mean radius. Throws std::invalid_argument for null input.
VesselMeasurements MeasureBranches(vtkPolyData* branches);

struct BranchChange
{
  int beforeIndex = -1; ///< into before.branches, -1 when the branch exists only after
  int afterIndex = -1;  ///< into after.branches, -1 when the branch exists only before
};

struct VesselComparison
{
  VesselMeasurements before;
  VesselMeasurements after;
  /// Branches matched by the set of outlets they lead to (the same endpoint order must have
  /// been used for both centerline computations, e.g. with MatchedSeeds).
  std::vector<BranchChange> pairs;
};

VesselComparison CompareVessels(vtkPolyData* beforeBranches, vtkPolyData* afterBranches);

/// Seeds for computing the centerlines of `after` with the endpoints of `before` in the same
/// order: when both surfaces have the same number of points (a warp moves points, keeps ids),
/// each endpoint is moved by the mean displacement of the surface points within twice its
/// radius; otherwise (a remeshed surface) the endpoints are used as they are.
std::vector<Point3> MatchedSeeds(vtkPolyData* beforeSurface,
  vtkPolyData* afterSurface,
  const std::vector<CenterlineEndpoint>& beforeEndpoints);

} // namespace bender

#endif
