#ifndef bender_BenderMeshCheck_h
#define bender_BenderMeshCheck_h

#include "MeshTopology.h"

#include <vtkType.h>

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

class vtkPolyData;

namespace bender
{

struct MeshCheckOptions
{
  /// Open boundaries count as problems (a surface meant to be watertight). Default false:
  /// vessel surfaces are open at their inlets and outlets; boundaries are then reported only.
  bool requireClosed = false;
  /// Look for self-intersections (uniform grid + triangle-triangle tests). Default true.
  bool selfIntersections = true;
  /// At most this many example pairs / ids are kept in the lists of the report.
  std::size_t maxExamples = 10;
};

/// Edge-length or angle statistics; all 0 when there is nothing to measure.
struct MeshStatistic
{
  double min = 0.0;
  double mean = 0.0;
  double max = 0.0;
};

/// What a CFD engineer checks before meshing a surface (issue 6). Polygons are counted as the
/// triangles of their fans and strips as their triangles; vertices and lines are ignored.
/// Lengths in the mesh's unit (mm for Bender's vessels), angles in degrees.
struct MeshCheckReport
{
  vtkIdType points = 0;    ///< points of the mesh
  vtkIdType triangles = 0; ///< triangles after fanning polygons / converting strips
  vtkIdType unusedPoints = 0;
  vtkIdType components = 0; ///< edge-connected components of triangles
  vtkIdType boundaryEdges = 0;
  std::vector<vtkIdType> boundaryLoops; ///< edges of each boundary loop (open vessel ends)
  vtkIdType nonManifoldEdges = 0;       ///< edges with 3 or more triangles
  vtkIdType nonManifoldVertices = 0;    ///< vertices whose triangles form 2+ separate fans
  vtkIdType inconsistentEdges = 0;      ///< manifold edges traversed the same way by both triangles
  vtkIdType degenerateTriangles = 0;    ///< repeated vertex or area <= 1e-14 * diagonal^2
  vtkIdType selfIntersections = 0;      ///< intersecting pairs of triangles sharing no vertex
  std::vector<std::pair<vtkIdType, vtkIdType>> intersectingPairs; ///< examples (triangle ids)
  bool selfIntersectionsChecked = false;
  bool closed = false; ///< no boundary and no non-manifold edge
  double area = 0.0;   ///< total area
  double volume = 0.0; ///< enclosed volume (signed: < 0 when the triangles face inwards);
                       ///< only meaningful when closed
  MeshStatistic edgeLength;
  MeshStatistic minimumAngle; ///< per-triangle minimum angle, degrees
  /// With a mesh before the warp (same points and triangles in the same order): triangles
  /// whose orientation flipped relative to the local motion (on a fold, or against the
  /// best-fitting local rotation: space inversion, paper 3.8; see BenderMeshCheck.cxx).
  bool flipsChecked = false;
  vtkIdType flippedTriangles = 0;
  std::string flipsNote; ///< why flips were not checked, when they were not
  vtkIdType nonFinitePoints = 0;

  /// The problems found, one short sentence each; empty for a clean mesh.
  std::vector<std::string> problems;
  bool Clean() const { return this->problems.empty(); }
};

/// Checks a surface. `before` (optional) is the same surface before a warp, for flips.
/// Never throws on empty, non-manifold or NaN-containing meshes (NaN points are counted and
/// reported, and the geometric measures skip the triangles that use them).
MeshCheckReport CheckMesh(vtkPolyData* mesh,
  vtkPolyData* before = nullptr,
  const MeshCheckOptions& options = {});

/// The report as a JSON object: "mesh" (name), "clean", the counts, "boundaryLoops" (edges of
/// each loop), "selfIntersections", "volume" and "flippedTriangles" (null when not checked or
/// not closed), "edgeLength" and "minimumAngleDegrees" ({min, mean[, max]}), "problems".
nlohmann::ordered_json ToJson(const MeshCheckReport& report, const std::string& name);

/// The report as human-readable lines, and as ToJson's text (two-space indent, one member
/// per line, ending with a newline).
std::string FormatReportText(const MeshCheckReport& report, const std::string& name);
std::string FormatReportJson(const MeshCheckReport& report, const std::string& name);

} // namespace bender

#endif
