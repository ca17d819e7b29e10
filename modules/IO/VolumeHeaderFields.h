#ifndef bender_VolumeHeaderFields_h
#define bender_VolumeHeaderFields_h

// Internal to the volume pre-validators (VolumeValidation.h): what the NRRD, MetaImage and
// NIfTI header checks share. Never throws; no library dependency.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace bender
{
namespace io_detail
{

/// Longest header line accepted (ITK copies lines into fixed buffers).
constexpr std::size_t MaxHeaderLine = 1000;
/// Longest MetaImage field name accepted.
constexpr std::size_t MaxMetaKey = 64;

/// Whitespace-separated unsigned integers, each > 0 and at most 2^32, at most 17 of them;
/// false for anything else or none.
bool PositiveList(std::string_view text, std::vector<std::uint64_t>& values);

/// The product of sizes and channels into n; false when it exceeds 1e18.
bool Product(const std::vector<std::uint64_t>& sizes, std::uint64_t channels, std::uint64_t& n);

/// Header lines of a text header (without "\r\n"); false for an over-long line or a NUL byte.
bool HeaderLines(std::string_view header,
  std::vector<std::string_view>& lines,
  std::string& problem);

/// A 32-bit / 16-bit word of a binary header, byte-swapped when swap.
std::uint32_t Read32(const unsigned char* p, bool swap);
std::int16_t Read16(const unsigned char* p, bool swap);

} // namespace io_detail
} // namespace bender

#endif
