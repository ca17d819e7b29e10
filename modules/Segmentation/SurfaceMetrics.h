#ifndef bender_SurfaceMetrics_h
#define bender_SurfaceMetrics_h

#include <cstddef>

class vtkPolyData;

namespace bender
{

/// Distances (mm) from the vertices of one surface to the other surface (closest point on any
/// triangle).
struct DistanceStats
{
  double mean = 0.0;
  double p95 = 0.0;
  double max = 0.0;
  std::size_t samples = 0;
};

struct SurfaceAccuracy
{
  DistanceStats toTruth;   ///< extracted vertices -> truth surface
  DistanceStats fromTruth; ///< truth vertices -> extracted surface
};

/// Surface distance between an extracted surface and the ground truth, both in the same frame.
/// Vertices of either surface closer than `exclusionDistance` mm to `exclude` (may be null:
/// nothing excluded) are left out, e.g. the flat caps that close the cut vessel ends of an open
/// truth surface, where the truth has no wall to compare with. Throws std::invalid_argument
/// for an empty surface or when every vertex is excluded.
SurfaceAccuracy MeasureSurfaceAccuracy(vtkPolyData* extracted,
  vtkPolyData* truth,
  vtkPolyData* exclude = nullptr,
  double exclusionDistance = 0.0);

/// Shape of the triangles: the smallest angle of each triangle (60 deg = equilateral).
struct TriangleQuality
{
  double meanMinAngle = 0.0;       ///< degrees
  double fractionBelow10Deg = 0.0; ///< share of slivers with a smallest angle under 10 degrees
  double fractionBelow30Deg = 0.0;
  std::size_t triangles = 0;
};

TriangleQuality MeasureTriangleQuality(vtkPolyData* surface);

} // namespace bender

#endif
