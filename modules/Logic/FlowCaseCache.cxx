#include "FlowCaseCache.h"

#include "AtomicFileRecovery.h"
#include "BenderErrors.h"
#include "CfdFlowResults.h"
#include "ContentHash.h"
#include "PolyDataCopy.h"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace bender
{

std::string FlowCaseKey(const CfdCaseResult& written)
{
  std::vector<std::string> files = written.written;
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  ContentHash hash;
  const std::string version = "bender-flow-case 1";
  hash.Add(version.c_str(), version.size() + 1);
  for (const std::string& name : files)
  {
    hash.Add(name.c_str(), name.size() + 1);
    const fs::path path = fs::path(written.caseDirectory) / name;
    if (!hash.AddFile(path.string()))
    {
      throw InputError(path.string() + ": cannot be read for the flow cache's key");
    }
    hash.Add("", 1);
  }
  return hash.Finish();
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
