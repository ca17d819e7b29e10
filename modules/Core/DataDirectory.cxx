#include "DataDirectory.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace bender
{

namespace fs = std::filesystem;

std::string ExecutableDirectory()
{
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (error || exe.empty())
  {
    return {};
  }
  return exe.parent_path().string();
}

std::vector<std::string> DataDirectoryCandidates()
{
  std::vector<std::string> candidates;
  const char* overridden = std::getenv("BENDER_DATA_DIR");
  if (overridden && *overridden)
  {
    candidates.emplace_back(overridden);
    return candidates;
  }
  const std::string exeDir = ExecutableDirectory();
  if (!exeDir.empty())
  {
    candidates.push_back((fs::path(exeDir).parent_path() / "share" / "bender").string());
  }
  return candidates;
}

std::string DataDirectory()
{
  const std::vector<std::string> candidates = DataDirectoryCandidates();
  for (const std::string& candidate : candidates)
  {
    std::error_code error;
    if (fs::is_directory(candidate, error))
    {
      return candidate;
    }
  }
  return candidates.empty() ? std::string("share/bender") : candidates.front();
}

} // namespace bender
