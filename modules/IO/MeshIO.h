#ifndef bender_MeshIO_h
#define bender_MeshIO_h

#include <vtkSmartPointer.h>

#include <stdexcept>
#include <string>

class vtkPolyData;

namespace bender
{

/// A mesh file that cannot be read or written. what() is one line that names the file and the
/// problem, e.g. "cow.off: line 12: expected 3 coordinates".
class MeshIOError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

enum class StlEncoding
{
  Binary,
  Ascii
};

struct MeshWriteOptions
{
  StlEncoding stlEncoding = StlEncoding::Binary;
  /// Written into the STL header / file comment where the format has one (frame and unit,
  /// e.g. "bender: LPS mm"). Truncated to what the format allows.
  std::string header;
};

/// Reads a surface mesh; the format is chosen by the extension (case-insensitive):
/// .stl (binary or ASCII; vertices welded on reading), .obj, .ply, .vtp, .vtk (polydata),
/// .off. Throws MeshIOError for a missing, unreadable, truncated or corrupt file, an unknown
/// extension, non-finite coordinates or a file with no points.
/// A mesh with points but no polygons is returned as is (callers decide).
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path);

/// Writes a surface mesh; the format is chosen by the extension: .stl, .obj, .ply, .vtp,
/// .vtk, .off. Atomic: writes a temporary file beside the target and renames it over the
/// target, so a failure leaves no partial file. Throws MeshIOError (unknown extension,
/// unwritable folder, non-finite coordinates in the mesh).
void WriteMesh(vtkPolyData* mesh, const std::string& path, const MeshWriteOptions& options = {});

/// True when both paths name the same existing file (same device and inode), or the same
/// path after normalisation. Used to refuse overwriting an input.
bool SameFile(const std::string& a, const std::string& b);

} // namespace bender

#endif
