#include "VolumeValidation.h"

#include "InputValidation.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <sys/stat.h>

namespace bender
{
namespace io_detail
{

namespace
{

constexpr std::size_t MaxHeaderLine = 1000;
constexpr std::size_t MaxMetaKey = 64;

bool IsSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

std::string_view Trim(std::string_view text)
{
  while (!text.empty() && IsSpace(text.front()))
  {
    text.remove_prefix(1);
  }
  while (!text.empty() && IsSpace(text.back()))
  {
    text.remove_suffix(1);
  }
  return text;
}

std::string Lower(std::string_view text)
{
  std::string lower(text);
  for (char& c : lower)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return lower;
}

// Whitespace-separated unsigned integers, each > 0.
bool PositiveList(std::string_view text, std::vector<std::uint64_t>& values)
{
  values.clear();
  text = Trim(text);
  while (!text.empty())
  {
    std::size_t end = 0;
    while (end < text.size() && !IsSpace(text[end]))
    {
      ++end;
    }
    std::uint64_t v = 0;
    const auto r = std::from_chars(text.data(), text.data() + end, v);
    if (r.ec != std::errc() || r.ptr != text.data() + end || v == 0 || v > (1ull << 32) ||
      values.size() > 16)
    {
      return false;
    }
    values.push_back(v);
    text = Trim(text.substr(end));
  }
  return !values.empty();
}

bool Product(const std::vector<std::uint64_t>& sizes, std::uint64_t channels, std::uint64_t& n)
{
  long double p = static_cast<long double>(channels);
  for (const std::uint64_t s : sizes)
  {
    p *= static_cast<long double>(s);
  }
  if (p > 1e18L)
  {
    return false;
  }
  n = static_cast<std::uint64_t>(p);
  return true;
}

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

bool Budget(const VolumeHeaderInfo& info, std::uint64_t budgetBytes, std::string& problem)
{
  if (static_cast<long double>(info.voxels) * 4 > static_cast<long double>(budgetBytes))
  {
    problem = std::to_string(info.voxels) + " voxels exceed the memory budget of " +
      std::to_string(budgetBytes >> 20) + " MiB (as float)";
    return false;
  }
  return true;
}

// Raw data must hold exactly what the header implies (a longer file is another file's data or
// a wrong header: ITK would read the wrong part of it).
bool RawSize(std::uint64_t present, std::uint64_t expected, std::string& problem)
{
  if (present < expected)
  {
    problem = "truncated volume data (the header implies " + std::to_string(expected) + " bytes, " +
      std::to_string(present) + " are present)";
    return false;
  }
  return true;
}

bool RegularFile(const std::string& path, std::uint64_t& size, std::string& problem)
{
  struct stat info
  {
  };
  if (::stat(path.c_str(), &info) != 0)
  {
    problem = "no such file";
    return false;
  }
  if (S_ISDIR(info.st_mode))
  {
    problem = "is a folder, not a file";
    return false;
  }
  if (!S_ISREG(info.st_mode))
  {
    problem = "not a regular file (a pipe, device or socket cannot be read as a volume)";
    return false;
  }
  size = static_cast<std::uint64_t>(info.st_size);
  return true;
}

// The detached data file named by a header, as a path beside the header.
bool DetachedData(const std::string& folder,
  const std::string& name,
  std::string& path,
  std::uint64_t& size,
  std::string& problem)
{
  if (folder.empty())
  {
    problem = "detached data file \"" + QuoteBytes(name) + "\" cannot be checked";
    return false;
  }
  if (name.find('%') != std::string::npos || Lower(name).rfind("list", 0) == 0)
  {
    problem = "data file lists and patterns (\"" + QuoteBytes(name) + "\") are not supported";
    return false;
  }
  std::filesystem::path p(name);
  path = p.is_absolute() ? name : (std::filesystem::path(folder) / p).string();
  std::string why;
  if (!RegularFile(path, size, why))
  {
    problem = "data file \"" + QuoteBytes(name) + "\": " + why;
    return false;
  }
  return true;
}

// Header lines of a text header; false for an over-long line or a NUL byte.
bool HeaderLines(std::string_view header,
  std::vector<std::string_view>& lines,
  std::string& problem)
{
  std::size_t pos = 0;
  while (pos < header.size())
  {
    std::size_t end = header.find('\n', pos);
    if (end == std::string_view::npos)
    {
      end = header.size();
    }
    std::string_view line = header.substr(pos, end - pos);
    if (line.size() > MaxHeaderLine)
    {
      problem = "header line " + std::to_string(lines.size() + 1) + " is longer than " +
        std::to_string(MaxHeaderLine) + " bytes";
      return false;
    }
    if (line.find('\0') != std::string_view::npos)
    {
      problem = "NUL byte in header line " + std::to_string(lines.size() + 1);
      return false;
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.remove_suffix(1);
    }
    lines.push_back(line);
    pos = end + 1;
  }
  return true;
}

std::uint32_t Read32(const unsigned char* p, bool swap)
{
  return swap
    ? (std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3])
    : (std::uint32_t(p[3]) << 24 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[1]) << 8 | p[0]);
}

std::int16_t Read16(const unsigned char* p, bool swap)
{
  return static_cast<std::int16_t>(swap ? (p[0] << 8 | p[1]) : (p[1] << 8 | p[0]));
}

// Where the header of an attached NRRD ends: after the first empty line.
std::size_t NrrdHeaderEnd(std::string_view bytes)
{
  for (std::size_t pos = 0; pos < bytes.size();)
  {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos)
    {
      return std::string_view::npos;
    }
    std::string_view line = bytes.substr(pos, end - pos);
    if (line.empty() || line == "\r")
    {
      return end + 1;
    }
    pos = end + 1;
  }
  return std::string_view::npos;
}

