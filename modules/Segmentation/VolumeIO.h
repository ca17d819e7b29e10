#ifndef bender_VolumeIO_h
#define bender_VolumeIO_h

#include "Progress.h"
#include "SegmentationErrors.h"
#include "Volume.h"

#include <string>
#include <vector>

namespace bender
{

/// One DICOM series found in a folder.
struct DicomSeriesInfo
{
  std::string uid;         ///< SeriesInstanceUID (0020,000E)
  std::string description; ///< SeriesDescription (0008,103E), may be empty
  std::size_t sliceCount = 0;
};

struct VolumeReadOptions
{
  /// For a DICOM folder holding several series: the UID of the one to read. Empty (default):
  /// the folder must hold exactly one series, otherwise VolumeReadError lists them.
  std::string dicomSeriesUid;
};

/// Reads a scalar volume and casts its intensities to float, keeping spacing, origin and the
/// direction matrix so that physical points are LPS mm (ITK's convention; NIfTI's RAS
/// qform/sform is converted by ITK). Formats, chosen by extension: .nrrd .nhdr (NRRD),
/// .nii .nii.gz (NIfTI), .mha .mhd (MetaImage), .vti (VTK XML image; its origin, spacing and
/// direction are taken as LPS), or a folder = a DICOM series read with GDCM, slices sorted by
/// position along the slice normal. Any scalar pixel type is accepted.
/// Throws VolumeReadError (one line naming the path): missing path, unknown extension,
/// truncated or corrupt file, non-scalar or unknown pixel type, zero or non-finite spacing,
/// a folder without DICOM files, several series without a choice (the message lists each UID
/// and description), and SegmentationCancelled.
Volume ReadVolume(const std::string& path,
  const VolumeReadOptions& options = {},
  const ProgressReporter& progress = {});

/// The DICOM series of a folder, sorted by UID. Throws VolumeReadError for a missing folder.
/// An empty vector when the folder holds no DICOM series.
std::vector<DicomSeriesInfo> ListDicomSeries(const std::string& folder);

/// Writes a float volume: .nrrd .nhdr .nii .nii.gz .mha .mhd .vti (compressed where the format
/// allows). Throws VolumeWriteError (unknown extension, unwritable path, empty volume).
void WriteVolume(const Volume& volume, const std::string& path);

/// Writes a mask as unsigned char (same formats as WriteVolume).
void WriteLabelMap(const LabelMap& mask, const std::string& path);

} // namespace bender

#endif
