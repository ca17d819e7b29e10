#ifndef bender_CfdPatches_h
#define bender_CfdPatches_h

// The geometry of a labelled surface that an OpenFOAM case needs, in metres: each patch
// (area, centre, outward normal, equivalent diameter) and a point inside the lumen, both taken
// from the one measure of the surface's patches (ComputePatchSidecar, PatchSidecar.h).

#include "CfdCase.h"
#include "PatchSidecar.h"

#include <array>
#include <string>
#include <vector>

namespace bender
{

/// True for an inlet or an outlet.
bool IsEndPatch(PatchType type);

/// The patches of `measured` (ComputePatchSidecar in LPS millimetres) with their areas,
/// centres and outward normals, in metres. Throws InputError naming `name` when the surface
/// encloses no volume.
std::vector<CfdPatch> CfdPatchesOf(const PatchSidecar& measured, const std::string& name);

/// A point well inside the lumen (metres): the inside point of `measured` (ComputePatchSidecar
/// in LPS millimetres; InsidePoint.h: the verified chord midpoint farthest from the wall), moved
/// off the background grid's planes by a few hundredths of `cellSize`. Throws InputError naming
/// `name` when none was found.
std::array<double, 3> InsidePoint(const PatchSidecar& measured,
  double cellSize,
  const std::string& name);

} // namespace bender

#endif
