#ifndef bender_DelaunayTetrahedra_h
#define bender_DelaunayTetrahedra_h

// 3D Delaunay tetrahedralisation of a point cloud, for the centerlines' internal Voronoi
// diagram (VesselCenterlines.cxx).
//
// Method: incremental insertion (Bowyer-Watson), the way the fast Delaunay codes of the field
// work. The points are inserted in a biased randomised order (rounds of doubling size, each
// sorted along a Morton curve), each located by a visibility walk from the previous insertion;
// the tetrahedra whose circumsphere holds the new point are removed and the cavity's boundary
// is joined to the point. Everything starts inside one large tetrahedron whose corners lie at
// least 2.5 bounding-box diagonals from the points.
//
// Robustness: the points are first snapped to an integer grid of 2^22 steps across the large
// tetrahedron, so that the orientation and in-sphere determinants can be evaluated exactly in
// 128-bit integers whenever the double-precision evaluation (with an error bound) cannot tell
// their sign. Exact ties (four co-planar, five co-spherical points: common on voxel surfaces)
// are broken by a symbolic perturbation of the points' lifts that favours the later point
// index, so the result is the Delaunay tetrahedralisation of a perturbed point set and has no
// flat tetrahedra.
//
// What the large tetrahedron leaves out: only tetrahedra whose circumsphere reaches one of its
// corners, that is circumspheres of radius beyond 1.25 bounding-box diagonals (the flat
// tetrahedra along the convex hull). Every tetrahedron with a smaller circumsphere is a
// Delaunay tetrahedron of the points, and every Delaunay tetrahedron of the points with a
// smaller circumsphere is returned.

#include <vtkType.h>

#include <array>
#include <string>
#include <vector>

namespace bender
{

struct DelaunayStatistics
{
  vtkIdType duplicates = 0;    ///< points equal (on the grid) to an earlier one, left out
  vtkIdType exactTests = 0;    ///< predicates the double-precision filter could not decide
  vtkIdType perturbations = 0; ///< exact ties broken by the symbolic perturbation
  double gridStep = 0.0;       ///< the snapping step, in the points' unit
};

/// Delaunay tetrahedra of `points` (indices into it), each positively oriented (its fourth
/// point on the side of the first three to which (b - a) x (c - a) points). The points are
/// moved onto the integer grid the predicates use (by at most half a grid step,
/// DelaunayStatistics::gridStep, about 1.5e-6 of the bounding-box diagonal), so that
/// circumcentres computed afterwards belong to the triangulated positions. Returns false with
/// a one-line reason when there are fewer than four distinct points, non-finite coordinates,
/// or the points are all co-planar.
/// `neighbours`, when given, receives for each tetrahedron the index of the one across the face
/// opposite each of its vertices (-1 where there is none among those returned).
bool DelaunayTetrahedra(std::vector<std::array<double, 3>>& points,
  std::vector<std::array<vtkIdType, 4>>& tetras,
  std::string& error,
  DelaunayStatistics* statistics = nullptr,
  std::vector<std::array<vtkIdType, 4>>* neighbours = nullptr);

/// Qhull's Delaunay of the same points (not moved), kept as the fallback should the incremental
/// one ever report an internal inconsistency, and as the reference of bench_centerlines and the
/// tests. Tetrahedra as Qhull orders them (not oriented). Returns false with Qhull's first
/// message line, or when the build has no Qhull.
/// `neighbours` as for DelaunayTetrahedra (found by matching shared faces).
bool QhullTetrahedra(const std::vector<std::array<double, 3>>& points,
  std::vector<std::array<vtkIdType, 4>>& tetras,
  std::string& error,
  std::vector<std::array<vtkIdType, 4>>* neighbours = nullptr);

} // namespace bender

#endif
