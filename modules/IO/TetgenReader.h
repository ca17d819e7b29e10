#ifndef bender_TetgenReader_h
#define bender_TetgenReader_h

// Internal: the reader of the TetGen rows of the mesh-format table (.smesh and .poly, as
// TetgenExport.h writes them and TetGen reads them): the nodes of part 1 (numbered from 0 or 1,
// attributes and markers skipped), the facets of part 2 as polygons with their boundary marker
// as cell data "CellEntityIds" when the file has markers; holes and regions are not surface.

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <string>

namespace bender
{
namespace io_detail
{

/// Throws MeshIOError naming the file and the line: a count or index that is not a number or
/// out of range, a missing line, non-finite coordinates, nodes kept in a separate .node file.
vtkSmartPointer<vtkPolyData> ReadTetgenMesh(const std::string& path, std::uintmax_t size);

} // namespace io_detail
} // namespace bender

#endif
