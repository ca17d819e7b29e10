#ifndef bender_VesselSegmentation_h
#define bender_VesselSegmentation_h

#include "Progress.h"
#include "SegmentationErrors.h"
#include "Volume.h"

#include <limits>
#include <vector>

namespace bender
{

enum class SegmentationMethod
{
  /// Intensity window + seeded connected region (bright lumen of an MRA/CTA).
  Threshold,
  /// Multi-scale Hessian (Frangi) vesselness, thresholded, then seeded as Threshold.
  Vesselness
};

/// Parameters of SegmentVessels. Defaults work on the demo phantom (bender-cli phantom).
struct SegmentationParameters
{
  SegmentationMethod method = SegmentationMethod::Threshold;

  /// Threshold: intensity window [lower, upper] of the lumen, in the volume's units.
  /// Default 250 fits the phantom (background ~100, lumen ~400). Any finite lower <= upper.
  double lower = 250.0;
  double upper = std::numeric_limits<double>::max();

  /// Seeds, LPS mm. The components of the window that contain a seed are kept; each seed must
  /// lie in the volume and inside the window (else SeedError). Empty: the largest component.
  std::vector<Point3> seeds;

  /// Fill cavities enclosed by the lumen (noise dropouts, calcifications). Default on.
  bool fillHoles = true;
  /// Morphological closing radius, mm; 0 (default) = off. Range [0, 5]. Bridges gaps of up to
  /// about twice the radius; costs time on large volumes.
  double closingRadius = 0.0;

  /// Vesselness: the vessel radii to look for, mm (scales sigma = radius / sqrt(2) over
  /// `scales` log-spaced steps). Ranges: 0.1 <= minRadius <= maxRadius <= 20, scales 1..10.
  double minRadius = 0.5;
  double maxRadius = 2.5;
  int scales = 4;
  /// Vesselness: Frangi's plate (alpha), blob (beta) and structureness (gamma) sensitivities.
  /// Ranges (0, 2], (0, 2], > 0. Defaults 0.5, 0.5, 5 (ITK's).
  double alpha = 0.5;
  double beta = 0.5;
  double gamma = 5.0;
  /// Vesselness: keep voxels whose vesselness, normalised to [0, 1] by its maximum, is at least
  /// this. Range (0, 1), default 0.05. Lower keeps more of the faint, thin vessels and noise.
  double vesselnessThreshold = 0.05;
  /// Vesselness looks for bright tubes (true, MRA/CTA lumen) or dark ones (false, black-blood).
  bool brightVessels = true;

  /// Optional geodesic active contour refinement of the result, 0 (default) = off, otherwise
  /// the number of iterations, range [0, 1000]. Pulls the mask's boundary onto the strongest
  /// edge of the Gaussian-smoothed volume (edge sigma: `levelSetSigma` mm, range (0, 5]).
  int levelSetIterations = 0;
  double levelSetSigma = 0.5;
  /// Balloon force of the refinement (> 0 grows, < 0 shrinks), range [-1, 1].
  double levelSetPropagation = 0.0;
  /// Curvature (smoothness) weight of the refinement, range [0, 5].
  double levelSetCurvature = 1.0;
};

/// Throws ParameterError naming the first parameter outside its documented range.
void ValidateSegmentationParameters(const SegmentationParameters& parameters);

/// Segments the vessels of a volume: a mask on the volume's grid. Throws ParameterError,
/// SeedError (seed outside the volume or in background, message gives the seed, its voxel and
/// its value), SegmentationError (empty result), SegmentationCancelled.
LabelMap SegmentVessels(const Volume& volume,
  const SegmentationParameters& parameters,
  const ProgressReporter& progress = {});

/// The normalised [0, 1] vesselness of a volume (the map SegmentVessels thresholds).
Volume ComputeVesselness(const Volume& volume,
  const SegmentationParameters& parameters,
  const ProgressReporter& progress = {});

} // namespace bender

#endif
