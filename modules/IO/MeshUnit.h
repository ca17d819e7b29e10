#ifndef bender_MeshUnit_h
#define bender_MeshUnit_h

// The length unit and the frame a mesh file written by Bender states, and reading it in LPS
// millimetres (the one space of a session, of plans and of every measure). An export says both
// where its format has room (ExportHeader's "bender export: frame RAS, unit m"): the binary STL
// header, the ASCII STL "solid" line or the first "endsolid" line (named solids), the legacy
// VTK title line, a "#" comment line of OFF, OBJ and TetGen files, a PLY "comment" line, and
// the field data "Unit" and "Frame" of VTK polydata. ReadMesh reads every such file back in
// LPS millimetres.

#include <string>

class vtkPolyData;

namespace bender
{

/// What a file states about its coordinates.
struct StatedSpace
{
  std::string unit;  ///< "m" or "mm"; empty when the file states none (read as millimetres)
  std::string frame; ///< "LPS" or "RAS"; empty when the file states none (read as LPS)
};

/// The unit and frame `mesh`, just read from the file at `path`, is stated in: the field data
/// "Unit" and "Frame" when present, else the header or comments of the file as Bender writes
/// them (its first 4 KiB, and the first "endsolid" line of an ASCII STL).
StatedSpace StatedCoordinates(const std::string& path, vtkPolyData* mesh);

/// Puts `mesh`, just read from `path`, in LPS millimetres: a file that states RAS has x and y
/// of its points negated (the half turn about z the export made), one that states metres has
/// its points multiplied by 1000; its field data "Unit" and "Frame", if any, then say "mm" and
/// "LPS" (so that writing it again states what it holds). Returns what the file stated.
StatedSpace ToLpsMillimetres(const std::string& path, vtkPolyData* mesh);

} // namespace bender

#endif
