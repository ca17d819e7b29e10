#ifndef bender_SegmentVolume_h
#define bender_SegmentVolume_h

#include "Progress.h"
#include "SurfaceExtraction.h"
#include "VesselPhantom.h"
#include "VesselSegmentation.h"
#include "VolumeIO.h"

#include <functional>
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

/// The segment workflow of bender-cli and the GUI: reads the volume, segments the vessels and
/// extracts their surface (LPS mm). The series of a DICOM folder is the one of ChooseDicomSeries
/// (read.dicomSeriesUid, else the largest). The result's timings start with "read" and
/// "segmentation", then the surface stages. Throws the segmentation module's errors
/// (VolumeReadError, ParameterError, SeedError, SegmentationError; all bender::Error) and
/// bender::Cancelled.
SurfaceResult SegmentVolume(const SegmentVolumeOptions& options);

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
