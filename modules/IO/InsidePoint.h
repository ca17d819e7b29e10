#ifndef bender_InsidePoint_h
#define bender_InsidePoint_h

// The one "point inside the lumen" of Bender (snappyHexMesh's locationInMesh, TetGen's region
// point, the sidecar's insidePoint): the midpoints of chords through the volume, shot inwards
// from the ends' centres and from wall triangles spread over the surface, each verified inside
// by its generalized winding number (exact for a closed surface, whatever its shape: a bent
// tube's chords stay inside although a straight line from an end would leave it), the one
// farthest from the wall kept.

#include "LabelledSurface.h"
#include "Vec3.h"

#include <vtkType.h>

#include <array>
#include <optional>
#include <vector>

class vtkPolyData;

namespace bender
{

/// A chord's start: a point on the surface and the unit direction into the volume.
struct InwardRay
{
  Vec3 origin;
  Vec3 direction;
};

/// A point inside the closed surface and its distance to the surface (its unit).
struct LumenPoint
{
  Vec3 point;
  double clearance = 0.0;
};

/// The generalized winding number of point about the closed triangle surface (points and
/// triangles as given): about +1 inside an outward-oriented surface, -1 inside an inward one,
/// 0 outside.
double WindingNumber(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<vtkIdType, 3>>& triangles,
  const double point[3]);

/// The point inside the closed triangle surface (points and triangles as given, either
/// orientation) farthest from it among the verified midpoints of chords: one chord per ray of
/// `seeds` (e.g. from each end's centre against its outward normal), then one from each of up
/// to 48 triangles spread along the list (those for which `shoot` is true; all when it is
/// empty) against its normal. None when no midpoint is inside (an open or degenerate surface).
std::optional<LumenPoint> FindLumenPoint(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<vtkIdType, 3>>& triangles,
  const std::vector<InwardRay>& seeds,
  const std::vector<bool>& shoot = {});

/// The point inside the lumen of a closed surface in its own coordinates: FindLumenPoint with
/// the ends of its patch table as seeds and its wall triangles, as the patches.json sidecar
/// measures it (PatchSidecar::insidePoint). None for an open surface or when none is found.
/// Throws StlExportError (no triangles, non-finite coordinates, bad cell labels).
std::optional<LumenPoint> FindInsidePoint(const LabelledSurface& surface);

} // namespace bender

#endif
