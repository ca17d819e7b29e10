#ifndef bender_CfdVerificationTubes_h
#define bender_CfdVerificationTubes_h

// The one generator of tubes: a circular tube swept along a straight or curved centreline, open
// (a vessel's wall as a scan gives it: the sweep tests' tube) or closed by flat caps and labelled
// in Bender's convention (PatchLabels.h: wall 1, the first cap "inlet" 2, the last "outlet_1" 3),
// so that the ordinary OpenFOAM case (WriteOpenFoamCase) meshes it (the CFD verification cases
// of bender-cli cfd-verify, issue 23, and the CFD tests' tubes). LPS millimetres, outward
// triangles.

#include "Vec3.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <vector>

namespace bender
{

/// A station of a tube's centreline: the centre of a ring, the unit tangent (the flow's
/// direction) and a unit vector perpendicular to it where each ring starts.
struct TubeStation
{
  Vec3 centre;
  Vec3 tangent;
  Vec3 normal;
  double abscissa = 0.0; ///< arc length from the inlet, mm
};

/// A straight tube along +x from x = 0 (the inlet) to x = length, mm, stations every `spacing`
/// mm or closer.
std::vector<TubeStation> StraightCentreline(double length, double spacing);

/// A straight tube along +x from x = `from` (the inlet) to x = `to`, mm, in `pieces` equal
/// pieces (pieces + 1 stations; at least one piece). Each ring starts on +y.
std::vector<TubeStation> StraightCentreline(double from, double to, int pieces);

/// A planar arc in the x-y plane of centreline radius `bendRadius` turning by `angle` radians
/// towards +y, starting at the origin along +x (the inlet; the arc's centre is at
/// (0, bendRadius, 0)): a torus section. Stations every `spacing` mm of arc or closer.
std::vector<TubeStation> ArcCentreline(double bendRadius, double angle, double spacing);

/// The open tube of `radius` (mm) around the centreline, `sides` points per ring (>= 3), two
/// triangles between consecutive rings, no caps and no labels: point k of ring r is
/// r * sides + k. Throws InputError for fewer than 2 stations, radius <= 0 or sides < 3.
vtkSmartPointer<vtkPolyData> SweepOpenTube(const std::vector<TubeStation>& stations,
  double radius,
  int sides);

/// The closed tube of `radius` (mm) around the centreline, `sides` points per ring (>= 8), flat
/// caps at the first (inlet) and last (outlet_1) station (SweepOpenTube and a fan about each
/// end's centre), labelled wall / inlet / outlet_1. Throws InputError for fewer than 2 stations,
/// radius <= 0 or sides < 8.
vtkSmartPointer<vtkPolyData> SweepClosedTube(const std::vector<TubeStation>& stations,
  double radius,
  int sides);

} // namespace bender

#endif
