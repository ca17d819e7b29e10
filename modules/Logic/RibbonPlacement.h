#ifndef bender_RibbonPlacement_h
#define bender_RibbonPlacement_h

#include "BenderErrors.h"
#include "WarpPlan.h"

class vtkPolyData;

namespace bender
{

/// A straight ribbon laid along the vessel around a picked point, so that a first bend takes
/// seconds: the vessel's local axis and radius are estimated from the surface points near the
/// pick (principal axis of their covariance, refined twice on a sphere of three local radii).
struct RibbonPlacement
{
  RibbonSpec ribbon;            ///< straight, along the local axis, centred on the axis
  double vesselRadius = 0.0;    ///< estimated local lumen radius, model units
  double suggestedRadius = 0.0; ///< R covering the vessel wall around the ribbon
};

struct RibbonPlacementOptions
{
  /// Ribbon length as a multiple of the local vessel radius; range [2, 40], default 8.
  double lengthFactor = 8.0;
  /// Suggested R as a multiple of the local vessel radius; range [1.1, 10], default 2.2.
  double radiusFactor = 2.2;
};

/// The pick is not usable (empty surface, non-finite point, not enough surface near it).
class RibbonPlacementError : public InputError
{
public:
  using InputError::InputError;
};

/// Places a straight ribbon along the part of `surface` near `picked` (model coordinates,
/// LPS mm for segmented vessels). Throws RibbonPlacementError.
RibbonPlacement PlaceRibbonOnSurface(vtkPolyData* surface,
  const Vec3& picked,
  const RibbonPlacementOptions& options = {});

} // namespace bender

#endif
