#ifndef bender_SurfaceExport_h
#define bender_SurfaceExport_h

#include "BenderMeshCheck.h"
#include "MeshIO.h"

#include <string>

class vtkPolyData;

namespace bender
{

/// How a surface is exported for CFD or printing. The format follows the file extension:
/// .stl (binary or ASCII), .vtp, .ply, .obj (also .vtk, .off).
struct ExportOptions
{
  StlEncoding stlEncoding = StlEncoding::Binary;
  /// Coordinate frame and unit of the surface, stated in the file header where the format has
  /// one and in the messages: segmented vessels are LPS millimetres.
  std::string frame = "LPS";
  std::string unit = "mm";
};

/// "bender: frame LPS, unit mm" (the header written into STL/OBJ/PLY files).
std::string ExportHeader(const ExportOptions& options);

/// The check shown before writing: watertightness, manifoldness, self-intersections and, with
/// `before` of the same points and triangles (the surface before the warps), flipped triangles.
/// `before` with another topology (after subdivision) is ignored for flips.
MeshCheckReport CheckForExport(vtkPolyData* surface, vtkPolyData* before);

/// Writes atomically through bender::WriteMesh. Throws MeshIOError naming the file.
void ExportSurface(vtkPolyData* surface, const std::string& path, const ExportOptions& options);

} // namespace bender

#endif
