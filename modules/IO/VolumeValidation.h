#ifndef bender_VolumeValidation_h
#define bender_VolumeValidation_h

// Pre-validation of volume files before ITK or VTK reads them (docs/input-validation.md).
// ITK's NRRD and MetaImage readers overflow fixed buffers on long header lines or field
// names, loop forever on a negative NDims, and (like the NIfTI and VTK XML readers) accept
// truncated data, filling the rest with zeros. These checks parse the header as the readers
// would, bound every line and field, and compare the data the header implies with the bytes
// present (inflating compressed data to count it). No ITK or VTK dependency: the libFuzzer
// harnesses in fuzz/ call them directly.

#include <cstdint>
#include <istream>
#include <string>
#include <string_view>

namespace bender
{
namespace io_detail
{

/// Memory budget for a volume: the voxels as float (what ReadVolume returns) must fit.
constexpr std::uint64_t MaxVolumeBytes = std::uint64_t(2) << 30; // 2 GiB = 512 M voxels

/// What a header says about the data.
struct VolumeHeaderInfo
{
  std::uint64_t voxels = 0;      ///< product of the sizes, times the channels
  std::uint64_t dataBytes = 0;   ///< voxels times the bytes per component
  std::string dataFile;          ///< detached data file as written in the header, or empty
  bool compressed = false;       ///< gzip/zlib data (counted by inflating)
  std::uint64_t headerBytes = 0; ///< where attached data starts
};

/// NRRD header text (".nrrd" attached or ".nhdr"), up to and without the data: magic line,
/// lines of at most 1000 bytes, dimension 1 to 16, positive sizes, a known type and
/// encoding. Sets info (dataFile for "data file:").
bool CheckNrrdHeader(std::string_view header, VolumeHeaderInfo& info, std::string& problem);

/// MetaImage header text (".mha"/".mhd"), up to and including the ElementDataFile line:
/// "Key = Value" lines of at most 1000 bytes, keys of at most 64, NDims 1 to 4, DimSize with
/// NDims positive values, a known ElementType, 1 to 16 channels, ElementDataFile last.
bool CheckMetaHeader(std::string_view header, VolumeHeaderInfo& info, std::string& problem);

/// A NIfTI-1 header (the first 348 bytes, either byte order): dim[0] 1 to 7, positive sizes,
/// a known datatype whose bitpix agrees, vox_offset at least 352 (single file).
bool CheckNiftiHeader(std::string_view header, VolumeHeaderInfo& info, std::string& problem);

/// The whole check of a volume's bytes: ext is ".nrrd", ".nhdr", ".mha", ".mhd", ".nii",
/// ".nii.gz" or ".vti"; folder is where detached data files are looked up (may be empty: then
/// a detached data file is an error). The data implied by the header must be present (and
/// no more than one record's slack for raw data), and fit budgetBytes as float voxels.
bool CheckVolumeBytes(std::string_view ext,
  std::string_view bytes,
  const std::string& folder,
  std::uint64_t budgetBytes,
  std::string& problem);

/// The same for a file: it (and any detached data file) must be a regular file (not a FIFO
/// or a device such as /dev/zero, also through a symlink). Reads at most the header and
/// streams compressed data. problem does not name the file (callers prefix it).
bool CheckVolumeFile(const std::string& path, std::uint64_t budgetBytes, std::string& problem);

/// Counts the bytes that gzip (or zlib, gzip=false) data from in inflates to, stopping once
/// more than limit bytes came out. False (problem set) for corrupt or truncated data.
bool InflatedSize(std::istream& in,
  bool gzip,
  std::uint64_t limit,
  std::uint64_t& size,
  std::string& problem);

} // namespace io_detail
} // namespace bender

#endif
