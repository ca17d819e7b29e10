#include "VolumeValidation.h"

#include "InputValidation.h"
#include "StringUtil.h"
#include "ValidationText.h"
#include "VolumeHeaderFields.h"

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
  if (name.find('%') != std::string::npos || ToLower(name).rfind("list", 0) == 0)
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
  const std::string lower = ToLower(std::filesystem::path(path).filename().string());
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
    run = IsBlank(c) ? 0 : run + 1;
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
      const std::string line = ToLower(Trim(rest.substr(0, nl)));
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
        ToLower(std::string(bytes.substr(0, end))).find("compresseddata = true") !=
        std::string::npos;
      return CheckData(info, false, compressed, compressed ? &in : nullptr, size, problem);
    }
    const std::string lowerHeader = ToLower(bytes.substr(0, end));
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
          ToLower(head.substr(0, end)).find("compresseddata = true") != std::string::npos;
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
