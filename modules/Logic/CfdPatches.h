#ifndef bender_CfdPatches_h
#define bender_CfdPatches_h

// The geometry of a labelled surface that an OpenFOAM case needs: each patch measured (area,
// centre, outward normal, equivalent diameter) and a point inside the lumen.

#include "CfdCase.h"

#include <array>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// True for an inlet or an outlet.
bool IsEndPatch(PatchType type);

/// The patches of `surface` (LPS mm, labelled by `labels`) with their areas, centres and
/// outward normals, in metres. Throws InputError naming `name` when the surface encloses no
/// volume.
std::vector<CfdPatch> MeasurePatches(vtkPolyData* surface,
  const std::vector<PatchLabel>& labels,
  const std::string& name);

/// A point well inside the lumen (metres): on the inward normal of an end (the inlet first),
/// the candidate farthest from the wall. Throws InputError naming `name` when none is inside.
std::array<double, 3> InsidePoint(vtkPolyData* surface,
  const std::vector<CfdPatch>& patches,
  std::size_t inlet,
  double cellSize,
  const std::string& name);

} // namespace bender

#endif
