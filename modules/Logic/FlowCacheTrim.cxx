#include "FlowCacheTrim.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
/// A name FlowCaseKey makes: 32 lower-case hexadecimal digits (16 in caches of earlier
/// versions, whose cases are trimmed too).
bool IsCaseKey(const std::string& name)
{
  return (name.size() == 32 || name.size() == 16) &&
    std::all_of(name.begin(),
      name.end(),
      [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || (c >= 'a' && c <= 'f'); });
}

struct CacheEntry
{
  fs::path folder;
  fs::file_time_type used;
  std::uintmax_t bytes = 0;
  bool kept = false;
};

bool SameFolder(const fs::path& a, const std::string& b)
{
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}
} // namespace

void MarkFlowCaseUsed(const std::string& caseDirectory)
{
  std::error_code ec;
  if (fs::is_directory(caseDirectory, ec))
  {
    fs::last_write_time(caseDirectory, fs::file_time_type::clock::now(), ec);
  }
}

std::uintmax_t FolderBytes(const std::string& folder)
{
  std::uintmax_t bytes = 0;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
  {
    std::error_code sizeError;
    if (it->is_regular_file(sizeError) && !it->is_symlink(sizeError))
    {
      const std::uintmax_t size = it->file_size(sizeError);
      bytes += sizeError ? 0 : size;
    }
  }
  return bytes;
}

FlowCacheTrimResult TrimFlowCache(const std::string& cacheDirectory,
  const FlowCacheLimits& limits,
  const std::vector<std::string>& keep)
{
  FlowCacheTrimResult result;
  std::vector<CacheEntry> entries;
  std::error_code ec;
  for (fs::directory_iterator it(cacheDirectory, ec), end; !ec && it != end; it.increment(ec))
  {
    std::error_code entryError;
    if (!it->is_directory(entryError) || !IsCaseKey(it->path().filename().string()))
    {
      continue;
    }
    CacheEntry entry;
    entry.folder = it->path();
    entry.used = fs::last_write_time(entry.folder, entryError);
    entry.bytes = FolderBytes(entry.folder.string());
    entry.kept = std::any_of(keep.begin(),
      keep.end(),
      [&entry](const std::string& k) { return SameFolder(entry.folder, k); });
    entries.push_back(entry);
  }
  std::sort(entries.begin(),
    entries.end(),
    [](const CacheEntry& a, const CacheEntry& b)
    { return a.used != b.used ? a.used < b.used : a.folder < b.folder; });
  int cases = static_cast<int>(entries.size());
  std::uintmax_t bytes = 0;
  for (const CacheEntry& entry : entries)
  {
    bytes += entry.bytes;
  }
  const int maxCases = std::max(1, limits.maxCases);
  for (const CacheEntry& entry : entries)
  {
    if (cases <= maxCases && bytes <= limits.maxBytes)
    {
      break;
    }
    if (entry.kept)
    {
      continue;
    }
    std::error_code removeError;
    fs::remove_all(entry.folder, removeError);
    if (removeError && fs::exists(entry.folder, ec))
    {
      continue; // in use or not ours to remove: the next one
    }
    result.removed.push_back(entry.folder.string());
    --cases;
    bytes -= entry.bytes;
  }
  result.casesLeft = cases;
  result.bytesLeft = bytes;
  return result;
}

} // namespace bender
