#ifndef bender_SegmentVolume_h
#define bender_SegmentVolume_h

#include "Progress.h"
#include "SurfaceExtraction.h"
#include "VesselSegmentation.h"
#include "VolumeIO.h"

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
};

/// The segment workflow of bender-cli and the GUI: reads the volume, segments the vessels and
/// extracts their surface (LPS mm). The result's timings start with "read" and "segmentation",
/// then the surface stages. Throws the segmentation module's errors (VolumeReadError,
/// ParameterError, SeedError, SegmentationError; all bender::Error) and bender::Cancelled.
SurfaceResult SegmentVolume(const SegmentVolumeOptions& options);

} // namespace bender

#endif
