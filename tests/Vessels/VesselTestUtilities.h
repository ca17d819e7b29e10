#ifndef bender_VesselTestUtilities_h
#define bender_VesselTestUtilities_h

// Analytic tube surfaces with known axes for the centerline tests.

#include "VesselCenterlines.h"

#include <vtkSmartPointer.h>

#include <functional>
#include <vector>

class vtkPolyData;

namespace bender
{
namespace test
{

using Curve = std::function<Point3(double)>;

/// A circle of radius `radius` swept along curve(t), t in [t0, t1], with `rings` rings of
/// `sides` points and a rotation-minimising frame; open at both ends.
vtkSmartPointer<vtkPolyData> SweptTube(const Curve& curve,
  double t0,
  double t1,
  int rings,
  int sides,
  double radius);

/// A Y made of three swept circles (trunk and two children meeting at the origin) as the
/// iso-surface of the union of the tubes on a grid of the given spacing; open where the tubes
/// leave the grid (the trunk's end at z = -zCut, the children's at z = +zCut).
struct Segment
{
  Point3 a, b;
  double radius;
};
vtkSmartPointer<vtkPolyData> ImplicitTubes(const std::vector<Segment>& segments,
  const double bounds[6],
  double spacing);

/// Dense samples of a curve (for distances to the true axis).
std::vector<Point3> SampleCurve(const Curve& curve, double t0, double t1, int count);

/// Distance from p to the polyline through samples.
double DistanceToPolyline(const Point3& p, const std::vector<Point3>& samples);

/// Points of all cells of a polydata.
std::vector<Point3> PointsOf(vtkPolyData* lines);

/// Largest distance from the points of `a` to the polylines of `b`.
double MaxDistanceToLines(vtkPolyData* a, vtkPolyData* b);

} // namespace test
} // namespace bender

#endif
