#ifndef bender_CapTriangulation_h
#define bender_CapTriangulation_h

// Internal to vtkBenderCapFilter: the flat cap of one rim, in the rim's plane (2D coordinates
// along the plane's axes, the units of the surface). The rim is checked first (RimProblem):
// vtkDelaunay2D is only handed simple polygons, as a degenerate or self-overlapping boundary
// makes it read outside its own arrays.

#include <array>
#include <string>
#include <vector>

namespace bender
{
namespace cap_detail
{

using P2 = std::array<double, 2>;
using Tri = std::array<int, 3>;

/// Twice the signed area of the triangle o, a, b (positive counter-clockwise).
double Cross2(const P2& o, const P2& a, const P2& b);

/// Smallest angle of a triangle, degrees (0 for a degenerate one).
double MinAngle2(const P2& a, const P2& b, const P2& c);

/// Empty when rim (a closed polygon, vertex i joined to i + 1 and the last to the first) is a
/// simple polygon that can be triangulated: at least 3 vertices, no edge shorter than 1e-9 of
/// the rim's extent (coincident or nearly coincident vertices), an area above 1e-9 of its
/// extent squared, no vertex where the rim turns straight back, and no two edges that cross or
/// touch other than neighbours at their shared vertex. Otherwise one line naming the problem
/// with the rim's vertex positions (0-based): "its edges 2-3 and 7-8 cross (...)".
std::string RimProblem(const std::vector<P2>& rim);

/// The cap of a counter-clockwise rim that RimProblem accepts: interior points and
/// counter-clockwise triangles (ids 0..m-1 the rim, m.. the interior points). The cap is a
/// constrained Delaunay triangulation of the rim and of a triangular lattice of the rim's mean
/// edge length, smoothed three times. False when no triangulation covers the rim.
bool TriangulateCap(const std::vector<P2>& rim, std::vector<P2>& interior, std::vector<Tri>& tris);

} // namespace cap_detail
} // namespace bender

#endif