// Where a MetaImage header ends: after the ElementDataFile line.
std::size_t MetaHeaderEnd(std::string_view bytes)
{
  for (std::size_t pos = 0; pos < bytes.size();)
  {
    std::size_t end = bytes.find('\n', pos);
    const std::string_view line =
      bytes.substr(pos, end == std::string_view::npos ? bytes.size() - pos : end - pos);
    const std::string_view trimmed = Trim(line);
    if (trimmed.rfind("ElementDataFile", 0) == 0)
    {
      return end == std::string_view::npos ? bytes.size() : end + 1;
    }
    if (end == std::string_view::npos)
    {
      break;
    }
    pos = end + 1;
  }
  return std::string_view::npos;
}

std::string LowerExt(const std::string& path)
{
  const std::string lower = Lower(std::filesystem::path(path).filename().string());
  if (lower.size() > 7 && lower.compare(lower.size() - 7, 7, ".nii.gz") == 0)
  {
    return ".nii.gz";
  }
  const std::size_t dot = lower.rfind('.');
  return dot == std::string::npos ? std::string() : lower.substr(dot);
}

class ViewBuffer : public std::streambuf
{
public:
  explicit ViewBuffer(std::string_view bytes)
  {
    char* begin = const_cast<char*>(bytes.data());
    this->setg(begin, begin, begin + bytes.size());
  }
};

} // namespace

