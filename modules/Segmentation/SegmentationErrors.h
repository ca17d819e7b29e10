#ifndef bender_SegmentationErrors_h
#define bender_SegmentationErrors_h

#include "BenderErrors.h"

#include <stdexcept>
#include <string>

namespace bender
{

/// Base of every error thrown by the segmentation module. what() is one line that names the
/// input and the problem; ITK and VTK errors are caught inside the module and rethrown as one of
/// these.
class SegmentationError : public Error
{
public:
  using Error::Error;
};

/// A volume that cannot be read: missing or truncated file, unknown format or pixel type,
/// zero/non-finite spacing, a folder with no DICOM series or several without a choice.
class VolumeReadError : public SegmentationError
{
public:
  using SegmentationError::SegmentationError;
};

/// A volume that cannot be written (unknown extension, unwritable folder).
class VolumeWriteError : public SegmentationError
{
public:
  using SegmentationError::SegmentationError;
};

/// A parameter outside its documented range, or an unusable command line.
class ParameterError : public SegmentationError
{
public:
  using SegmentationError::SegmentationError;
};

/// A seed point outside the volume, or in background (outside the intensity window).
class SeedError : public SegmentationError
{
public:
  using SegmentationError::SegmentationError;
};

/// The caller set the cancel flag; nothing was produced. The app-wide bender::Cancelled of
/// bender_core (Progress.h), under its historical name.
using SegmentationCancelled = Cancelled;

} // namespace bender

#endif
