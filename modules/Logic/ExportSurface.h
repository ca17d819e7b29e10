#ifndef bender_ExportSurface_h
#define bender_ExportSurface_h

#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "BenderStlExport.h"
#include "LabelledSurface.h"
#include "MeshIO.h"
#include "PatchSidecar.h"
#include "TetgenExport.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

namespace bender
{

/// Options of ExportSurface, the one export of Bender (GUI, session, bender-cli export).
/// The format follows the extension of `output`: every writable row of the mesh-format table
/// (MeshFormats.h; the rules of ResolveMeshExport apply): .stl (binary, ASCII, named solids or
/// one file per patch), .vtp and .vtk (keep the labels of PatchLabels.h: CellEntityIds,
/// ModelFaceID and the names and types in field data, plus the field data strings Unit and
/// Frame), .smesh and .poly (TetGen: facet markers = CellEntityIds, TetgenExport.h), .ply, .obj,
/// .off.
struct ExportSurfaceOptions
{
  std::string output;
  /// Coordinate frame of the written coordinates. The surface is LPS millimetres; RAS negates
  /// x and y (a half turn about z: orientation and volume are kept). Stated in the header.
  StlFrame frame = StlFrame::LPS;
  /// Unit of the written coordinates: "mm" (as the surface) or "m" (divided by 1000), stated
  /// where the format allows (STL header, VTP field data Unit, TetGen comment, sidecar).
  std::string unit = "mm";
  /// .stl of the whole surface: binary (default) or ASCII (written as named solids). Named
  /// solids (StlPatchMode::Solids) are always ASCII: callers offering "STL (binary)" must
  /// not combine it with named solids without saying so (ExportPanel switches the format).
  StlEncoding stlEncoding = StlEncoding::Binary;
  /// .stl only: one file (Single), one ASCII file with a solid per patch named by the patch
  /// (Solids), or one binary file per patch (Files, OUT_<name>.stl, rims shared bit for bit).
  /// Patches come from the labels of PatchLabels.h (or the legacy PatchId) or from `cap`.
  StlPatchMode patches = StlPatchMode::Single;
  /// Also write the sidecar OUT.patches.json (PatchSidecar.h) with the other files.
  bool patchesJson = false;
  /// Close the planar-ish open ends (vessel inlets and outlets) with flat caps, labelled as
  /// ends. A surface with no open end and no labelled end is refused (nothing to cap).
  bool cap = false;
  /// A loop is capped when its points lie within planarity x its diameter of a plane, [0, 1].
  double planarity = 0.1;
  /// A file that must never be written (the user's input surface), also among the names of
  /// one file per patch.
  std::string protectedPath;
  /// What messages about the surface itself call it (the input's file name, "aneurysm.stl"), so
  /// that a problem of the input is never blamed on the output; empty: "the surface".
  std::string sourceName;
};

/// What was written.
struct ExportSurfaceResult
{
  std::vector<std::string> written; ///< the files, in order (the sidecar last)
  int caps = 0;                     ///< open ends capped
  int skippedLoops = 0;             ///< boundary loops left open (not planar-ish)
  long long triangles = 0;          ///< of the written surface (caps included)
  /// The surface written (caps included), in LPS millimetres.
  vtkSmartPointer<vtkPolyData> surface;
  /// The patches as written (names, ids, types: the patch table of `surface`).
  std::vector<PatchLabel> patches;
  /// Measured for the sidecar, in the written frame and unit (when patchesJson or .smesh/.poly:
  /// the TetGen region point is its insidePoint).
  bool measured = false;
  PatchSidecar sidecar;
};

/// "bender export: frame LPS, unit mm": the header of the written files where the format has one.
std::string ExportHeader(StlFrame frame, const std::string& unit = "mm");

/// The check shown before writing: watertightness, manifoldness, self-intersections and, with
/// `before` of the same points and triangles (the surface before the warps), flipped triangles.
/// `before` with another topology (after subdivision) is ignored for flips.
MeshCheckReport CheckForExport(vtkPolyData* surface, vtkPolyData* before);

/// Caps (optionally) and writes `surface` atomically (all files, the sidecar included, or
/// none). Throws InputError naming the file: no surface, an output that is the protected
/// input, patches for a format other than .stl, an unknown unit, --cap with nothing to cap,
/// capping failure, bad labels, an unwritable file.
ExportSurfaceResult ExportSurface(vtkPolyData* surface, const ExportSurfaceOptions& options);
/// ExportSurface with the patch table already read: the same files and result.
ExportSurfaceResult ExportSurface(const LabelledSurface& surface,
  const ExportSurfaceOptions& options);

} // namespace bender

#endif
