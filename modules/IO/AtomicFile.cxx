#include "AtomicFile.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace bender
{

namespace
{

std::string BaseName(const std::string& path)
{
  const std::string name = fs::path(path).filename().string();
  return name.empty() ? path : name;
}

// Flushes a file (or a folder's entries) to disk, so that a rename never publishes a file
// whose content is still only in the page cache (a crash would otherwise leave an empty
// target).
bool Sync(const fs::path& path, int flags)
{
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0)
  {
    return false;
  }
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

// A name beside the target that no other writer uses: the process id and a counter; the
// target's extension stays last because some writers choose the format by it.
fs::path SiblingName(const fs::path& target, const char* kind)
{
  static std::atomic<unsigned> counter{ 0 };
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  return folder /
    ("." + target.stem().string() + "." + kind + "-" + std::to_string(::getpid()) + "-" +
      std::to_string(counter++) + target.extension().string());
}

// Checks that path can be the target of an atomic write; sets problem otherwise.
bool CheckTarget(const std::string& path, std::string& problem)
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
  return true;
}

// Removes the files it holds when it goes out of scope, unless released.
class FileRemover
{
public:
  FileRemover() = default;
  FileRemover(const FileRemover&) = delete;
  FileRemover& operator=(const FileRemover&) = delete;
  ~FileRemover()
  {
    for (const fs::path& path : this->Paths)
    {
      std::error_code ignored;
      fs::remove(path, ignored);
    }
  }
  void Add(const fs::path& path) { this->Paths.push_back(path); }
  void Release() { this->Paths.clear(); }

private:
  std::vector<fs::path> Paths;
};

// Runs produce into temp and flushes the result; sets problem on failure.
bool Produce(const FileProducer& produce, const fs::path& temp, std::string& problem)
{
  if (!produce(temp.string(), problem))
  {
    if (problem.empty())
    {
      problem = "write failed";
    }
    return false;
  }
  std::error_code ec;
  if (!fs::is_regular_file(temp, ec))
  {
    problem = "the writer produced no file";
    return false;
  }
  if (!Sync(temp, O_RDONLY))
  {
    problem = std::string("cannot flush the written file (") + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

void SyncFolder(const fs::path& target)
{
  // Best effort: makes the rename itself durable; some file systems refuse it.
  Sync(target.has_parent_path() ? target.parent_path() : fs::path("."), O_RDONLY | O_DIRECTORY);
}

} // namespace

bool AtomicWrite(const std::string& path, const FileProducer& produce, std::string& problem)
{
  if (!CheckTarget(path, problem))
  {
    return false;
  }
  const fs::path target(path);
  const fs::path temp = SiblingName(target, "tmp");
  FileRemover remover;
  remover.Add(temp);
  if (!Produce(produce, temp, problem))
  {
    return false;
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec)
  {
    problem = "cannot replace the target (" + ec.message() + ")";
    return false;
  }
  remover.Release();
  SyncFolder(target);
  return true;
}

FileProducer TextProducer(std::shared_ptr<const std::string> text)
{
  return [text](const std::string& temp, std::string& why)
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out)
    {
      why = "cannot create a file there";
      return false;
    }
    out.write(text->data(), static_cast<std::streamsize>(text->size()));
    out.flush();
    if (!out)
    {
      why = "write failed (disk full?)";
      return false;
    }
    return true;
  };
}

bool AtomicWriteText(const std::string& path, const std::string& text, std::string& problem)
{
  return AtomicWrite(path, TextProducer(std::make_shared<const std::string>(text)), problem);
}

bool AtomicWriteAll(const std::vector<AtomicFile>& files, std::string& problem)
{
  if (files.empty())
  {
    problem = "no files to write";
    return false;
  }
  std::set<fs::path> targets;
  for (const AtomicFile& file : files)
  {
    std::string why;
    if (!CheckTarget(file.path, why))
    {
      problem = BaseName(file.path) + ": " + why;
      return false;
    }
    if (!file.produce)
    {
      problem = BaseName(file.path) + ": no content to write";
      return false;
    }
    std::error_code ec;
    fs::path key = fs::weakly_canonical(fs::absolute(file.path), ec);
    if (ec)
    {
      key = fs::absolute(file.path).lexically_normal();
    }
    if (!targets.insert(key).second)
    {
      problem = BaseName(file.path) + ": named twice in one write";
      return false;
    }
  }

  // 1. Every file complete and on disk in its temporary.
  FileRemover temporaries;
  std::vector<fs::path> temps;
  for (const AtomicFile& file : files)
  {
    temps.push_back(SiblingName(file.path, "tmp"));
    temporaries.Add(temps.back());
    std::string why;
    if (!Produce(file.produce, temps.back(), why))
    {
      problem = BaseName(file.path) + ": " + why;
      return false;
    }
  }

  // 2. Keep the previous targets (hard links: no copy, same file system) so that a failed
  //    rename can put them back.
  FileRemover backups;
  std::vector<fs::path> previous(files.size());
  for (std::size_t k = 0; k < files.size(); ++k)
  {
    std::error_code ec;
    const fs::path target(files[k].path);
    if (!fs::exists(fs::symlink_status(target, ec)))
    {
      continue;
    }
    const fs::path backup = SiblingName(target, "previous");
    fs::create_hard_link(target, backup, ec);
    if (ec)
    {
      ec.clear();
      fs::copy_file(target, backup, fs::copy_options::overwrite_existing, ec);
    }
    if (ec)
    {
      problem = BaseName(files[k].path) + ": cannot keep the previous file while writing (" +
        ec.message() + ")";
      return false;
    }
    backups.Add(backup);
    previous[k] = backup;
  }

  // 3. Publish; on a failure, undo the renames already done.
  for (std::size_t k = 0; k < files.size(); ++k)
  {
    std::error_code ec;
    fs::rename(temps[k], files[k].path, ec);
    if (!ec)
    {
      continue;
    }
    problem = BaseName(files[k].path) + ": cannot replace the target (" + ec.message() + ")";
    for (std::size_t j = 0; j < k; ++j)
    {
      std::error_code ignored;
      if (previous[j].empty())
      {
        fs::remove(files[j].path, ignored);
      }
      else
      {
        fs::rename(previous[j], files[j].path, ignored);
      }
    }
    return false;
  }
  temporaries.Release();
  for (const AtomicFile& file : files)
  {
    SyncFolder(file.path);
  }
  return true; // backups removes the kept previous files
}

} // namespace bender