bool InflatedSize(std::istream& in,
  bool gzip,
  std::uint64_t limit,
  std::uint64_t& size,
  std::string& problem)
{
  z_stream stream{};
  if (inflateInit2(&stream, gzip ? 16 + MAX_WBITS : MAX_WBITS) != Z_OK)
  {
    problem = "cannot start decompression";
    return false;
  }
  std::vector<unsigned char> input(1 << 16), output(1 << 18);
  size = 0;
  int status = Z_OK;
  bool ok = true;
  while (status != Z_STREAM_END)
  {
    if (stream.avail_in == 0)
    {
      in.read(reinterpret_cast<char*>(input.data()), static_cast<std::streamsize>(input.size()));
      const std::streamsize got = in.gcount();
      if (got <= 0)
      {
        problem = "truncated compressed data (the stream ends early)";
        ok = false;
        break;
      }
      stream.next_in = input.data();
      stream.avail_in = static_cast<uInt>(got);
    }
    stream.next_out = output.data();
    stream.avail_out = static_cast<uInt>(output.size());
    status = inflate(&stream, Z_NO_FLUSH);
    if (status != Z_OK && status != Z_STREAM_END)
    {
      problem = "corrupt compressed data";
      ok = false;
      break;
    }
    size += output.size() - stream.avail_out;
    if (size > limit)
    {
      break; // enough: more than anyone asked for
    }
  }
  inflateEnd(&stream);
  return ok;
}

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
    const std::string field = Lower(Trim(line.substr(0, colon)));
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
      typeSize = NrrdTypeSize(Lower(value));
      if (typeSize == 0)
      {
        problem = "NRRD type \"" + QuoteBytes(value) + "\" is not supported";
        return false;
      }
    }
    else if (field == "encoding")
    {
      encoding = Lower(value);
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
      info.compressed = Lower(value) == "true";
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

namespace
{

// The data part once the header is known. stream: positioned at the first data byte of a
// compressed stream (attached) or null; present: raw bytes available after the header.
bool CheckData(const VolumeHeaderInfo& info,
  bool gzipData,
  bool zlibData,
  std::istream* stream,
  std::uint64_t present,
  std::string& problem)
{
  if (gzipData || zlibData)
  {
    if (!stream)
    {
      return true;
    }
    std::uint64_t size = 0;
    if (!InflatedSize(*stream, gzipData, info.dataBytes, size, problem))
    {
      return false;
    }
    if (size < info.dataBytes)
    {
      problem = "truncated volume data (the header implies " + std::to_string(info.dataBytes) +
        " bytes, the compressed data holds " + std::to_string(size) + ")";
      return false;
    }
    return true;
  }
  return RawSize(present, info.dataBytes, problem);
}

bool CheckAsciiTokens(std::string_view data, std::string& problem)
{
  std::size_t run = 0;
  for (const char c : data)
  {
    run = IsSpace(c) ? 0 : run + 1;
    if (run > 64)
    {
      problem = "NRRD ASCII data holds a value longer than 64 bytes";
      return false;
    }
  }
  return true;
}

} // namespace

bool CheckVolumeBytes(std::string_view ext,
  std::string_view bytes,
  const std::string& folder,
  std::uint64_t budgetBytes,
  std::string& problem)
{
  VolumeHeaderInfo info;
  if (ext == ".vti")
  {
    return CheckVtkXml(bytes, "ImageData", budgetBytes, problem);
  }
  if (ext == ".nrrd" || ext == ".nhdr")
  {
    const std::size_t end = NrrdHeaderEnd(bytes);
    const std::string_view header =
      bytes.substr(0, end == std::string_view::npos ? bytes.size() : end);
    if (!CheckNrrdHeader(header, info, problem) || !Budget(info, budgetBytes, problem))
    {
      return false;
    }
    std::string encoding;
    for (std::string_view rest = header; !rest.empty();)
    {
      const std::size_t nl = rest.find('\n');
      const std::string line = Lower(Trim(rest.substr(0, nl)));
      if (line.rfind("encoding:", 0) == 0)
      {
        encoding = std::string(Trim(std::string_view(line).substr(9)));
      }
      rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
    }
    const bool skip = info.compressed && (encoding == "raw");
    if (!info.dataFile.empty())
    {
      std::string dataPath;
      std::uint64_t size = 0;
      if (!DetachedData(folder, info.dataFile, dataPath, size, problem))
      {
        return false;
      }
      if (encoding == "raw" && !skip)
      {
        return RawSize(size, info.dataBytes, problem);
      }
      if (encoding == "gzip" && !skip)
      {
        std::ifstream in(dataPath, std::ios::binary);
        return CheckData(info, true, false, &in, size, problem);
      }
      return true; // text and bzip2 data: teem detects short data itself
    }
    if (end == std::string_view::npos)
    {
      problem = "NRRD header without the empty line that ends it";
      return false;
    }
    const std::string_view data = bytes.substr(end);
    if (encoding == "ascii" || encoding == "text" || encoding == "txt")
    {
      return CheckAsciiTokens(data, problem);
    }
    if (encoding == "raw" && !skip)
    {
      return RawSize(data.size(), info.dataBytes, problem);
    }
    if (encoding == "gzip" && !skip)
    {
      ViewBuffer buffer(data);
      std::istream in(&buffer);
      return CheckData(info, true, false, &in, data.size(), problem);
    }
    return true;
  }
  if (ext == ".mha" || ext == ".mhd")
  {
    const std::size_t end = MetaHeaderEnd(bytes);
    if (end == std::string_view::npos)
    {
      // Report a bad line first when there is one.
      if (CheckMetaHeader(
            bytes.substr(0, std::min<std::size_t>(bytes.size(), 1 << 20)), info, problem))
      {
        problem = "MetaImage header without ElementDataFile";
      }
      return false;
    }
    if (!CheckMetaHeader(bytes.substr(0, end), info, problem) ||
      !Budget(info, budgetBytes, problem))
    {
      return false;
    }
    if (!info.dataFile.empty())
    {
      std::string dataPath;
      std::uint64_t size = 0;
      if (!DetachedData(folder, info.dataFile, dataPath, size, problem))
      {
        return false;
      }
      std::ifstream in(dataPath, std::ios::binary);
      const bool compressed =
        Lower(std::string(bytes.substr(0, end))).find("compresseddata = true") != std::string::npos;
      return CheckData(info, false, compressed, compressed ? &in : nullptr, size, problem);
    }
    const std::string lowerHeader = Lower(bytes.substr(0, end));
    const bool compressed = lowerHeader.find("compresseddata = true") != std::string::npos;
    if (!compressed && info.compressed)
    {
      return true; // HeaderSize given: the data start is elsewhere
    }
    ViewBuffer buffer(bytes.substr(end));
    std::istream in(&buffer);
    return CheckData(info, false, compressed, &in, bytes.size() - end, problem);
  }
  if (ext == ".nii" || ext == ".nii.gz")
  {
    std::string inflated;
    std::string_view header = bytes;
    if (ext == ".nii.gz")
    {
      // Inflate the header (and count the rest).
      z_stream stream{};
      if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK)
      {
        problem = "cannot start decompression";
        return false;
      }
      inflated.resize(352);
      stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
      stream.avail_in = static_cast<uInt>(std::min<std::size_t>(bytes.size(), 1u << 30));
      stream.next_out = reinterpret_cast<Bytef*>(inflated.data());
      stream.avail_out = 352;
      int status = Z_OK;
      while (stream.avail_out > 0 && status == Z_OK)
      {
        status = inflate(&stream, Z_NO_FLUSH);
        if (status == Z_BUF_ERROR)
        {
          break;
        }
      }
      inflated.resize(352 - stream.avail_out);
      inflateEnd(&stream);
      if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR)
      {
        problem = "corrupt gzip data";
        return false;
      }
      header = inflated;
    }
    if (!CheckNiftiHeader(header, info, problem) || !Budget(info, budgetBytes, problem))
    {
      return false;
    }
    if (ext == ".nii")
    {
      const std::uint64_t present =
        bytes.size() > info.headerBytes ? bytes.size() - info.headerBytes : 0;
      return RawSize(present, info.dataBytes, problem);
    }
    ViewBuffer whole(bytes);
    std::istream in(&whole);
    std::uint64_t size = 0;
    if (!InflatedSize(in, true, info.headerBytes + info.dataBytes, size, problem))
    {
      return false;
    }
    if (size < info.headerBytes + info.dataBytes)
    {
      problem = "truncated volume data (the header implies " + std::to_string(info.dataBytes) +
        " bytes, the compressed data holds " +
        std::to_string(size > info.headerBytes ? size - info.headerBytes : 0) + ")";
      return false;
    }
    return true;
  }
  problem = "unknown volume extension \"" + QuoteBytes(ext) + "\"";
  return false;
}

