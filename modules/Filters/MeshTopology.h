#ifndef bender_MeshTopology_h
#define bender_MeshTopology_h

// Topology of triangle surfaces shared by the mesh check, the cap filter, the surface
// extraction and the centerline code: triangles of a polydata, boundary edges and
// boundary loops. Triangles are given as a flat list of point ids, three per triangle, as
// CollectTriangles returns them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

class vtkPolyData;

namespace bender
{

/// Triangles of a polydata (polygons fanned from their first point, strips converted with
/// alternating orientation fixed), as 3 point ids each; vertices and lines are ignored.
std::vector<std::int64_t> CollectTriangles(vtkPolyData* mesh);

/// One undirected edge of a triangle list: its end points (lo < hi) and the triangles using
/// it (uses() of them, in increasing order from first in TriangleEdges::Uses()).
struct MeshEdge
{
  std::int64_t lo = 0;
  std::int64_t hi = 0;
  std::size_t first = 0;
  std::size_t uses = 0;
};

/// One use of an edge by a triangle: forward when the triangle runs from lo to hi.
struct EdgeUse
{
  std::int64_t triangle = 0;
  bool forward = false;
};

/// The undirected edges of a triangle list with the triangles that use each. Edges of
/// repeated points (a triangle (a, a, b)) are not edges and are left out; triangles with ids
/// outside [0, points) are skipped when points >= 0.
class TriangleEdges
{
public:
  explicit TriangleEdges(const std::vector<std::int64_t>& triangles, std::int64_t points = -1);
  /// Sorted by (lo, hi).
  const std::vector<MeshEdge>& Edges() const { return this->EdgeList; }
  const std::vector<EdgeUse>& Uses() const { return this->UseList; }
  /// Boundary edges (one use) directed as their triangle runs.
  std::vector<std::array<std::int64_t, 2>> DirectedBoundary() const;

private:
  std::vector<MeshEdge> EdgeList;
  std::vector<EdgeUse> UseList;
};

/// A chain of boundary edges followed from vertex to vertex.
struct BoundaryChain
{
  /// Vertices in order; a closed loop does not repeat its first vertex.
  std::vector<std::int64_t> vertices;
  /// Came back to its start without passing a vertex where the boundary branches.
  bool closed = false;
  /// Number of edges walked (vertices.size() for a loop, one less for an open chain).
  std::size_t edges = 0;
};

/// Follows directed boundary edges (each used once) into chains: from the smallest remaining
/// vertex, along the edge leaving it, until the start comes back or no edge leaves. Loops
/// of a manifold, consistently oriented surface come out closed; at a vertex where two
/// loops touch, or where the orientation is inconsistent, chains are open or not closed.
std::vector<BoundaryChain> FollowBoundary(std::vector<std::array<std::int64_t, 2>> directed);

/// The boundary loops of a triangle list (its open ends), in order of their smallest vertex.
std::vector<BoundaryChain> BoundaryLoops(const std::vector<std::int64_t>& triangles,
  std::int64_t points = -1);

/// Edge-connected components of the triangles: a label per triangle, 0, 1, ... in order of
/// each component's first triangle; count set to the number of components.
std::vector<std::int64_t> TriangleComponents(const std::vector<std::int64_t>& triangles,
  std::size_t& count,
  std::int64_t points = -1);

} // namespace bender

#endif
