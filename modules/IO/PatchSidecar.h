#ifndef bender_PatchSidecar_h
#define bender_PatchSidecar_h

// The sidecar OUT.patches.json of a mesher export: what a CFD case needs to know about each
// patch (name, label, role, centre, outward normal, area, equivalent diameter), a point inside
// the lumen (snappyHexMesh's locationInMesh, TetGen's region point) and the unit and frame of
// the coordinates, all in the coordinates of the exported files.

#include "AtomicFile.h"
#include "BenderStlExport.h"

#include <array>
#include <string>
#include <vector>

namespace bender
{

/// One patch measured (ComputePatchSidecar: the one measure of Bender's patches, for the
/// sidecar, the TetGen region point and the OpenFOAM case).
struct PatchGeometry
{
  PatchLabel label;
  std::size_t triangles = 0;
  double area = 0.0;
  /// Sum over the patch's triangles of area x centroid (centre = areaMoment / area), so that a
  /// change of unit scales the sum before the division, as the case's metres do.
  std::array<double, 3> areaMoment{ { 0.0, 0.0, 0.0 } };
  /// Area-weighted centroid of the patch's triangles.
  std::array<double, 3> centre{ { 0.0, 0.0, 0.0 } };
  /// Sum of the triangles' area vectors, turned outwards (the wall's too: nearly cancelled).
  std::array<double, 3> vectorArea{ { 0.0, 0.0, 0.0 } };
  /// Unit area-weighted normal pointing out of the enclosed volume; only for the ends (the
  /// wall's normals cancel), and only when the patch is not degenerate.
  bool hasNormal = false;
  std::array<double, 3> normal{ { 0.0, 0.0, 0.0 } };
  /// Diameter of the disc of the same area, sqrt(4 area / pi); ends only (0 for the wall).
  double equivalentDiameter = 0.0;
};

struct PatchSidecar
{
  std::string unit = "mm";
  StlFrame frame = StlFrame::LPS;
  /// Every edge shared by exactly two triangles (the inside point needs a closed surface).
  bool closed = false;
  /// Enclosed volume (positive; the normals above are outward whatever the triangle order).
  double volume = 0.0;
  bool hasInsidePoint = false;
  /// A point inside the lumen, far from the wall (FindLumenPoint of InsidePoint.h: the best of
  /// midpoints between the surface and the first surface hit along the inward normal, from
  /// each end's centre and from wall triangles, each verified inside by its winding number).
  std::array<double, 3> insidePoint{ { 0.0, 0.0, 0.0 } };
  /// Distance from insidePoint to the surface.
  double insideClearance = 0.0;
  std::vector<PatchGeometry> patches;
};

/// Measures the patches of mesh (its patch table, read once by ReadLabelledSurface) in the
/// coordinates of transform. Throws StlExportError (no triangles, non-finite coordinates, a
/// cell array CellPatchIds refuses).
PatchSidecar ComputePatchSidecar(const LabelledSurface& mesh, const ExportTransform& transform);

/// The JSON text: {"format": "bender-patches", "version": 1, "unit", "frame", "closed",
/// "volume", "insidePoint" (null when none was found), "patches": [{"name", "id", "type",
/// "triangles", "area", "centre", "normal" (null for the wall), "equivalentDiameter" (null for
/// the wall)}]}.
std::string PatchSidecarJson(const PatchSidecar& sidecar);

/// OUT.patches.json beside an export OUT.<ext> ("vessel.stl" -> "vessel.patches.json").
std::string PatchSidecarPath(const std::string& exportPath);

/// The sidecar of mesh as a producer for AtomicWriteAll (measured now; throws like
/// ComputePatchSidecar with the file's base name first).
AtomicFile PatchSidecarFile(const LabelledSurface& mesh,
  const std::string& path,
  const ExportTransform& transform,
  PatchSidecar* measured = nullptr);

} // namespace bender

#endif
