#ifndef bender_MeshIO_h
#define bender_MeshIO_h

#include "BenderErrors.h"
#include "FileIdentity.h"
#include "MeshUnit.h"

#include <vtkSmartPointer.h>

#include <stdexcept>
#include <string>

class vtkPolyData;

namespace bender
{

/// A mesh file that cannot be read or written. what() is one line that names the file and the
/// problem, e.g. "cow.off: line 12: expected 3 coordinates".
class MeshIOError : public InputError
{
public:
  using InputError::InputError;
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
  /// e.g. "bender: LPS mm"). Truncated to what the format allows: binary STL's 80-byte
  /// header (prefixed "# " when it starts with "solid", which would make readers take the
  /// file for ASCII), ASCII STL's "solid" line, the legacy .vtk title line, a "#" comment
  /// line in .off and .obj, a PLY "comment" line. Newlines become spaces. Not stored in .vtp
  /// (an export states its unit in the field data instead).
  std::string header;
};

/// Reads a surface mesh; the format is the row of the mesh-format table (MeshFormats.h) for
/// the extension (case-insensitive). The built-in readable formats:
/// .stl (binary or ASCII; exactly coincident corners welded into shared vertices, degenerate
/// triangles dropped), .obj, .ply, .vtp, .vtk (legacy polydata, every point and cell array),
/// .off (ASCII; also COFF/NOFF/CNOFF/STOFF, extra vertex and face columns ignored, comments
/// anywhere, counts on the keyword line or the next). Coordinates keep the file's precision
/// (double for .vtp, .vtk and .off; float for STL, OBJ, PLY).
/// Throws MeshIOError for a missing, unreadable, truncated or corrupt file, an unknown
/// extension, coordinates that are not finite or beyond single precision (CoordinateRange.h,
/// also for the double-precision formats), cell indices out of range or a file with no points;
/// what() is one line starting with the file's base name. VTK's own messages are collected
/// into that line instead of stderr (the VTK output window is redirected while a file is
/// read, so reads and writes of meshes run one at a time across threads).
/// A mesh with points but no polygons is returned as is (callers decide).
/// Always in LPS millimetres: a file that states metres (an export of Bender's, MeshUnit.h) is
/// scaled by 1000, one that states RAS has x and y negated.
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path);
/// The same, and what the file states (unit "m", "mm"; frame "LPS", "RAS"; empty when none) in
/// `stated`.
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, StatedSpace& stated);

/// Writes a surface mesh; the format is the row of the mesh-format table (MeshFormats.h) for
/// the extension. The built-in writable formats: .stl (binary or ASCII per
/// options; polygons and strips triangulated; float), .obj (float), .ply (binary little
/// endian, float), .vtp (appended raw binary, zlib, double kept, all arrays), .vtk (legacy
/// binary, version 5.1, double kept, all arrays), .off (ASCII, shortest decimals that read
/// back bit-identical; polygons and strips, no vertex or line cells), .smesh and .poly (TetGen,
/// TetgenExport.h, without a region point).
/// Atomic: writes a temporary file beside the target, flushes it to disk and renames it
/// over the target, so a failure leaves the previous file (if any) and no partial or
/// temporary file. Throws MeshIOError (unknown extension, missing or unwritable folder, a
/// folder at the target, a null mesh or one without points, coordinates that are not finite
/// or beyond single precision (CoordinateRange.h, in every format), no triangles for STL, a
/// writer error).
void WriteMesh(vtkPolyData* mesh, const std::string& path, const MeshWriteOptions& options = {});

} // namespace bender

#endif
