#ifndef bender_BenderStlExport_h
#define bender_BenderStlExport_h

// The STL writer of bender_io for CFD-ready exports (patches, frame and unit in the header).

#include <stdexcept>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// An export that could not be written; what() names the file and the problem.
class StlExportError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// How patches (the "PatchId" cell array: wall 0, caps 1..n) are written.
enum class StlPatchMode
{
  Single, ///< one binary STL of the whole surface
  Solids, ///< one ASCII STL with a named solid per patch: wall, cap_1, ... (snappyHexMesh)
  Files   ///< one binary STL per patch: OUT_wall.stl, OUT_cap_1.stl, ...
};

/// The frame the exported coordinates are in. Input meshes are LPS; RAS negates x and y
/// (a rotation by 180 degrees about z: orientation and volume are kept).
enum class StlFrame
{
  LPS,
  RAS
};

struct StlExportOptions
{
  StlPatchMode patches = StlPatchMode::Single;
  StlFrame frame = StlFrame::LPS;
  std::string unit = "mm";
};

/// Patch names in order of PatchId: "wall", "cap_1", ... Without a PatchId array: "wall".
/// Throws StlExportError when PatchId holds non-finite, negative or absurd values (more
/// patches than cells).
std::vector<std::string> PatchNames(vtkPolyData* mesh);

/// The files ExportStl would write for these arguments (one, or one per non-empty patch), so
/// that callers can refuse to overwrite an input before anything is written.
std::vector<std::string> PlannedStlPaths(vtkPolyData* mesh,
  const std::string& path,
  const StlExportOptions& options);

/// Writes mesh (triangles; polygons fanned) as STL. Every file states the frame and unit in
/// its header ("bender export: frame LPS, unit mm"). The files are written all-or-nothing
/// through AtomicWriteAll (AtomicFile.h): with StlPatchMode::Files either every patch file is
/// replaced or none is. Returns the paths written. Throws StlExportError (non-finite
/// coordinates, no triangles, unwritable folder), what() starting with a file's base name.
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
