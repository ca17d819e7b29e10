#ifndef bender_MeshCheckPasses_h
#define bender_MeshCheckPasses_h

// Internal to CheckMesh (BenderMeshCheck.h): its two costly passes, each in its own file.

#include "BenderMeshCheck.h"
#include "Vec3.h"

#include <vtkPolyData.h>

#include <cstdint>
#include <vector>

namespace bender
{
namespace mesh_check
{

/// Point i of mesh.
inline Vec3 PointOf(vtkPolyData* mesh, vtkIdType i)
{
  double x[3];
  mesh->GetPoint(i, x);
  return { x[0], x[1], x[2] };
}

/// The triangles (point ids, three per triangle; `usable` per triangle) turned inside out from
/// `before` (the same points and triangles before the warp) to `after` (MeshInversions.cxx).
vtkIdType CountInvertedTriangles(const std::vector<std::int64_t>& tris,
  const std::vector<std::uint8_t>& usable,
  vtkPolyData* before,
  const std::vector<Vec3>& after);

/// Pairs of usable triangles that cross each other, into report (selfIntersections,
/// intersectingPairs up to maxExamples, selfIntersectionsChecked) (MeshSelfIntersections.cxx).
void CheckSelfIntersections(const std::vector<std::int64_t>& tris,
  const std::vector<Vec3>& pts,
  const std::vector<std::uint8_t>& usable,
  std::size_t maxExamples,
  MeshCheckReport& report);

} // namespace mesh_check
} // namespace bender

#endif
