#include "AtomicFile.h"

#include "AtomicFileRecovery.h"
#include "FaultInjection.h"

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
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

// ---------------------------------------------------------------------------------------
// Leftovers of a writer that died (a crash, a kill, a power cut): its temporary files
// ".<stem>.tmp-<pid>-<n><ext>", the previous files it kept ".<stem>.previous-<pid>-<n><ext>",
// and the journal of a set it was publishing ".bender-publish-<pid>-<n>.journal" (written
// whole as ".partial" first, then renamed).

constexpr const char* JournalKind = "bender-publish";

// The writer's process id in a leftover's name of this kind (".x.tmp-123-4.stl": 123).
bool LeftoverPid(const std::string& name, const std::string& kind, long& pid)
{
  const std::string tag = "." + kind + "-";
  const std::size_t at = name.empty() || name[0] != '.' ? std::string::npos : name.rfind(tag);
  if (at == std::string::npos)
  {
    return false;
  }
  const char* digits = name.c_str() + at + tag.size();
  char* end = nullptr;
  pid = std::strtol(digits, &end, 10);
  return end != digits && *end == '-' && pid > 0;
}

// The target a kept previous file or folder stood for: ".case.previous-12-0" -> "case",
// ".a.b.previous-12-3.stl" -> "a.b.stl".
std::string OriginalName(const std::string& leftover)
{
  const std::size_t tag = leftover.rfind(".previous-");
  if (leftover.empty() || tag == std::string::npos)
  {
    return leftover;
  }
  std::size_t rest = tag + 10;
  for (int numbers = 0; numbers < 2; ++numbers)
  {
    while (rest < leftover.size() && std::isdigit(static_cast<unsigned char>(leftover[rest])))
    {
      ++rest;
    }
    rest += numbers == 0 ? 1 : 0; // the dash between the two
  }
  return leftover.substr(1, tag - 1) + leftover.substr(std::min(rest, leftover.size()));
}

bool ProcessAlive(long pid)
{
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

fs::path FolderOf(const fs::path& target)
{
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// Publishes what a dead writer's journal lists and still exists: every file of the set was
// complete on disk before the journal was written, so the set is finished, not undone.
void FinishJournal(const fs::path& journal)
{
  std::ifstream in(journal, std::ios::binary);
  std::string temp, target;
  while (std::getline(in, temp, '\0') && std::getline(in, target, '\0'))
  {
    std::error_code ec;
    if (fs::is_regular_file(temp, ec))
    {
      fs::rename(temp, target, ec);
    }
  }
}

// Writes the journal of a set about to be published (temporary and target, NUL-separated);
// false when it cannot be made durable.
bool WriteJournal(const fs::path& journal,
  const std::vector<fs::path>& temps,
  const std::vector<AtomicFile>& files)
{
  fs::path partial = journal;
  partial.replace_extension(".partial");
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    for (std::size_t k = 0; k < files.size(); ++k)
    {
      out << fs::absolute(temps[k]).string() << '\0' << fs::absolute(files[k].path).string()
          << '\0';
    }
    if (!out.flush())
    {
      return false;
    }
  }
  std::error_code ec;
  if (!Sync(partial, O_RDONLY))
  {
    fs::remove(partial, ec);
    return false;
  }
  fs::rename(partial, journal, ec);
  if (ec)
  {
    fs::remove(partial, ec);
    return false;
  }
  SyncFolder(journal);
  return true;
}

} // namespace

