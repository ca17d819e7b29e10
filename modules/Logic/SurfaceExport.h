#ifndef bender_SurfaceExport_h
#define bender_SurfaceExport_h

#include "BenderMeshCheck.h"
#include "BenderStlExport.h"
#include "MeshIO.h"

#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// How a surface is exported for CFD or printing. The format follows the file extension:
/// .stl (binary or ASCII), .vtp, .ply, .obj (also .vtk, .off).
struct ExportOptions
{
  StlEncoding stlEncoding = StlEncoding::Binary;
  /// Coordinate frame and unit of the exported coordinates, stated in the file header where the
  /// format has one and in the messages. The surface is LPS millimetres; "RAS" negates x and y.
  std::string frame = "LPS";
  std::string unit = "mm";
  /// Close the planar-ish open ends (vessel inlets and outlets) with flat caps, labelled in the
  /// "PatchId" cell array (wall 0, caps 1..n; kept in .vtp).
  bool cap = false;
  /// For .stl: one file of the whole surface (Single; binary or ASCII per stlEncoding), one
  /// ASCII file with a named solid per patch (Solids), or one file per patch (Files).
  StlPatchMode patches = StlPatchMode::Single;
  /// A file that must never be written (the user's input surface): with one file per patch
  /// the names derive from the output path, and none of them may be this file.
  std::string protectedPath;
};

/// "bender: frame LPS, unit mm" (the header written into STL/OBJ/PLY files).
std::string ExportHeader(const ExportOptions& options);

/// The check shown before writing: watertightness, manifoldness, self-intersections and, with
/// `before` of the same points and triangles (the surface before the warps), flipped triangles.
/// `before` with another topology (after subdivision) is ignored for flips.
MeshCheckReport CheckForExport(vtkPolyData* surface, vtkPolyData* before);

/// Writes atomically (through bender::WriteMesh, or bender::ExportStl for patches). Returns the
/// files written. Throws MeshIOError or StlExportError naming the file, or std::runtime_error
/// when capping fails.
std::vector<std::string> ExportSurface(
  vtkPolyData* surface, const std::string& path, const ExportOptions& options);

} // namespace bender

#endif
