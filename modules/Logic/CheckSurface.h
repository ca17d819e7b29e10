#ifndef bender_CheckSurface_h
#define bender_CheckSurface_h

#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "LumenGuard.h"

#include <optional>
#include <string>

namespace bender
{

/// Options of CheckSurface: the mesh to check and, optionally, the same mesh before a warp.
struct CheckSurfaceOptions
{
  std::string input;  ///< a mesh file (stl, obj, ply, vtp, vtk, off)
  std::string before; ///< the same points and triangles before a warp (flips); may be empty
  MeshCheckOptions check;
  /// With `before`: the lumen guard too (CheckLumen: both shapes' centerlines, each branch's
  /// minimal radius before and after; `before` may then be remeshed).
  LumenGuardOptions lumen;
};

/// The check a CFD engineer runs before meshing (bender-cli check; the GUI checks its surface
/// with CheckForExport): reads the mesh (and `before`) and returns the report. Throws
/// InputError naming the file when a mesh cannot be read.
MeshCheckReport CheckSurface(const CheckSurfaceOptions& options);

/// CheckSurface's report and, with `before` and options.lumen.enabled, the lumen guard's
/// check of the two shapes (`bender-cli check AFTER --before BEFORE`).
struct SurfaceCheck
{
  MeshCheckReport report;
  std::optional<LumenCheck> lumen;
  /// The report is clean and the lumen guard (when run) passed.
  bool Passed() const { return this->report.Clean() && (!this->lumen || this->lumen->Passed()); }
};
SurfaceCheck CheckSurfaceAndLumen(const CheckSurfaceOptions& options);

} // namespace bender

#endif