void RecoverInterruptedWrites(const std::string& folder)
{
  std::error_code ec;
  std::vector<fs::path> journals, stale;
  for (fs::directory_iterator it(folder.empty() ? fs::path(".") : fs::path(folder), ec), end;
       !ec && it != end;
       it.increment(ec))
  {
    const std::string name = it->path().filename().string();
    long pid = 0;
    if (LeftoverPid(name, JournalKind, pid))
    {
      if (!ProcessAlive(pid))
      {
        (it->path().extension() == ".journal" ? journals : stale).push_back(it->path());
      }
    }
    else if ((LeftoverPid(name, "tmp", pid) || LeftoverPid(name, "previous", pid)) &&
      !ProcessAlive(pid))
    {
      stale.push_back(it->path());
    }
  }
  for (const fs::path& journal : journals)
  {
    FinishJournal(journal);
    fs::remove(journal, ec);
  }
  for (const fs::path& path : stale)
  {
    // A previous folder set aside by AtomicReplaceFolder whose replacement never arrived goes
    // back; everything else is removed (a temporary the journal published is gone already).
    const fs::path original = path.parent_path() / OriginalName(path.filename().string());
    if (path.filename().string().find(".previous-") != std::string::npos &&
      fs::is_directory(path, ec) && !fs::exists(original, ec))
    {
      fs::rename(path, original, ec);
      continue;
    }
    fs::remove_all(path, ec);
  }
}

std::string TemporaryFolderBeside(const std::string& target)
{
  const fs::path path(target);
  RecoverInterruptedWrites(FolderOf(path).string());
  const fs::path folder = SiblingName(path, "tmp");
  fs::create_directory(folder);
  return folder.string();
}

bool AtomicReplaceFolder(const std::string& built, const std::string& target, std::string& problem)
{
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(target, ec)) || fs::is_empty(target, ec))
  {
    fs::remove(target, ec);
    fs::rename(built, target, ec);
    if (ec)
    {
      problem = "cannot be written (" + ec.message() + ")";
      return false;
    }
    SyncFolder(target);
    return true;
  }
  if (::renameat2(AT_FDCWD, built.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0)
  {
    SyncFolder(target);
    FaultPoint("folder-replace");
    fs::remove_all(built, ec); // the old content, now under the temporary name
    return true;
  }
  // No exchange on this file system: the old folder aside first.
  const fs::path old = SiblingName(fs::path(target), "previous");
  fs::rename(target, old, ec);
  if (ec)
  {
    problem = "cannot be replaced (" + ec.message() + ")";
    return false;
  }
  FaultPoint("folder-replace");
  fs::rename(built, target, ec);
  if (ec)
  {
    problem = "cannot be written (" + ec.message() + ")";
    fs::rename(old, target, ec);
    return false;
  }
  SyncFolder(target);
  fs::remove_all(old, ec);
  return true;
}

bool AtomicWrite(const std::string& path, const FileProducer& produce, std::string& problem)
{
  if (!CheckTarget(path, problem))
  {
    return false;
  }
  const fs::path target(path);
  RecoverInterruptedWrites(FolderOf(target).string());
  const fs::path temp = SiblingName(target, "tmp");
  FileRemover remover;
  remover.Add(temp);
  if (!Produce(produce, temp, problem))
  {
    return false;
  }
  FaultPoint("atomic-write");
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
    const std::size_t half = text->size() / 2;
    out.write(text->data(), static_cast<std::streamsize>(half));
    out.flush();
    FaultPoint("text-write");
    out.write(text->data() + half, static_cast<std::streamsize>(text->size() - half));
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

  std::set<fs::path> folders;
  for (const AtomicFile& file : files)
  {
    folders.insert(FolderOf(file.path));
  }
  for (const fs::path& folder : folders)
  {
    RecoverInterruptedWrites(folder.string());
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

  FaultPoint("atomic-write");

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

  // 3. Publish, under a journal so that a writer killed half-way is finished by the next
  //    (RecoverInterruptedWrites); on a failure, undo the renames already done.
  const fs::path journal =
    SiblingName(FolderOf(files.front().path) / "bender.journal", JournalKind);
  FileRemover journalRemover;
  journalRemover.Add(journal);
  if (files.size() > 1 && !WriteJournal(journal, temps, files))
  {
    problem = BaseName(files.front().path) + ": cannot write the journal of the set beside it";
    return false;
  }
  for (std::size_t k = 0; k < files.size(); ++k)
  {
    std::error_code ec;
    if (k == 1)
    {
      FaultPoint("atomic-publish");
    }
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
