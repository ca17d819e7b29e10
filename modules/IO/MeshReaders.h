#ifndef bender_MeshReaders_h
#define bender_MeshReaders_h

// Internal: the readers of the built-in rows of the mesh-format table (MeshFormats.h), one per
// format, each of the MeshReader form: the file at path, of size bytes, checked before a VTK
// reader sees it. Throw MeshIOError naming the file.

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <string>

namespace bender
{
namespace io_detail
{

/// Binary or ASCII STL; exactly coincident corners welded into shared vertices.
vtkSmartPointer<vtkPolyData> ReadStlMesh(const std::string& path, std::uintmax_t size);
/// Wavefront OBJ (vertex lines checked with their line numbers).
vtkSmartPointer<vtkPolyData> ReadObjMesh(const std::string& path, std::uintmax_t size);
/// PLY (header and element sizes checked).
vtkSmartPointer<vtkPolyData> ReadPlyMesh(const std::string& path, std::uintmax_t size);
/// VTK XML PolyData.
vtkSmartPointer<vtkPolyData> ReadVtpMesh(const std::string& path, std::uintmax_t size);
/// Legacy VTK polydata, every point and cell array.
vtkSmartPointer<vtkPolyData> ReadLegacyVtkMesh(const std::string& path, std::uintmax_t size);
/// OFF (OffFormat.h).
vtkSmartPointer<vtkPolyData> ReadOffMesh(const std::string& path, std::uintmax_t size);

} // namespace io_detail
} // namespace bender

#endif
