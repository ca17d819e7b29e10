#ifndef bender_FlowExtensions_h
#define bender_FlowExtensions_h

// Flow extensions (issue 11): a straight tube added at each open end of a vessel surface so
// that the flow entering or leaving a CFD model is developed before it reaches the vessel.
//
// Each end is extended along its outward normal by Factor x its equivalent radius
// (sqrt(rim area / pi)). The rim itself (its vertices shared, so the result stays watertight
// and consistently oriented) is zipped to a first ring one rim edge length away; every ring
// has the rim's number of vertices evenly spaced in angle about the end's centre, at a radius
// blended from the rim's own (the rim seen from its centre, as a function of the angle) into
// the equivalent radius with a smoothstep weight over the first min(half the extension,
// 2 radii); the rest is a straight cylinder, ring spacing about the rim's mean edge length. The
// far ring lies on a plane perpendicular to the normal at Length from the rim's centre, ready
// for a flat cap (vtkBenderCapFilter).
//
// An extension that would run into the vessel (a surface point beyond the rim's plane within
// 1.2 rim radii of its axis) or into another extension (a ring of one inside the other's
// cylinder, widened by 10 %: outlets pointing towards each other) is made shorter, with a
// warning (the longer of the two loses a tenth at a time); it may
// become 0 long. Coordinates and units are those of the input.

#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

using ExtensionPoint = std::array<double, 3>;

/// One open end to extend.
struct FlowExtensionEnd
{
  /// Rim point ids in the surface, in the order the wall's triangles run them.
  std::vector<long long> rim;
  ExtensionPoint centre{ { 0, 0, 0 } }; ///< of the rim
  ExtensionPoint normal{ { 0, 0, 1 } }; ///< outwards, unit
  double radius = 0.0;                  ///< equivalent radius of the rim
  /// Extension length / radius, >= 0 (0: no extension). < 0: the default (inlet or outlet).
  double factor = -1.0;
  bool inlet = false;
};

struct FlowExtensionOptions
{
  double inletFactor = 10.0; ///< default factor of the inlet, [0, 100]
  double outletFactor = 5.0; ///< default factor of the outlets, [0, 100]
};

/// One extended end.
struct ExtendedEnd
{
  std::vector<long long> farRim;           ///< the far ring's point ids, same direction as rim
  ExtensionPoint farCentre{ { 0, 0, 0 } }; ///< centre + length x normal
  ExtensionPoint normal{ { 0, 0, 1 } };
  double radius = 0.0;
  double length = 0.0;          ///< the extension's length (may be less than requested)
  double requestedLength = 0.0; ///< factor x radius as asked
  double factor = 0.0;          ///< length / radius
};

struct FlowExtensionResult
{
  /// The input's points and triangles followed by the extensions' (open at the far rims;
  /// point and cell data are not kept).
  vtkSmartPointer<vtkPolyData> surface;
  std::vector<ExtendedEnd> ends; ///< in the order of the ends given
  /// One line per extension made shorter than requested.
  std::vector<std::string> warnings;
};

/// The open ends of a surface as FlowExtensionEnd: its closed boundary loops, centre and
/// equivalent radius of each, the normal pointing away from the surface's point centroid;
/// the largest is the inlet.
std::vector<FlowExtensionEnd> OpenEnds(vtkPolyData* surface);

/// Extends `ends` of `surface`. Throws InputError (one line) for an empty or non-finite
/// surface, a rim with an id out of range or fewer than 3 points, a factor out of [0, 100].
FlowExtensionResult AddFlowExtensions(vtkPolyData* surface,
  const std::vector<FlowExtensionEnd>& ends,
  const FlowExtensionOptions& options = {});

} // namespace bender

#endif
