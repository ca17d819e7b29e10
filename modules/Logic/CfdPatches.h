#ifndef bender_CfdPatches_h
#define bender_CfdPatches_h

// The geometry of a labelled surface that an OpenFOAM case needs, in metres: each patch
// (area, centre, outward normal, equivalent diameter) and a point inside the lumen, both taken
// from the one measure of the surface's patches (ComputePatchSidecar, PatchSidecar.h).

#include "CfdCase.h"
#include "LabelledSurface.h"
#include "PatchSidecar.h"

#include <array>
#include <string>
#include <vector>

namespace bender
{

/// True for an inlet or an outlet.
bool IsEndPatch(PatchType type);

/// The indices of the inlets and outlets in `patches`.
std::vector<std::size_t> EndPatches(const std::vector<CfdPatch>& patches);

/// The patches of `measured` (ComputePatchSidecar in LPS millimetres) with their areas,
/// centres and outward normals, in metres. Throws InputError naming `name` when the surface
/// encloses no volume.
std::vector<CfdPatch> CfdPatchesOf(const PatchSidecar& measured, const std::string& name);

/// Makes the end named `inlet` (empty: the one end of type inlet) the inlet of `patches` (those
/// of `labelled`) and every other end an outlet, with names that say so, in both: a chosen end
/// named outlet_N becomes "inlet", and an end named "inlet" that is not chosen takes the chosen
/// end's old name when that was outlet_N, else the first free outlet_N; other names are kept.
/// When a name or role changes, labelled.surface becomes a copy carrying the new table (the
/// input surface is not changed). Returns the inlet's index in `patches`.
/// Throws InputError (one line naming `name` or --inlet) for an unknown name, the wall,
/// several inlets and no inlet.
std::size_t ChooseInlet(std::vector<CfdPatch>& patches,
  LabelledSurface& labelled,
  const std::string& inlet,
  const std::string& name);

/// A point well inside the lumen (metres): the inside point of `measured` (ComputePatchSidecar
/// in LPS millimetres; InsidePoint.h: the verified chord midpoint farthest from the wall), moved
/// off the background grid's planes by a few hundredths of `cellSize`. Throws InputError naming
/// `name` when none was found.
std::array<double, 3> InsidePoint(const PatchSidecar& measured,
  double cellSize,
  const std::string& name);

} // namespace bender

#endif