bool CheckVolumeFile(const std::string& path, std::uint64_t budgetBytes, std::string& problem)
{
  std::uint64_t size = 0;
  if (!RegularFile(path, size, problem))
  {
    return false;
  }
  if (size == 0)
  {
    problem = "empty file (0 bytes)";
    return false;
  }
  const std::string ext = LowerExt(path);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const std::string where = folder.empty() ? std::string(".") : folder;
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    problem = "cannot be opened for reading";
    return false;
  }
  // Small files (and every compressed or XML format, bounded by the budget) are checked whole;
  // a large raw file only needs its header and its size.
  const bool whole = size <= (std::uint64_t(64) << 20) || ext == ".nii.gz" || ext == ".vti";
  if (whole && size > budgetBytes + (std::uint64_t(64) << 20))
  {
    problem = "file of " + std::to_string(size >> 20) + " MiB exceeds the memory budget of " +
      std::to_string(budgetBytes >> 20) + " MiB";
    return false;
  }
  if (whole)
  {
    std::string bytes(static_cast<std::size_t>(size), '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    if (static_cast<std::uint64_t>(in.gcount()) != size)
    {
      problem = "cannot read the file";
      return false;
    }
    return CheckVolumeBytes(ext, bytes, where, budgetBytes, problem);
  }
  // Large raw files: header from the first MiB, data size from the file size.
  std::string head(1 << 20, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  VolumeHeaderInfo info;
  if (ext == ".nrrd" || ext == ".nhdr")
  {
    const std::size_t end = NrrdHeaderEnd(head);
    if (!CheckNrrdHeader(
          head.substr(0, end == std::string::npos ? head.size() : end), info, problem) ||
      !Budget(info, budgetBytes, problem))
    {
      return false;
    }
    if (!info.dataFile.empty() || info.compressed)
    {
      return true;
    }
    if (end == std::string::npos)
    {
      problem = "NRRD header without the empty line that ends it";
      return false;
    }
    return RawSize(size - end, info.dataBytes, problem);
  }
  if (ext == ".mha" || ext == ".mhd")
  {
    const std::size_t end = MetaHeaderEnd(head);
    if (end == std::string::npos)
    {
      problem = "MetaImage header without ElementDataFile in its first MiB";
      return false;
    }
    if (!CheckMetaHeader(std::string_view(head).substr(0, end), info, problem) ||
      !Budget(info, budgetBytes, problem))
    {
      return false;
    }
    if (!info.dataFile.empty() || info.compressed)
    {
      if (info.compressed && info.dataFile.empty())
      {
        in.clear();
        in.seekg(static_cast<std::streamoff>(end));
        const bool zlibData =
          Lower(head.substr(0, end)).find("compresseddata = true") != std::string::npos;
        return CheckData(info, false, zlibData, zlibData ? &in : nullptr, size - end, problem);
      }
      if (!info.dataFile.empty())
      {
        return CheckVolumeBytes(
          ext, std::string_view(head).substr(0, end), where, budgetBytes, problem);
      }
      return true;
    }
    return RawSize(size - end, info.dataBytes, problem);
  }
  if (ext == ".nii")
  {
    if (!CheckNiftiHeader(head, info, problem) || !Budget(info, budgetBytes, problem))
    {
      return false;
    }
    const std::uint64_t present = size > info.headerBytes ? size - info.headerBytes : 0;
    return RawSize(present, info.dataBytes, problem);
  }
  problem = "unknown volume extension \"" + QuoteBytes(ext) + "\"";
  return false;
}

} // namespace io_detail
} // namespace bender
