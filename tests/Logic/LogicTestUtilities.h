#ifndef bender_LogicTestUtilities_h
#define bender_LogicTestUtilities_h

#include "FlowStudy.h"
#include "WarpPlan.h"

#include <vtkSmartPointer.h>

#include <string>

class vtkPolyData;

namespace bender
{
namespace test
{

/// A closed-side open-ended tube along +x: `rings` rings of `sides` points, radius `radius`,
/// from x0 to x1, triangulated. Double points. The one tube generator's (SweepOpenTube,
/// CfdVerificationTubes.h).
vtkSmartPointer<vtkPolyData> MakeTube(double x0,
  double x1,
  double radius,
  int rings = 81,
  int sides = 32);

/// A straight ribbon along +x from (a,0,0) to (b,0,0), normal +z.
RibbonSpec StraightRibbon(double a, double b);

/// The ribbon with its end swung by `degrees` about +z around the start, tangent following.
RibbonSpec Bent(const RibbonSpec& straight, double degrees);

/// The warp of StraightRibbon(from, to) swung by `degrees` (Bent), with radius R.
WarpSpec Swing(double from, double to, double degrees, double radius);

/// MakeTube(-20, 20, 5, 41, 32) (LPS mm) prepared for CFD as it is (no clip: its open ends
/// capped, inlet and outlet, short extensions), then bent by Swing(0, 15, degrees, 8), as a
/// session holds it: the flow study's input (name "tube"). With degrees 0 nothing is bent: the
/// current shape is the original.
FlowStudyInput PreparedThenBentTube(double degrees);

/// Largest coordinate difference between two surfaces of the same points; infinity when the
/// point counts differ.
double MaxDifference(vtkPolyData* a, vtkPolyData* b);

/// Distance from p to the wire of `ribbon` (dense sampling).
double DistanceToWire(const RibbonSpec& ribbon, const Vec3& p);

/// A fresh empty folder under the system temporary folder.
std::string TemporaryFolder(const std::string& name);

} // namespace test
} // namespace bender

#endif
