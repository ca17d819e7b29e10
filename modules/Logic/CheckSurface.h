#ifndef bender_CheckSurface_h
#define bender_CheckSurface_h

#include "BenderErrors.h"
#include "BenderMeshCheck.h"

#include <string>

namespace bender
{

/// Options of CheckSurface: the mesh to check and, optionally, the same mesh before a warp.
struct CheckSurfaceOptions
{
  std::string input;  ///< a mesh file (stl, obj, ply, vtp, vtk, off)
  std::string before; ///< the same points and triangles before a warp (flips); may be empty
  MeshCheckOptions check;
};

/// The check a CFD engineer runs before meshing (bender-cli check; the GUI checks its surface
/// with CheckForExport): reads the mesh (and `before`) and returns the report. Throws
/// InputError naming the file when a mesh cannot be read.
MeshCheckReport CheckSurface(const CheckSurfaceOptions& options);

} // namespace bender

#endif
