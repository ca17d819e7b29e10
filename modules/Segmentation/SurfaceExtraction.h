#ifndef bender_SurfaceExtraction_h
#define bender_SurfaceExtraction_h

#include "Progress.h"
#include "SegmentationErrors.h"
#include "Volume.h"

#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

enum class SurfaceExtractor
{
  /// vtkFlyingEdges3D at iso-value 0.5 of the mask (multi-threaded). Default: its marching cubes
  /// ran 6.5-11x faster than the ITK extractor at equal accuracy, with 28 % fewer triangles
  /// (docs/segmentation.md).
  Vtk,
  /// ITK's marching cubes, itk::BinaryMask3DMeshSource, converted to vtkPolyData.
  Itk
};

/// Parameters of ExtractSurface.
struct SurfaceParameters
{
  SurfaceExtractor extractor = SurfaceExtractor::Vtk;
  /// The one smoothing knob, range [0, 1], default 0.5: 0 = the raw marching-cubes staircase,
  /// 1 = strongest. Windowed-sinc (non-shrinking) smoothing, 20 iterations, pass band
  /// 10^(-4 * smoothing) as in 3D Slicer.
  double smoothing = 0.5;
  /// Decimate to about this many triangles (quadric decimation, volume preserving);
  /// 0 (default) = keep all. Ignored when the surface already has fewer.
  std::size_t targetTriangles = 0;
  /// LPS mm. The connected surface pieces nearest to these points are kept; empty (default):
  /// the piece with the most triangles.
  std::vector<Point3> seeds;
};

/// Wall-clock time of one stage, seconds.
struct StageTime
{
  std::string stage;
  double seconds = 0.0;
};

struct SurfaceResult
{
  /// Triangles in LPS mm, consistently ordered so that normals point out of the lumen; point
  /// normals in the "Normals" array.
  vtkSmartPointer<vtkPolyData> surface;
  /// Edges used by one triangle only. 0 for a closed surface (the mask is zero-padded, so the
  /// surface also closes where the vessels leave the volume).
  std::size_t boundaryEdges = 0;
  /// Edges used by more than two triangles.
  std::size_t nonManifoldEdges = 0;
  std::vector<StageTime> timings;
};

/// Extracts the lumen surface of a mask: crop to the mask with a zero border, marching cubes
/// (the chosen extractor), keep the seeded piece, smoothing, decimation, image -> LPS transform
/// (spacing, origin and direction matrix; a left-handed direction keeps normals outward),
/// consistent outward normals. Throws ParameterError (smoothing outside [0, 1], empty mask),
/// SegmentationError (extractor failure), SegmentationCancelled.
SurfaceResult ExtractSurface(const LabelMap& mask,
  const SurfaceParameters& parameters,
  const ProgressReporter& progress = {});

} // namespace bender

#endif
