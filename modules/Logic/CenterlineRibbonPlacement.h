#ifndef bender_CenterlineRibbonPlacement_h
#define bender_CenterlineRibbonPlacement_h

// "Ribbon on the centerline": two picks on a vessel's wall place the ribbon with its end frames
// on the centerline (positions on the centerline, tangents = the centerline's tangents, the
// start normal from its Frenet frame carried along the centerline without twist to the end),
// and R from the local inscribed radius. A pick far from every centerline for the local
// radius (an aneurysm's sac, a bump) is refused. Model coordinates (LPS mm).

#include "RibbonPlacement.h"
#include "WarpPlan.h"

class vtkPolyData;

namespace bender
{

struct CenterlineRibbonOptions
{
  /// R = this x the largest inscribed radius between the ribbon's ends; [1.1, 10], default 2.2
  /// (the factor of the surface placement, so both give the same region for the same vessel).
  double radiusFactor = 2.2;
  /// A pick belongs to a vessel when its distance to the nearest centerline point is at most
  /// this x the inscribed radius there (a pick on the wall measures about 1; the wall of an
  /// aneurysm's sac 2 or more); [1, 3], default 1.5.
  double pickToleranceFactor = 1.5;
};

/// Places the ribbon between the centerline points nearest to `first` and `second`, on one of
/// the per-outlet centerlines (CenterlineResult::paths: polylines with
/// MaximumInscribedSphereRadius, FrenetTangent and FrenetNormal). The ribbon runs from the first
/// pick to the second. Throws RibbonPlacementError: no centerline, missing arrays, a non-finite
/// pick, a pick not on a vessel (the sac), both picks at the same place (closer than one inscribed
/// radius along the centerline).
RibbonPlacement PlaceRibbonOnCenterline(vtkPolyData* centerlinePaths,
  const Vec3& first,
  const Vec3& second,
  const CenterlineRibbonOptions& options = {});

} // namespace bender

#endif
