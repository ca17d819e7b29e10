// CheckNrrdHeader: the NRRD header as ITK's NrrdImageIO (teem) reads it.

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

namespace
{

int NrrdTypeSize(const std::string& type)
{
  static const std::array<std::pair<const char*, int>, 30> types{ { { "signed char", 1 },
    { "int8", 1 },
    { "int8_t", 1 },
    { "uchar", 1 },
    { "unsigned char", 1 },
    { "uint8", 1 },
    { "uint8_t", 1 },
    { "short", 2 },
    { "short int", 2 },
    { "signed short", 2 },
    { "signed short int", 2 },
    { "int16", 2 },
    { "int16_t", 2 },
    { "ushort", 2 },
    { "unsigned short", 2 },
    { "unsigned short int", 2 },
    { "uint16", 2 },
    { "uint16_t", 2 },
    { "int", 4 },
    { "signed int", 4 },
    { "int32", 4 },
    { "int32_t", 4 },
    { "uint", 4 },
    { "unsigned int", 4 },
    { "uint32", 4 },
    { "uint32_t", 4 },
    { "float", 4 },
    { "double", 8 },
    { "longlong", 8 },
    { "ulonglong", 8 } } };
  static const std::array<const char*, 8> eight{ "long long",
    "long long int",
    "signed long long",
    "signed long long int",
    "int64",
    "int64_t",
    "unsigned long long",
    "uint64" };
  for (const auto& [name, size] : types)
  {
    if (type == name)
    {
      return size;
    }
  }
  for (const char* name : eight)
  {
    if (type == name)
    {
      return 8;
    }
  }
  if (type == "unsigned long long int" || type == "uint64_t")
  {
    return 8;
  }
  return 0;
}

} // namespace

bool CheckNrrdHeader(std::string_view header, VolumeHeaderInfo& info, std::string& problem)
{
  info = VolumeHeaderInfo{};
  std::vector<std::string_view> lines;
  if (!HeaderLines(header, lines, problem))
  {
    return false;
  }
  if (lines.empty() || lines[0].rfind("NRRD000", 0) != 0 || lines[0].size() != 8 ||
    lines[0][7] < '1' || lines[0][7] > '5')
  {
    problem = "not a NRRD file (no \"NRRD000x\" magic line)";
    return false;
  }
  int dimension = 0;
  std::vector<std::uint64_t> sizes;
  int typeSize = 0;
  std::string encoding;
  for (std::size_t i = 1; i < lines.size(); ++i)
  {
    const std::string_view line = lines[i];
    if (line.empty())
    {
      break;
    }
    if (line[0] == '#')
    {
      continue;
    }
    const std::size_t keyValue = line.find(":=");
    const std::size_t colon = line.find(": ");
    if (keyValue != std::string_view::npos && (colon == std::string_view::npos || keyValue < colon))
    {
      continue; // key/value pair
    }
    if (colon == std::string_view::npos)
    {
      problem = "NRRD header line " + std::to_string(i + 1) + " is not \"field: value\"";
      return false;
    }
    const std::string field = ToLower(Trim(line.substr(0, colon)));
    const std::string_view value = Trim(line.substr(colon + 2));
    if (field == "dimension")
    {
      const auto r = std::from_chars(value.data(), value.data() + value.size(), dimension);
      if (r.ec != std::errc() || r.ptr != value.data() + value.size() || dimension < 1 ||
        dimension > 16)
      {
        problem = "NRRD dimension \"" + QuoteBytes(value) + "\" (1 to 16)";
        return false;
      }
    }
    else if (field == "sizes")
    {
      if (!PositiveList(value, sizes))
      {
        problem = "NRRD sizes \"" + QuoteBytes(value) + "\" are not positive integers";
        return false;
      }
    }
    else if (field == "type")
    {
      typeSize = NrrdTypeSize(ToLower(value));
      if (typeSize == 0)
      {
        problem = "NRRD type \"" + QuoteBytes(value) + "\" is not supported";
        return false;
      }
    }
    else if (field == "encoding")
    {
      encoding = ToLower(value);
      if (encoding == "txt" || encoding == "text")
      {
        encoding = "ascii";
      }
      if (encoding == "gz")
      {
        encoding = "gzip";
      }
      if (encoding != "raw" && encoding != "ascii" && encoding != "gzip" && encoding != "hex" &&
        encoding != "bzip2" && encoding != "bz2")
      {
        problem = "NRRD encoding \"" + QuoteBytes(value) + "\" is not supported";
        return false;
      }
    }
    else if (field == "data file" || field == "datafile")
    {
      info.dataFile = std::string(value);
    }
    else if (field == "line skip" || field == "lineskip" || field == "byte skip" ||
      field == "byteskip")
    {
      std::int64_t skip = 0;
      const auto r = std::from_chars(value.data(), value.data() + value.size(), skip);
      if (r.ec != std::errc() || skip < -1 || skip > (1ll << 32))
      {
        problem = "NRRD " + field + " \"" + QuoteBytes(value) + "\"";
        return false;
      }
      if (skip != 0)
      {
        encoding = encoding.empty() ? "skip" : encoding;
        info.compressed = true; // the data start is not known here: no exact size check
      }
    }
  }
  if (dimension == 0 || sizes.size() != static_cast<std::size_t>(dimension) || typeSize == 0 ||
    encoding.empty())
  {
    problem = "NRRD header without consistent dimension, sizes, type and encoding";
    return false;
  }
  if (!Product(sizes, 1, info.voxels))
  {
    problem = "NRRD sizes too large";
    return false;
  }
  info.dataBytes = info.voxels * static_cast<std::uint64_t>(typeSize);
  info.compressed = info.compressed || (encoding != "raw");
  if (encoding == "ascii" || encoding == "hex")
  {
    info.compressed = true; // not a byte count; checked token by token
  }
  return true;
}

} // namespace io_detail
} // namespace bender
