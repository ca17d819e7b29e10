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

/// A point well inside the lumen (metres): the one inside point of Bender (InsidePoint.h,
/// FindInsidePoint: the verified chord midpoint farthest from the wall), moved off the
/// background grid's planes by a few hundredths of `cellSize`. Throws InputError naming `name`
/// when none is found.
std::array<double, 3> InsidePoint(vtkPolyData* surface, double cellSize, const std::string& name);

} // namespace bender

#endif
