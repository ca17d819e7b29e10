#ifndef bender_VesselClip_h
#define bender_VesselClip_h

// Clipping the ends of a vessel surface perpendicular to its centerline (issue 11).
//
// Each vessel end of the centerlines is cut by the plane through a centerline point and
// perpendicular to the centerline's tangent there; only the piece of the surface that belongs
// to the vessel at that point is cut: the ring of triangles that the plane crosses within a
// ball around the centerline point (1.5 radii, widened up to 4 radii until the ring closes
// around the vessel), and the part of the surface beyond that ring (towards the end) is
// removed. A neighbouring vessel that the plane also crosses, farther away or not connected to
// the ring, is left whole. Works on closed surfaces (segmentations: the rounded or flat end is
// cut off) and on open ones (an oblique or ragged open end is re-cut perpendicular; when the
// plane still meets the old rim the cut moves inwards, for the default distance only).
//
// The vessel ends of a centerline polydata (polylines with point data
// MaximumInscribedSphereRadius; the Paths or Branches of ComputeCenterlines, or a file written
// by `bender-cli centerline`): the polyline end points that are not bifurcations. End points
// closer than a quarter radius are one end (the shared inlet of the per-outlet paths); a group
// whose polylines leave it in directions more than 90 degrees apart, or that another polyline
// passes within a radius of, or that the cell data StartBifurcationId / EndBifurcationId of
// the branches mark, is a bifurcation.
//
// Default clip distance ("where the inscribed radius has settled"), measured along the
// centerline from its end point s = 0 inwards, with r(s) the inscribed radius and r0 the
// larger of r(0) and the median radius within four median radii of the end (a closed end's tip
// has a small radius): the smallest s >= r0 such that over [s, s + 2 r(s)] r stays within 10 %
// of r(s) and the tangent turns by less than 5 degrees. When no such s exists before
// min(half the centerline's length, 10 r0): the first s where the radius alone has settled,
// else the s in [r0, that limit] where r varies least over its window. Open ends: the centerline
// ends at the rim's centre, and the cut is at least one radius inside it; closed ends: the
// centerline stops about one radius before the end (see CenterlineOptions::endTrimFactor), so the
// cut is about two radii from the end.
//
// Coordinates and units are those of the inputs (LPS mm for Bender's surfaces).

#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

using ClipPoint = std::array<double, 3>;

/// A point within this many inscribed radii of a vessel's centerline is on that vessel (a
/// ClipEndRequest with a distance must be on the vessel of its end).
constexpr double kClipPointReach = 2.0;

/// A user's choice for one end.
struct ClipEndRequest
{
  /// With distance >= 0: a point on the vessel near its end (the nearest end is taken; the
  /// point must be within kClipPointReach inscribed radii of that end's centerline).
  /// With distance < 0: a point near the centerline where to cut; the cut is at the nearest
  /// centerline point, and the side towards the nearer vessel end (along the centerline) is
  /// removed.
  ClipPoint position{ { 0, 0, 0 } };
  /// mm from the vessel end along the centerline; < 0: see position.
  double distance = -1.0;
};

struct ClipOptions
{
  /// Ends with a user's position or distance; the others are cut at the default distance.
  std::vector<ClipEndRequest> ends;
};

/// One clipped end.
struct ClippedEnd
{
  ClipPoint centre{ { 0, 0, 0 } };        ///< area centroid of the rim, on the cut plane
  ClipPoint normal{ { 0, 0, 1 } };        ///< unit, outwards (from the vessel through the cut)
  double radius = 0.0;                    ///< equivalent radius sqrt(area / pi) of the rim
  double area = 0.0;                      ///< of the planar region inside the rim
  double inscribedRadius = 0.0;           ///< of the centerline at the cut
  ClipPoint centerlineEnd{ { 0, 0, 0 } }; ///< the vessel end on the centerline
  double distance = 0.0;                  ///< along the centerline from its end to the cut
  bool userChosen = false;                ///< from ClipOptions::ends
  /// Rim point ids in the output surface, in the order the wall's triangles run them.
  std::vector<long long> rim;
};

/// An open end of the input surface that no centerline end reached: the clip left it as it
/// was (an open loop of ClipResult::surface that is no rim).
struct UnclippedEnd
{
  ClipPoint centre{ { 0, 0, 0 } }; ///< mean of the loop's points
  double radius = 0.0;             ///< mean distance of the loop's points to centre
};

struct ClipResult
{
  /// The surface with every end open (triangles only, unused points removed; point and cell
  /// data are not kept).
  vtkSmartPointer<vtkPolyData> surface;
  std::vector<ClippedEnd> ends; ///< in the order of the centerline's ends
  /// Open ends of the input that were not clipped (no centerline reaches them); a CFD model
  /// made of this surface would miss them (PrepareForCfd refuses it).
  std::vector<UnclippedEnd> unclipped;
  std::vector<std::string> warnings;
};

/// The vessel ends of a centerline polydata (see above): each end's position and inscribed
/// radius. Throws InputError when the polydata has no polyline or no radius array.
struct CenterlineEnd
{
  ClipPoint position{ { 0, 0, 0 } };
  double radius = 0.0;
};
std::vector<CenterlineEnd> FindCenterlineEnds(vtkPolyData* centerlines);

/// A vessel end's centerline walked from the end inwards: the path along which
/// ClipVesselEnds moves the end's clip plane (ClipEndRequest::distance is an arc length on it).
struct CenterlineEndPath
{
  ClipPoint position{ { 0, 0, 0 } }; ///< the vessel end (as FindCenterlineEnds)
  double radius = 0.0;               ///< inscribed radius at the end
  std::vector<ClipPoint> points;     ///< from the end inwards, no repeated point
  std::vector<double> arcLengths;    ///< of points, from 0
  std::vector<double> radii;         ///< inscribed radius at points
  double defaultDistance = 0.0;      ///< the default cut ("where the radius has settled")
  double maximumDistance = 0.0;      ///< the farthest cut a request may ask: half the path
};

/// The paths of the vessel ends of FindCenterlineEnds, in the same order (the order of
/// ClipResult::ends). Throws InputError as FindCenterlineEnds.
std::vector<CenterlineEndPath> FindCenterlineEndPaths(vtkPolyData* centerlines);

/// The plane that ClipVesselEnds cuts by at arc length `distance` (clamped to the path) of
/// `path`: its centre (the centerline point), its unit normal pointing outwards (towards the
/// end) and the inscribed radius there. For the default distance ClipVesselEnds may move the
/// cut inwards (an oblique old rim in the way); for a requested distance it cuts here or fails.
struct ClipPlane
{
  ClipPoint centre{ { 0, 0, 0 } };
  ClipPoint normal{ { 0, 0, 1 } };
  double radius = 0.0;
};
ClipPlane ClipPlaneAt(const CenterlineEndPath& path, double distance);

/// The arc length in [0, path.maximumDistance] of the path point nearest `point`.
double NearestDistanceOnPath(const CenterlineEndPath& path, const ClipPoint& point);

/// Clips every vessel end of `surface` (a triangle surface; polygons are triangulated). Throws
/// InputError (one line) for an empty or non-finite surface, centerlines without ends, a
/// requested position that is not on a vessel (with a distance: not within kClipPointReach
/// inscribed radii of the centerline of the end nearest to it; without: not within 3 of any
/// centerline), a requested
/// distance whose plane cuts no vessel cleanly, and when the default cut of an end fails.
ClipResult ClipVesselEnds(vtkPolyData* surface,
  vtkPolyData* centerlines,
  const ClipOptions& options = {});

} // namespace bender

#endif
