#include "FileUtilities.h"

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace bender
{
namespace io_detail
{

std::string DisplayName(const std::string& path)
{
  const std::string name = fs::path(path).filename().string();
  return name.empty() ? path : name;
}

std::string LowerExtension(const std::string& path)
{
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return ext;
}

bool CheckReadableFile(const std::string& path, std::uintmax_t& size, std::string& problem)
{
  size = 0;
  if (path.empty())
  {
    problem = "empty file name";
    return false;
  }
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
  {
    problem = "no such file";
    return false;
  }
  if (fs::is_directory(status))
  {
    problem = "is a folder, not a file";
    return false;
  }
  if (!fs::is_regular_file(status))
  {
    problem = "not a regular file";
    return false;
  }
  size = fs::file_size(path, ec);
  if (ec)
  {
    problem = "cannot read the file size (" + ec.message() + ")";
    return false;
  }
  std::ifstream probe(path, std::ios::binary);
  if (!probe)
  {
    problem = std::string("cannot be opened for reading (") + std::strerror(errno) + ")";
    return false;
  }
  if (size == 0)
  {
    problem = "empty file (0 bytes)";
    return false;
  }
  return true;
}

namespace
{

// Flushes a finished file to disk so that the rename below never publishes a file whose
// content is still only in the page cache (a crash would otherwise leave an empty target).
bool SyncFile(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
  {
    return false;
  }
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

std::string TemporaryName(const fs::path& target)
{
  static std::atomic<unsigned> counter{ 0 };
  // Keep the target's extension last: some writers look at it.
  return "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
    std::to_string(counter++) + target.extension().string();
}

} // namespace

bool AtomicWrite(const std::string& path,
  const std::function<bool(const std::string& tempPath, std::string& problem)>& produce,
  std::string& problem)
{
  if (path.empty())
  {
    problem = "empty file name";
    return false;
  }
  const fs::path target(path);
  if (target.filename().empty() || target.filename() == "." || target.filename() == "..")
  {
    problem = "not a file name";
    return false;
  }
  std::error_code ec;
  if (fs::is_directory(target, ec))
  {
    problem = "is a folder, not a file";
    return false;
  }
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(folder, ec))
  {
    problem = "folder " + folder.string() + " does not exist";
    return false;
  }
  if (::access(folder.c_str(), W_OK) != 0)
  {
    problem = "folder " + folder.string() + " is not writable";
    return false;
  }

  const fs::path temp = folder / TemporaryName(target);
  const std::string tempPath = temp.string();
  struct TempRemover
  {
    const fs::path& Path;
    bool Armed = true;
    ~TempRemover()
    {
      if (this->Armed)
      {
        std::error_code ignored;
        fs::remove(this->Path, ignored);
      }
    }
  } remover{ temp };

  if (!produce(tempPath, problem))
  {
    if (problem.empty())
    {
      problem = "write failed";
    }
    return false;
  }
  if (!fs::is_regular_file(temp, ec))
  {
    problem = "the writer produced no file";
    return false;
  }
  if (!SyncFile(tempPath))
  {
    problem = std::string("cannot flush the written file (") + std::strerror(errno) + ")";
    return false;
  }
  fs::rename(temp, target, ec);
  if (ec)
  {
    problem = "cannot replace the target (" + ec.message() + ")";
    return false;
  }
  remover.Armed = false;
  return true;
}

} // namespace io_detail
} // namespace bender
