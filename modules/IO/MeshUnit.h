#ifndef bender_MeshUnit_h
#define bender_MeshUnit_h

// The length unit a mesh file written by Bender states, and reading it in millimetres (the one
// unit of a session, of plans and of every measure). An export in metres says so where its
// format has room (ExportHeader's "bender export: frame LPS, unit m"): the binary STL header,
// the ASCII STL "solid" line or the first "endsolid" line (named solids), the legacy VTK title
// line, a "#" comment line of OFF, OBJ and TetGen files, a PLY "comment" line, and the field
// data "Unit" of VTK XML polydata. ReadMesh reads every such file back in millimetres.

#include <string>

class vtkPolyData;

namespace bender
{

/// The unit `mesh`, just read from the file at `path`, is stated in: the field data "Unit"
/// when present, else the header or comments of the file as Bender writes them (its first
/// 4 KiB, and the first "endsolid" line of an ASCII STL). "m" or "mm"; empty when the file
/// states none (read as millimetres).
std::string StatedLengthUnit(const std::string& path, vtkPolyData* mesh);

/// Puts `mesh`, just read from `path`, in millimetres: a file that states metres has its points
/// multiplied by 1000 and its field data "Unit", if any, set to "mm" (so that writing it again
/// does not state metres). Returns the stated unit (StatedLengthUnit).
std::string ToMillimetres(const std::string& path, vtkPolyData* mesh);

} // namespace bender

#endif
