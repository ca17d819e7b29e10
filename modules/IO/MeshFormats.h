#ifndef bender_MeshFormats_h
#define bender_MeshFormats_h

// The one table of surface mesh formats. ReadMesh and WriteMesh dispatch on it, FileKind
// classifies mesh files with it, ExportSurface writes every writable row, and the CLI's and the
// GUI's lists (extensions, file-dialog filters, `bender-cli formats`) iterate it. A new format
// is one row here (MeshFormats.cxx) plus its reader/writer and a test.
//
// API (namespace bender):
//   struct MeshFormat                      one row: name, extensions, label, read, write,
//                                          namedPatches, patchLabels, regionPoint, precision,
//                                          encodingChoice
//   std::vector<MeshFormat> MeshFormats()  all rows, in table order (built-ins first)
//   std::optional<MeshFormat> FindMeshFormat(path)        by the path's extension, any case
//   std::optional<MeshFormat> FindMeshFormatByName(name)  by name ("stl")
//   std::vector<std::string> MeshExtensions(MeshAccess)   ".stl", ".obj", ... readable/writable
//   std::string MeshExtensionList(MeshAccess, separator)  ".stl, .obj, ..." for messages
//   std::string MeshFilesFilter(MeshAccess, title)        "Meshes (*.stl *.obj ...)"
//   std::vector<std::string> MeshFormatFilters(MeshAccess) "STL (*.stl)", ... one per format
//   std::string MeshFileDialogFilters(MeshAccess)         all of the above joined by ";;"
//   void RegisterMeshFormat(MeshFormat)    adds a row (throws std::invalid_argument on a
//                                          duplicate name or extension, or a bad row)
//   bool UnregisterMeshFormat(name)        removes a row; false when there is none
//   class ScopedMeshFormat                 registers for its lifetime (tests)
//   MeshExportRules ResolveMeshExport(format, MeshExportRequest)
//                                          the export rules in one place: named solids are
//                                          ASCII, patches only where the format names them,
//                                          when the patches.json sidecar is written and when
//                                          the patches are measured

#include "BenderStlExport.h"
#include "MeshIO.h"

#include <vtkSmartPointer.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// Reads the file at `path` (`size` bytes; ReadMesh has checked it is a readable regular
/// file within the mesh size budget) and returns its mesh. Throws MeshIOError naming the
/// file (any other exception is reported by ReadMesh as a corrupt file). ReadMesh checks the
/// result (coordinates within CoordinateRange.h's rule, cell indices in range).
using MeshReader =
  std::function<vtkSmartPointer<vtkPolyData>(const std::string& path, std::uintmax_t size)>;

/// Writes `mesh` (non-empty, coordinates within CoordinateRange.h's rule) to `file` (the temporary
/// file of WriteMesh's atomic write). Returns false with a one-line `problem` (without the
/// file name) on failure.
using MeshWriter = std::function<bool(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem)>;

/// Coordinate precision a format stores.
enum class MeshPrecision
{
  Float, ///< single precision
  Double
};

/// Which side of a format a list is about.
enum class MeshAccess
{
  Read,
  Write
};

/// One row of the table.
struct MeshFormat
{
  /// Short lower-case identifier: "stl", "obj" (bender-cli formats, JSON).
  std::string name;
  /// Lower-case extensions with their dot, the first the preferred one: {".stl"}.
  std::vector<std::string> extensions;
  /// What file dialogs call it: "STL", "VTK XML polydata".
  std::string label;
  /// Empty when Bender cannot read the format.
  MeshReader read;
  /// Empty when Bender cannot write the format.
  MeshWriter write;
  /// Patches can be written as named parts (STL: one solid per patch, or one file per patch).
  bool namedPatches = false;
  /// The written file keeps the patch labels (CellEntityIds ...) of PatchLabels.h and states
  /// the export's frame and unit in its field data (VTK polydata, XML and legacy: both read
  /// back with their labels).
  bool patchLabels = false;
  /// The format takes a region point inside the lumen (TetGen): an export measures the
  /// patches to find one.
  bool regionPoint = false;
  MeshPrecision precision = MeshPrecision::Float;
  /// The writer offers binary or ASCII (MeshWriteOptions::stlEncoding).
  bool encodingChoice = false;

