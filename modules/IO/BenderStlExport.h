#ifndef bender_BenderStlExport_h
#define bender_BenderStlExport_h

// The STL writer of bender_io for CFD-ready exports (patches, frame and unit in the header),
// and the export geometry the other mesher formats share (TetgenExport.h, PatchSidecar.h):
// labelled triangles and the frame/unit change of the written coordinates.

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "LabelledSurface.h"
#include "PatchLabels.h"

#include <vtkType.h>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// An export that could not be written; what() names the file and the problem.
class StlExportError : public InputError
{
public:
  using InputError::InputError;
};

/// How patches (the labels of PatchLabels.h: wall 1, ends 2..) are written.
enum class StlPatchMode
{
  Single, ///< one binary STL of the whole surface
  Solids, ///< one ASCII STL with a solid per patch named by it: wall, inlet, ... (snappyHexMesh)
  Files   ///< one binary STL per patch: OUT_wall.stl, OUT_inlet.stl, ...
};

/// The frame the exported coordinates are in. Input meshes are LPS; RAS negates x and y
/// (a rotation by 180 degrees about z: orientation and volume are kept).
enum class StlFrame
{
  LPS,
  RAS
};

/// "LPS" or "RAS".
const char* StlFrameName(StlFrame frame);

struct StlExportOptions
{
  StlPatchMode patches = StlPatchMode::Single;
  StlFrame frame = StlFrame::LPS;
  /// Unit of the written coordinates: "mm" (the surface's own) or "m" (divided by 1000).
  std::string unit = "mm";
};

/// True for the units an export can be written in: "mm" and "m".
bool IsExportUnit(const std::string& unit);

/// The change from the surface's LPS millimetres to the written coordinates: x and y negated
/// for RAS, then divided by 1000 for metres. The same input point always gives the same output
/// bits, so patches written to separate files share their rim vertices exactly.
class ExportTransform
{
public:
  /// Throws StlExportError for a unit other than "mm" or "m".
  ExportTransform(StlFrame frame, const std::string& unit);
  void Apply(const double in[3], double out[3]) const;
  StlFrame Frame() const { return this->FrameValue; }
  const std::string& Unit() const { return this->UnitValue; }

private:
  StlFrame FrameValue;
  std::string UnitValue;
  bool Metres;
};

/// The triangles of a surface (polygons fanned, strips split) with the patch of the cell each
/// came from.
struct LabelledTriangles
{
  std::vector<std::array<vtkIdType, 3>> triangles; ///< point ids
  std::vector<std::size_t> patch;                  ///< per triangle, an index into patches
  std::vector<PatchLabel> patches;                 ///< the surface's table: sorted by id
  /// Triangles per patch (same index as patches).
  std::vector<std::size_t> CountPerPatch() const;
};

/// Collects the labelled triangles of `mesh` with the patch table it carries (read once, by
/// ReadLabelledSurface). Throws StlExportError (no triangles, non-finite coordinates, a cell
/// array CellPatchIds refuses: the message names the array).
LabelledTriangles CollectLabelledTriangles(const LabelledSurface& mesh);

/// The labelled surface of an export to `path`: ReadLabelledSurface of mesh, with labels it
/// refuses thrown as StlExportError starting with path's base name.
LabelledSurface ReadExportLabels(vtkPolyData* mesh, const std::string& path);

/// Patch names in order of label: "wall", "inlet", "outlet_1", ...; legacy PatchId surfaces
/// give "wall", "cap_1", ... Without labels: "wall".
std::vector<std::string> PatchNames(const LabelledSurface& mesh);

/// The files ExportStl would write for these arguments (one, or one per patch with
/// triangles), so that callers can refuse to overwrite an input before anything is written.
std::vector<std::string> PlannedStlPaths(const LabelledSurface& mesh,
  const std::string& path,
  const StlExportOptions& options);

/// The files of an STL export as producers for AtomicWriteAll (nothing is written yet), so
/// that a caller can write them together with other files (the patches sidecar). Throws
/// StlExportError like ExportStl.
std::vector<AtomicFile> StlFiles(const LabelledSurface& mesh,
  const std::string& path,
  const StlExportOptions& options);

/// Writes mesh (triangles; polygons fanned) as STL. Every file states the frame and unit in
/// its header ("bender export: frame LPS, unit mm"): the 80-byte header of binary files, the
/// endsolid line of the first solid in ASCII. Solids: one ASCII solid per patch named by the
/// patch (wall, inlet, outlet_1, ...); Files: OUT_<name>.stl per patch, sharing the rim
/// vertices bit for bit. The files are written all-or-nothing through AtomicWriteAll
/// (AtomicFile.h). Returns the paths written. Throws StlExportError (non-finite coordinates,
/// no triangles, bad labels, unknown unit, unwritable folder), what() starting with a file's
/// base name. The labels are read once (ReadExportLabels).
std::vector<std::string> ExportStl(vtkPolyData* mesh,
  const std::string& path,
  const StlExportOptions& options);

/// Writes one STL file of mesh's triangles (polygons fanned, strips converted) to path as it
/// is (no frame change, not atomic: pass the temporary file of an AtomicWrite), binary (the
/// first line of header in the 80-byte header, prefixed "# " when it starts with "solid") or
/// ASCII (one solid named by that line, "mesh" when empty). The one STL writer of bender_io
/// beside ExportStl. Returns false with problem set (no triangles, non-finite coordinates,
/// write failure).
bool WriteStlFile(vtkPolyData* mesh,
  const std::string& path,
  bool binary,
  const std::string& header,
  std::string& problem);

} // namespace bender

#endif
