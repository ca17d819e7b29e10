// CheckMetaHeader: the MetaImage header as ITK's MetaImageIO reads it.

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

int MetaTypeSize(const std::string& type)
{
  static const std::array<std::pair<const char*, int>, 12> types{ { { "MET_CHAR", 1 },
    { "MET_UCHAR", 1 },
    { "MET_SHORT", 2 },
    { "MET_USHORT", 2 },
    { "MET_INT", 4 },
    { "MET_UINT", 4 },
    { "MET_LONG", 4 },
    { "MET_ULONG", 4 },
    { "MET_LONG_LONG", 8 },
    { "MET_ULONG_LONG", 8 },
    { "MET_FLOAT", 4 },
    { "MET_DOUBLE", 8 } } };
  for (const auto& [name, size] : types)
  {
    if (type == name)
    {
      return size;
    }
  }
  return 0;
}

} // namespace

bool CheckMetaHeader(std::string_view header, VolumeHeaderInfo& info, std::string& problem)
{
  info = VolumeHeaderInfo{};
  std::vector<std::string_view> lines;
  if (!HeaderLines(header, lines, problem))
  {
    return false;
  }
  int dims = 0;
  std::vector<std::uint64_t> sizes;
  int typeSize = 0;
  std::uint64_t channels = 1;
  bool sawDataFile = false;
  bool sawObjectType = false;
  for (std::size_t i = 0; i < lines.size(); ++i)
  {
    const std::string_view line = Trim(lines[i]);
    if (line.empty())
    {
      continue;
    }
    if (sawDataFile)
    {
      problem = "MetaImage header continues after ElementDataFile";
      return false;
    }
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos)
    {
      problem = "MetaImage header line " + std::to_string(i + 1) + " is not \"Key = Value\"";
      return false;
    }
    const std::string_view key = Trim(line.substr(0, eq));
    const std::string_view value = Trim(line.substr(eq + 1));
    if (key.size() > MaxMetaKey || key.empty())
    {
      problem = "MetaImage header line " + std::to_string(i + 1) + ": field name of " +
        std::to_string(key.size()) + " bytes (1 to " + std::to_string(MaxMetaKey) + ")";
      return false;
    }
    if (key == "ObjectType")
    {
      sawObjectType = true;
      if (value != "Image")
      {
        problem = "MetaImage ObjectType \"" + QuoteBytes(value) + "\" (Image expected)";
        return false;
      }
    }
    else if (key == "NDims")
    {
      const auto r = std::from_chars(value.data(), value.data() + value.size(), dims);
      if (r.ec != std::errc() || r.ptr != value.data() + value.size() || dims < 1 || dims > 4)
      {
        problem = "MetaImage NDims \"" + QuoteBytes(value) + "\" (1 to 4)";
        return false;
      }
    }
    else if (key == "DimSize")
    {
      if (!PositiveList(value, sizes))
      {
        problem = "MetaImage DimSize \"" + QuoteBytes(value) + "\" is not positive integers";
        return false;
      }
    }
    else if (key == "ElementType")
    {
      typeSize = MetaTypeSize(std::string(value));
      if (typeSize == 0)
      {
        problem = "MetaImage ElementType \"" + QuoteBytes(value) + "\" is not supported";
        return false;
      }
    }
    else if (key == "ElementNumberOfChannels")
    {
      const auto r = std::from_chars(value.data(), value.data() + value.size(), channels);
      if (r.ec != std::errc() || r.ptr != value.data() + value.size() || channels < 1 ||
        channels > 16)
      {
        problem = "MetaImage ElementNumberOfChannels \"" + QuoteBytes(value) + "\" (1 to 16)";
        return false;
      }
    }
    else if (key == "CompressedData")
    {
      info.compressed = ToLower(value) == "true";
    }
    else if (key == "HeaderSize")
    {
      info.compressed = info.compressed || value != "0"; // data start not known: no exact check
    }
    else if (key == "ElementDataFile")
    {
      sawDataFile = true;
      if (value.empty())
      {
        problem = "MetaImage ElementDataFile is empty";
        return false;
      }
      if (value != "LOCAL" && value != "Local" && value != "local")
      {
        info.dataFile = std::string(value);
      }
    }
  }
  if (!sawObjectType && !lines.empty() && Trim(lines[0]).rfind("ObjectType", 0) != 0)
  {
    problem = "not a MetaImage file (no ObjectType line)";
    return false;
  }
  if (dims == 0 || sizes.size() != static_cast<std::size_t>(dims) || typeSize == 0 || !sawDataFile)
  {
    problem = "MetaImage header without consistent NDims, DimSize, ElementType and ElementDataFile";
    return false;
  }
  if (!Product(sizes, channels, info.voxels))
  {
    problem = "MetaImage DimSize too large";
    return false;
  }
  info.dataBytes = info.voxels * static_cast<std::uint64_t>(typeSize);
  return true;
}

} // namespace io_detail
} // namespace bender
