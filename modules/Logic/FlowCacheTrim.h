#ifndef bender_FlowCacheTrim_h
#define bender_FlowCacheTrim_h

// Keeping the flow cache (FlowCaseCache.h) bounded (issue 23, the Flow panel): every bend the
// surgeon runs leaves a case of tens of megabytes in the user's cache folder. After a run the
// panel trims the cache to a number of cases and a size, removing the least recently used case
// first and never a case it shows. A case's last use is its folder's modification time, set
// when the flow study stores or finds it (MarkFlowCaseUsed).

#include <cstdint>
#include <string>
#include <vector>

namespace bender
{

/// How much the flow cache may hold.
struct FlowCacheLimits
{
  int maxCases = 20; ///< case folders, at least 1
  /// Bytes of all the case folders together (a demo case at the default mesh, run: ~30 MB).
  std::uintmax_t maxBytes = std::uintmax_t(2) << 30;
};

/// What TrimFlowCache did.
struct FlowCacheTrimResult
{
  std::vector<std::string> removed; ///< the case folders removed, least recently used first
  int casesLeft = 0;
  std::uintmax_t bytesLeft = 0;
};

/// Marks a case of the cache as used now (its folder's modification time). A folder that is
/// not there is left alone.
void MarkFlowCaseUsed(const std::string& caseDirectory);

/// The bytes of the regular files under `folder` (links not followed); 0 when it is not there.
std::uintmax_t FolderBytes(const std::string& folder);

/// Removes case folders of `cacheDirectory` (those named by a cache key: 32 hexadecimal
/// digits, or 16 from earlier versions; anything else there is left alone), the least recently used
/// first, until at most limits.maxCases remain and they hold at most limits.maxBytes. The folders
/// in `keep` (the cases on screen) are never removed, even when they alone exceed the limits. A
/// missing cache folder is an empty one; a case that cannot be removed is skipped. Throws nothing.
FlowCacheTrimResult TrimFlowCache(const std::string& cacheDirectory,
  const FlowCacheLimits& limits,
  const std::vector<std::string>& keep);

} // namespace bender

#endif
