#ifndef bender_SegmentVolume_h
#define bender_SegmentVolume_h

#include "Progress.h"
#include "SurfaceExtraction.h"
#include "VesselPhantom.h"
#include "VesselSegmentation.h"
#include "VolumeIO.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

namespace bender
{

/// Options of SegmentVolume: the volume to read and the parameters of each stage.
struct SegmentVolumeOptions
{
  std::string input; ///< a volume file or DICOM folder (see ReadVolume)
  VolumeReadOptions read;
  SegmentationParameters segmentation;
  SurfaceParameters surface;
  ProgressReporter progress;
  /// Told one sentence when a choice was made for the user before reading (a DICOM folder
  /// holding several series and no UID in `read`: which series is read; ChooseDicomSeries).
  std::function<void(const std::string&)> inform;
};

/// Below this many surface points a segmentation kept implausibly little for a vessel (a
/// threshold above the lumen's intensities, a seed outside the lumen).
constexpr long long MinimumSurfacePoints = 1000;

/// Whether `volume` holds only integers in [0, 255] (non-finite voxels aside; at least one
/// finite voxel): an 8-bit acquisition, whose intensities are not those of a CT or an MRA.
bool IsEightBit(const Volume& volume);

/// The plausibility rule of a segmentation: empty when its surface has at least
/// MinimumSurfacePoints points, else one sentence for the user naming the lumen threshold, the
/// volume (`eightBit`: "an 8-bit volume") and what was kept: the surface's points, or
/// (`surfacePoints` < 0: no surface was made) the mask's `maskVoxels` voxels. What to do about
/// it is each front end's to say (the window's histogram, the command line's --lower).
std::string SegmentationWarning(double threshold,
  bool eightBit,
  std::size_t maskVoxels,
  long long surfacePoints);

/// What a segmentation made: the surface (SurfaceResult: LPS mm, its edges, the timings of
/// every stage), the mask it was extracted from, and SegmentationWarning's sentence (empty
/// when the segmentation is plausible).
struct SegmentVolumeResult : SurfaceResult
{
  std::shared_ptr<const LabelMap> mask;
  std::string warning;
};

/// Segments a loaded volume (SegmentVessels), extracts the surface (ExtractSurface) and judges
/// it (SegmentationWarning): the segment step of the GUI's Segment panel and of SegmentVolume.
/// The timings start with "segmentation", then the surface stages. Throws as SegmentVolume.
SegmentVolumeResult SegmentLoadedVolume(const Volume& volume,
  const SegmentationParameters& segmentation,
  const SurfaceParameters& surface,
  const ProgressReporter& progress = {});

/// The segment workflow of bender-cli: reads the volume, then SegmentLoadedVolume (LPS mm).
/// The series of a DICOM folder is the one of ChooseDicomSeries (read.dicomSeriesUid, else the
/// largest). The result's timings start with "read" and "segmentation", then the surface
/// stages. Throws the segmentation module's errors (VolumeReadError, ParameterError,
/// SeedError, SegmentationError; all bender::Error) and bender::Cancelled.
SegmentVolumeResult SegmentVolume(const SegmentVolumeOptions& options);

/// Options of MakePhantomVolume: the vessel surface, the phantom's parameters, the output.
struct PhantomVolumeOptions
{
  std::string input; ///< a vessel surface (stl, obj, ply, vtp, vtk, off), LPS mm
  std::string
    output; ///< the volume to write (.nrrd, .nhdr, .mha, .mhd, .nii, .nii.gz, .vti); may be empty
  PhantomParameters phantom;
  ProgressReporter progress;
};

/// The phantom workflow of bender-cli phantom: reads the surface, makes the MRA-like volume
/// (MakeVesselPhantom) and, when options.output is set, writes it all-or-nothing (the output's
/// folder is created). Throws InputError (unreadable surface), the segmentation module's errors
/// (ParameterError, VolumeWriteError; all bender::Error) and bender::Cancelled.
Phantom MakePhantomVolume(const PhantomVolumeOptions& options);

} // namespace bender

#endif
