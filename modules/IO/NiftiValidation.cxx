// CheckNiftiHeader: the NIfTI-1 header as ITK's NiftiImageIO reads it.

#include "VolumeValidation.h"

#include "InputValidation.h"
#include "StringUtil.h"
#include "ValidationText.h"
#include "VolumeHeaderFields.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <vector>

namespace bender
{
namespace io_detail
{

bool CheckNiftiHeader(std::string_view header, VolumeHeaderInfo& info, std::string& problem)
{
  info = VolumeHeaderInfo{};
  if (header.size() < 348)
  {
    problem = "truncated NIfTI header (" + std::to_string(header.size()) + " of 348 bytes)";
    return false;
  }
  const auto* p = reinterpret_cast<const unsigned char*>(header.data());
  bool swap = false;
  if (Read32(p, false) != 348)
  {
    swap = true;
    if (Read32(p, true) != 348)
    {
      problem = Read32(p, false) == 540 || Read32(p, true) == 540
        ? "NIfTI-2 files are not supported"
        : "not a NIfTI-1 file (sizeof_hdr is not 348)";
      return false;
    }
  }
  if (std::memcmp(p + 344, "n+1\0", 4) != 0)
  {
    problem = "not a single-file NIfTI-1 image (magic is not \"n+1\")";
    return false;
  }
  const int dims = Read16(p + 40, swap);
  if (dims < 1 || dims > 7)
  {
    problem = "NIfTI dim[0] = " + std::to_string(dims) + " (1 to 7)";
    return false;
  }
  std::vector<std::uint64_t> sizes;
  for (int d = 1; d <= dims; ++d)
  {
    const int n = Read16(p + 40 + 2 * d, swap);
    if (n < 1)
    {
      problem = "NIfTI dim[" + std::to_string(d) + "] = " + std::to_string(n) + " (must be > 0)";
      return false;
    }
    sizes.push_back(static_cast<std::uint64_t>(n));
  }
  const int datatype = Read16(p + 70, swap);
  const int bitpix = Read16(p + 72, swap);
  int expectedBits = 0;
  switch (datatype)
  {
    case 2:
    case 256:
      expectedBits = 8;
      break; // uint8, int8
    case 4:
    case 512:
      expectedBits = 16;
      break; // int16, uint16
    case 8:
    case 16:
    case 768:
      expectedBits = 32;
      break; // int32, float32, uint32
    case 64:
    case 1024:
    case 1280:
      expectedBits = 64;
      break; // float64, int64, uint64
    case 128:
      expectedBits = 24;
      break; // RGB24
    case 32:
      expectedBits = 64;
      break; // complex64
    case 2304:
      expectedBits = 32;
      break; // RGBA32
    default:
      break;
  }
  if (expectedBits == 0 || bitpix != expectedBits)
  {
    problem = "NIfTI datatype " + std::to_string(datatype) + " with bitpix " +
      std::to_string(bitpix) + " is not supported";
    return false;
  }
  float voxOffset = 0;
  {
    std::uint32_t bits = Read32(p + 108, swap);
    std::memcpy(&voxOffset, &bits, 4);
  }
  if (!std::isfinite(voxOffset) || voxOffset < 352 || voxOffset > 1e9f)
  {
    problem = "NIfTI vox_offset " + std::to_string(voxOffset) + " (at least 352)";
    return false;
  }
  if (!Product(sizes, 1, info.voxels))
  {
    problem = "NIfTI sizes too large";
    return false;
  }
  info.dataBytes = info.voxels * static_cast<std::uint64_t>(bitpix / 8);
  info.headerBytes = static_cast<std::uint64_t>(voxOffset);
  return true;
}

} // namespace io_detail
} // namespace bender