  bool CanRead() const { return static_cast<bool>(this->read); }
  bool CanWrite() const { return static_cast<bool>(this->write); }
  bool Can(MeshAccess access) const
  {
    return access == MeshAccess::Read ? this->CanRead() : this->CanWrite();
  }
};

/// Every row, in table order (the built-in formats first, then registered ones).
std::vector<MeshFormat> MeshFormats();

/// The row whose extensions hold the extension of path's last component (case-insensitive);
/// none for an unknown or missing extension.
std::optional<MeshFormat> FindMeshFormat(const std::string& path);

/// The row called `name` (case-insensitive); none when there is none.
std::optional<MeshFormat> FindMeshFormatByName(const std::string& name);

/// The extensions of the formats that can be read (written), in table order: ".stl", ...
std::vector<std::string> MeshExtensions(MeshAccess access);

/// Those extensions joined for a message: ".stl, .obj, .ply, .vtp, .vtk, .off".
std::string MeshExtensionList(MeshAccess access, const std::string& separator = ", ");

/// One file-dialog filter for all of them: "Meshes (*.stl *.obj *.ply *.vtp *.vtk *.off)".
std::string MeshFilesFilter(MeshAccess access, const std::string& title = "Meshes");

/// One file-dialog filter per format that can be read (written): "STL (*.stl)", ...
std::vector<std::string> MeshFormatFilters(MeshAccess access);

/// The filters of a mesh file dialog, Qt's ";;" form: MeshFilesFilter first (reading only),
/// then MeshFormatFilters.
std::string MeshFileDialogFilters(MeshAccess access);

/// Adds a row at the end of the table. Throws std::invalid_argument for a row without a name,
/// extension or label, with neither a reader nor a writer, an extension that is not lower case
/// with a leading dot, or a name or extension that is already in the table.
void RegisterMeshFormat(MeshFormat format);

/// Removes the row called `name`; false when there is none.
bool UnregisterMeshFormat(const std::string& name);

/// Registers a row for its lifetime (tests add a dummy format and see it in every list).
class ScopedMeshFormat
{
public:
  explicit ScopedMeshFormat(MeshFormat format);
  ~ScopedMeshFormat();
  ScopedMeshFormat(const ScopedMeshFormat&) = delete;
  ScopedMeshFormat& operator=(const ScopedMeshFormat&) = delete;

private:
  std::string Name;
};

/// Whether the patches.json sidecar goes with an export.
enum class SidecarChoice
{
  Auto, ///< with every export of patches (solids, files) and for region-point formats
  On,
  Off
};

/// What an export asks for.
struct MeshExportRequest
{
  StlEncoding encoding = StlEncoding::Binary;
  StlPatchMode patches = StlPatchMode::Single;
  SidecarChoice sidecar = SidecarChoice::Off;
};

/// What an export of a format does, after the rules.
struct MeshExportRules
{
  StlEncoding encoding = StlEncoding::Binary;
  StlPatchMode patches = StlPatchMode::Single;
  /// Write OUT.patches.json beside the output.
  bool sidecar = false;
  /// Measure the patches (for the sidecar, or the format's region point).
  bool measure = false;
  /// Empty when the request is possible; else the reason, one line without the file name.
  std::string problem;
};

/// The export rules, in one place:
/// - patches as solids or files only for formats with namedPatches (others keep them as labels);
/// - named solids are ASCII: Solids forces ASCII, and an ASCII export of the whole surface of a
///   namedPatches format is written as named solids;
/// - the sidecar: Auto writes it with every export of patches and for regionPoint formats;
/// - the patches are measured when the sidecar is written or the format takes a region point.
MeshExportRules ResolveMeshExport(const MeshFormat& format, const MeshExportRequest& request);

} // namespace bender

#endif
