#ifndef bender_MeshWriters_h
#define bender_MeshWriters_h

// Internal: the writers of the built-in rows of the mesh-format table (MeshFormats.h), one per
// format, each of the MeshWriter form: mesh into `file` (WriteMesh's temporary file), false
// with a one-line problem on failure.

#include "MeshIO.h"

#include <string>

class vtkPolyData;

namespace bender
{
namespace io_detail
{

/// STL, binary or ASCII per options (polygons and strips triangulated; float).
bool WriteStlMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);
/// Wavefront OBJ (float).
bool WriteObjMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);
/// PLY, binary little endian (float).
bool WritePlyMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);
/// VTK XML PolyData: appended raw binary, zlib, double kept, all arrays.
bool WriteVtpMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);
/// Legacy VTK polydata: binary, version 5.1, double kept, all arrays.
bool WriteLegacyVtkMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);
/// OFF: ASCII, shortest decimals that read back bit-identical.
bool WriteOffMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);
/// TetGen .smesh / .poly of the labelled surface (TetgenExport.h) as it is (frame LPS, unit
/// mm stated), without a region point.
bool WriteSmeshMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);
bool WritePolyMesh(vtkPolyData* mesh,
  const std::string& file,
  const MeshWriteOptions& options,
  std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
