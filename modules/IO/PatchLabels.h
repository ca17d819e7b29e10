#ifndef bender_PatchLabels_h
#define bender_PatchLabels_h

// The labels of a CFD-ready surface: which triangles are the wall and which close each vessel
// end, with the end's name and role. The one place that reads and writes them, so that the cap
// and clip filters, the warp, subdivision, undo, every export and the OpenFOAM case agree.
//
// On a vtkPolyData:
//  - cell data "CellEntityIds" (int, VMTK's convention): 1 on the wall, 2, 3, ... on the ends;
//  - cell data "ModelFaceID" (int, SimVascular's convention): the same values;
//  - field data "PatchNames" and "PatchTypes" (vtkStringArray): entry id-1 names patch `id`
//    ("wall", "inlet", "outlet_1", ...) and gives its role ("wall", "inlet", "outlet").
// Older files carry "PatchId" (wall 0, caps 1..n, named cap_1..cap_n): read as ids + 1.

#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

inline constexpr const char* kCellEntityIdsArrayName = "CellEntityIds";
inline constexpr const char* kModelFaceIdArrayName = "ModelFaceID";
inline constexpr const char* kPatchNamesArrayName = "PatchNames";
inline constexpr const char* kPatchTypesArrayName = "PatchTypes";
inline constexpr const char* kLegacyPatchIdArrayName = "PatchId";
inline constexpr int kWallEntityId = 1;

enum class PatchType
{
  Wall,
  Inlet,
  Outlet
};

/// "wall", "inlet", "outlet".
const char* PatchTypeName(PatchType type);
/// The inverse of PatchTypeName; throws InputError for any other text.
PatchType PatchTypeFromName(const std::string& name);

struct PatchLabel
{
  int id = kWallEntityId; ///< the CellEntityIds value, >= 1
  std::string name;       ///< unique, [A-Za-z0-9_], usable as an OpenFOAM patch name
  PatchType type = PatchType::Wall;
};

/// True when the surface carries CellEntityIds or the legacy PatchId.
bool HasPatchLabels(vtkPolyData* surface);

/// The id of every cell, in cell order: CellEntityIds, else PatchId + 1, else all wall (1).
/// Throws InputError (naming the array) for an array of the wrong length or with values that
/// are non-finite, non-integral, below 1 (below 0 for PatchId) or above the number of cells.
std::vector<int> CellPatchIds(vtkPolyData* surface);

/// The patches present, sorted by id: names and types from the field data when present (and
/// consistent), else "wall" for id 1 and "cap_<id-1>" / Outlet for the others. Patches with
/// no cell are left out. Throws InputError like CellPatchIds, and for duplicate names.
std::vector<PatchLabel> ReadPatchLabels(vtkPolyData* surface);

/// Writes CellEntityIds and ModelFaceID from cellIds (one per cell of surface) and the names
/// and types of `patches` into the field data (entry id-1; ids without a patch get "" and
/// "wall"); removes the legacy PatchId. Throws InputError when cellIds has the wrong length,
/// an id has no patch in `patches`, or names are empty, duplicated or not [A-Za-z0-9_].
void WritePatchLabels(vtkPolyData* surface,
  const std::vector<int>& cellIds,
  const std::vector<PatchLabel>& patches);

/// True when name is a valid patch name: non-empty, at most 64 characters of [A-Za-z0-9_],
/// not starting with a digit.
bool IsValidPatchName(const std::string& name);

} // namespace bender

#endif
