#include "FlowCaseCache.h"

#include "AtomicFileRecovery.h"
#include "BenderErrors.h"
#include "CfdFlowResults.h"
#include "PolyDataCopy.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
constexpr std::uint64_t FnvOffset = 1469598103934665603ull;
constexpr std::uint64_t FnvPrime = 1099511628211ull;

void Mix(std::uint64_t& hash, const char* data, std::size_t size)
{
  for (std::size_t i = 0; i < size; ++i)
  {
    hash ^= static_cast<unsigned char>(data[i]);
    hash *= FnvPrime;
  }
}
} // namespace

std::string FlowCaseKey(const CfdCaseResult& written)
{
  std::vector<std::string> files = written.written;
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  std::uint64_t hash = FnvOffset;
  const std::string version = "bender-flow-case 1";
  Mix(hash, version.c_str(), version.size() + 1);
  std::vector<char> buffer(1 << 16);
  for (const std::string& name : files)
  {
    Mix(hash, name.c_str(), name.size() + 1);
    const fs::path path = fs::path(written.caseDirectory) / name;
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
      throw InputError(path.string() + ": cannot be read for the flow cache's key");
    }
    while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
    {
      Mix(hash, buffer.data(), static_cast<std::size_t>(in.gcount()));
    }
    Mix(hash, "", 1);
  }
  static const char* digits = "0123456789abcdef";
  std::string key(16, '0');
  for (int i = 15; i >= 0; --i, hash >>= 4)
  {
    key[static_cast<std::size_t>(i)] = digits[hash & 0xf];
  }
  return key;
}

bool HasFlowResults(const std::string& caseDirectory)
{
  std::error_code ec;
  if (!fs::exists(fs::path(caseDirectory) / "results" / "surface.vtp", ec))
  {
    return false;
  }
  try
  {
    ReadCfdFlowResults(caseDirectory);
    return true;
  }
  catch (const InputError&)
  {
    return false;
  }
}

CachedFlowCase StoreFlowCase(const LabelledSurface& surface,
  const CfdCaseOptions& options,
  const std::string& cacheDirectory)
{
  std::error_code ec;
  fs::create_directories(cacheDirectory, ec);
  if (!fs::is_directory(cacheDirectory, ec))
  {
    throw InputError(cacheDirectory + ": the flow cache folder cannot be created");
  }
  // Written beside the cases first: the key is the content's.
  std::string incoming;
  try
  {
    incoming = TemporaryFolderBeside((fs::path(cacheDirectory) / "incoming").string());
  }
  catch (const fs::filesystem_error& e)
  {
    throw InputError(cacheDirectory + ": cannot write a case there (" + e.code().message() + ")");
  }
  CachedFlowCase stored;
  try
  {
    CfdCaseOptions write = options;
    write.caseDirectory = incoming;
    write.force = false;
    // Written from a copy: the writer may add to the surface's data, and the same surface must
    // give the same bytes each time.
    const LabelledSurface copy{ DeepCopyOf(surface.surface), surface.patches };
    stored.written = WriteOpenFoamCase(copy, write);
    stored.key = FlowCaseKey(stored.written);
  }
  catch (...)
  {
    fs::remove_all(incoming, ec);
    throw;
  }
  stored.caseDirectory = (fs::path(cacheDirectory) / stored.key).string();
  stored.written.caseDirectory = stored.caseDirectory;
  if (HasFlowResults(stored.caseDirectory))
  {
    fs::remove_all(incoming, ec);
    stored.solved = true;
    return stored;
  }
  std::string problem;
  if (!AtomicReplaceFolder(incoming, stored.caseDirectory, problem))
  {
    fs::remove_all(incoming, ec);
    throw InputError(stored.caseDirectory + ": " + problem);
  }
  return stored;
}

} // namespace bender
