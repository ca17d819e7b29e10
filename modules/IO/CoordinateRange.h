#ifndef bender_CoordinateRange_h
#define bender_CoordinateRange_h

// The one range rule for the coordinates of every mesh Bender reads or writes: each coordinate
// finite and representable in single precision (|x| <= FLT_MAX, about 3.4e38), in the written
// frame and unit. STL, OBJ and PLY store floats, where a larger double becomes inf; a surface
// that far out is a corrupt file, not anatomy, and the volumes and areas measured from it
// overflow. ReadMesh applies it to every file read, WriteMesh and the STL exports (after the
// frame and unit change) to everything written.

#include <vtkType.h>

#include <limits>
#include <string>

class vtkPolyData;

namespace bender
{

/// The largest coordinate magnitude a mesh may have: the largest finite float.
constexpr double MaxMeshCoordinate = static_cast<double>(std::numeric_limits<float>::max());

/// True when value is finite and |value| <= MaxMeshCoordinate.
bool InMeshCoordinateRange(double value);

/// True when every component of p is in range.
bool InMeshCoordinateRange(const double p[3]);

/// Empty when every component of p is in range; otherwise the one-line problem with the
/// first offending component: "non-finite coordinate (nan)" or "coordinate -1e+308 is beyond
/// the single-precision range (|x| <= 3.40282e+38)".
std::string CoordinateRangeProblem(const double p[3]);

/// Empty when every point of mesh is in range (a null mesh or one without points is);
/// otherwise "point 12: " followed by CoordinateRangeProblem of its first point out of range.
std::string MeshCoordinateRangeProblem(vtkPolyData* mesh);

} // namespace bender

#endif
