#ifndef bender_PlyValidation_h
#define bender_PlyValidation_h

// Internal: a whitelist check of PLY files before vtkPLYReader sees them. VTK 9.1's reader
// and the vtkPLY library under it trust the file (a missing header word, a face before the
// vertices, an element between them, a control byte in a record, a wrong index or a truncated
// body crash them), so only what they read safely is accepted: the grammar, the elements and
// every record are checked (PlyValidation.cxx lists the rules).

#include <cstdint>
#include <string>

namespace bender
{
namespace io_detail
{

/// True when the file at path is a PLY file (ASCII or binary, either endianness) within the
/// whitelist: a header in vtkPLY's grammar, a "vertex" element with x, y, z, an optional
/// "face" element after it with one vertex_indices (or vertex_index) list, other elements
/// after those, and a body that holds exactly the records announced, each matching its
/// declared types (faces of 3 to 255 vertices, indices below the vertex count). Otherwise
/// false with problem set ("truncated binary PLY (element \"face\" record 12 of 40 ends past
/// the end of the file)", "PLY face element before the vertex element", ...).
bool CheckPlyStructure(const std::string& path, std::string& problem);

/// The same check on the file's bytes (for the fuzz harness). ASCII bodies must hold one
/// record per line (as vtkPLY reads them), every line shorter than 4000 bytes, of printable
/// ASCII and tabs.
bool CheckPlyBytes(const std::string& data, std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
