#ifndef bender_VesselPhantom_h
#define bender_VesselPhantom_h

#include "Progress.h"
#include "SegmentationErrors.h"
#include "Volume.h"

#include <vtkSmartPointer.h>

#include <cstdint>
#include <vector>

class vtkPolyData;

namespace bender
{

/// How the MRA-like demo volume is made from a vessel surface (ground truth).
struct PhantomParameters
{
  /// Isotropic voxel size, mm. Range [0.1, 2], default 0.4.
  double spacing = 0.4;
  /// Background around the surface's bounding box, mm. Range [0, 50], default 3.
  double margin = 3.0;
  /// Full width at half maximum of the Gaussian point-spread function, mm. Range [0, 5],
  /// default 0.8 (about two voxels, a typical 3D TOF MRA).
  double psfFwhm = 0.8;
  /// Intensities of the lumen and of the surrounding tissue (before bias and noise).
  double vesselIntensity = 400.0;
  double backgroundIntensity = 100.0;
  /// Smooth multiplicative bias field: intensities vary by up to +-biasAmplitude across the
  /// volume (coil sensitivity). Range [0, 0.5], default 0.1.
  double biasAmplitude = 0.1;
  /// Rician noise: the magnitude of the signal plus complex Gaussian noise of this standard
  /// deviation per channel. Range [0, 200], default 15 (SNR 20 in the lumen).
  double noiseSigma = 15.0;
  /// Seed of the noise generator (fixed: the phantom is deterministic).
  std::uint32_t randomSeed = 20240503;
  /// Sub-voxels per axis used to compute the partial-volume fraction. Range [1, 4], default 2.
  int supersampling = 2;
};

struct Phantom
{
  /// The MRA-like volume (float, LPS mm = the surface's coordinates, identity direction).
  Volume volume;
  /// The truth surface with its open vessel ends closed by flat caps: the solid that was
  /// voxelized. Points and triangles of the input come first; the caps follow.
  vtkSmartPointer<vtkPolyData> cappedTruth;
  /// Only the caps (empty when the input was closed): the accuracy measure excludes their
  /// neighbourhood, where the truth has no vessel wall.
  vtkSmartPointer<vtkPolyData> caps;
  /// A point deep inside the lumen (LPS mm): a seed for the threshold method.
  Point3 seed{ { 0, 0, 0 } };
  /// One point per capped vessel end, 3 mm inside the vessel from the cap centre: seeds on
  /// tubular parts (for the vesselness method, which ignores the round aneurysm sac).
  std::vector<Point3> vesselSeeds;
  /// The threshold halfway between background and lumen intensity.
  double midIntensity = 0.0;
};

/// Builds the demo volume: caps the open ends of `surface` (vtkFillHolesFilter), voxelizes the
/// closed solid with vtkPolyDataToImageStencil at spacing/supersampling, averages sub-voxels to
/// a partial-volume fraction, blurs with the PSF, applies the bias field and Rician noise.
/// Deterministic for given parameters. Throws ParameterError (parameter outside its range, empty
/// surface, more than 2e8 voxels), SegmentationCancelled.
Phantom MakeVesselPhantom(vtkPolyData* surface,
  const PhantomParameters& parameters = {},
  const ProgressReporter& progress = {});

} // namespace bender

#endif
