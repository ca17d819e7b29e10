// bender::AtomicWrite / AtomicWriteAll: the content appears whole or not at all, the previous
// files survive every failure, and no temporary file is left behind.

#include "AtomicFile.h"

#include "AtomicFileRecovery.h"
#include "FaultInjection.h"
#include "IOTestUtilities.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

#include <cstdlib>
#include <sys/wait.h>
#include <unistd.h>

namespace
{

using bender_test::ReadText;
using bender_test::TempDir;
using bender_test::WriteText;

bender::FileProducer Text(const std::string& text)
{
  return [text](const std::string& temp, std::string& problem)
  {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    if (!out)
    {
      problem = "cannot write";
      return false;
    }
    return true;
  };
}

bender::FileProducer Failing(const std::string& why)
{
  return [why](const std::string& temp, std::string& problem)
  {
    std::ofstream(temp, std::ios::binary) << "half";
    problem = why;
    return false;
  };
}

TEST(AtomicWrite, WritesAndReplacesLeavingNoTemporary)
{
  TempDir dir;
  std::string problem;
  ASSERT_TRUE(bender::AtomicWriteText(dir / "a.txt", "first", problem)) << problem;
  EXPECT_EQ(ReadText(dir / "a.txt"), "first");
  ASSERT_TRUE(bender::AtomicWrite(dir / "a.txt", Text("second"), problem)) << problem;
  EXPECT_EQ(ReadText(dir / "a.txt"), "second");
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "a.txt" });
}

TEST(AtomicWrite, TemporaryIsBesideTheTargetWithItsExtension)
{
  TempDir dir;
  std::string seen;
  std::string problem;
  ASSERT_TRUE(bender::AtomicWrite(
    dir / "mesh.vtp",
    [&](const std::string& temp, std::string&)
    {
      seen = temp;
      std::ofstream(temp) << "x";
      return true;
    },
    problem));
  EXPECT_EQ(std::filesystem::path(seen).parent_path(), dir.path());
  EXPECT_EQ(std::filesystem::path(seen).extension(), ".vtp");
  EXPECT_NE(std::filesystem::path(seen).filename(), "mesh.vtp");
}

TEST(AtomicWrite, FailureOrExceptionKeepsThePreviousFile)
{
  TempDir dir;
  WriteText(dir / "a.txt", "old");
  std::string problem;
  EXPECT_FALSE(bender::AtomicWrite(dir / "a.txt", Failing("disk full"), problem));
  EXPECT_EQ(problem, "disk full");
  EXPECT_EQ(ReadText(dir / "a.txt"), "old");

  EXPECT_THROW(bender::AtomicWrite(
                 dir / "a.txt",
                 [](const std::string& temp, std::string&) -> bool
                 {
                   std::ofstream(temp) << "half";
                   throw std::runtime_error("writer crashed");
                 },
                 problem),
    std::runtime_error);
  EXPECT_EQ(ReadText(dir / "a.txt"), "old");

  problem.clear();
  EXPECT_FALSE(bender::AtomicWrite(
    dir / "a.txt", [](const std::string&, std::string&) { return true; }, problem));
  EXPECT_EQ(problem, "the writer produced no file");
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "a.txt" });
}

TEST(AtomicWrite, RefusesBadTargets)
{
  TempDir dir;
  std::string problem;
  EXPECT_FALSE(bender::AtomicWriteText(dir / "missing/a.txt", "x", problem));
  EXPECT_NE(problem.find("does not exist"), std::string::npos) << problem;
  std::filesystem::create_directory(dir / "folder");
  EXPECT_FALSE(bender::AtomicWriteText(dir / "folder", "x", problem));
  EXPECT_EQ(problem, "is a folder, not a file");
  EXPECT_FALSE(bender::AtomicWriteText("", "x", problem));
  EXPECT_EQ(problem, "empty file name");
}

TEST(AtomicWriteAll, WritesEveryFile)
{
  TempDir dir;
  WriteText(dir / "b.stl", "old b");
  std::string problem;
  ASSERT_TRUE(bender::AtomicWriteAll(
    { { dir / "a.stl", Text("A") }, { dir / "b.stl", Text("B") }, { dir / "c.stl", Text("C") } },
    problem))
    << problem;
  EXPECT_EQ(ReadText(dir / "a.stl"), "A");
  EXPECT_EQ(ReadText(dir / "b.stl"), "B");
  EXPECT_EQ(ReadText(dir / "c.stl"), "C");
  EXPECT_EQ(dir.Entries(), (std::set<std::string>{ "a.stl", "b.stl", "c.stl" }));
}

TEST(AtomicWriteAll, OneFailedFileWritesNone)
{
  TempDir dir;
  WriteText(dir / "a.stl", "old a");
  std::string problem;
  EXPECT_FALSE(bender::AtomicWriteAll({ { dir / "a.stl", Text("A") },
                                        { dir / "b.stl", Text("B") },
                                        { dir / "c.stl", Failing("no room") } },
    problem));
  EXPECT_EQ(problem, "c.stl: no room");
  EXPECT_EQ(ReadText(dir / "a.stl"), "old a");
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "a.stl" });

  EXPECT_THROW(bender::AtomicWriteAll({ { dir / "a.stl", Text("A") },
                                        { dir / "b.stl",
                                          [](const std::string&, std::string&) -> bool
                                          { throw std::runtime_error("writer crashed"); } } },
                 problem),
    std::runtime_error);
  EXPECT_EQ(ReadText(dir / "a.stl"), "old a");
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "a.stl" });
}

// A rename that fails after others succeeded: the files already replaced get their previous
// content back and the new ones disappear.
TEST(AtomicWriteAll, FailedRenameRollsBackTheRenamesDone)
{
  TempDir dir;
  WriteText(dir / "a.stl", "old a");
  std::filesystem::create_directory(dir / "sub");
  std::string problem;
  // The last producer runs after the targets were checked and before any rename: it moves
  // the third file's folder (with its finished temporary) away, so that the third rename
  // fails after the first two succeeded.
  const bool ok = bender::AtomicWriteAll({ { dir / "a.stl", Text("A") },
                                           { dir / "b.stl", Text("B") },
                                           { dir / "sub/c.stl", Text("C") },
                                           { dir / "d.stl",
                                             [&](const std::string& temp, std::string&)
                                             {
                                               std::filesystem::rename(dir / "sub", dir / "moved");
                                               std::ofstream(temp) << "D";
                                               return true;
                                             } } },
    problem);
  EXPECT_FALSE(ok);
  EXPECT_EQ(problem.rfind("c.stl: cannot replace the target", 0), 0u) << problem;
  EXPECT_EQ(ReadText(dir / "a.stl"), "old a");
  EXPECT_EQ(dir.Entries(), (std::set<std::string>{ "a.stl", "moved" }));
}

TEST(AtomicWriteAll, RefusesAnEmptySetAndDuplicates)
{
  TempDir dir;
  std::string problem;
  EXPECT_FALSE(bender::AtomicWriteAll({}, problem));
  EXPECT_EQ(problem, "no files to write");
  EXPECT_FALSE(bender::AtomicWriteAll(
    { { dir / "a.stl", Text("1") }, { (dir.path() / "." / "a.stl").string(), Text("2") } },
    problem));
  EXPECT_EQ(problem, "a.stl: named twice in one write");
  EXPECT_TRUE(dir.Entries().empty());
}

// A writer killed (SIGKILL, BENDER_FAULT_AT) at `point` in a child process while it writes
// the set a, b, c over "old" files; returns whether it died by SIGKILL.
bool KillWriterAt(const TempDir& dir, const std::string& point)
{
  const pid_t child = ::fork();
  if (child == 0)
  {
    ::setenv(bender::FaultInjectionVariable, point.c_str(), 1);
    std::string problem;
    bender::AtomicWriteAll(
      { { dir / "a.stl", Text("A") }, { dir / "b.stl", Text("B") }, { dir / "c.stl", Text("C") } },
      problem);
    std::_Exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

std::set<std::string> Contents(const TempDir& dir)
{
  return { ReadText(dir / "a.stl"), ReadText(dir / "b.stl"), ReadText(dir / "c.stl") };
}

// Killed with every temporary complete and nothing published: the old files stay, the
// temporaries are left, and the next write there (or RecoverInterruptedWrites) removes them.
TEST(AtomicWriteAll, KilledBeforePublishingLeavesTheOldSet)
{
  TempDir dir;
  for (const char* name : { "a.stl", "b.stl", "c.stl" })
  {
    WriteText(dir / name, "old");
  }
  ASSERT_TRUE(KillWriterAt(dir, "atomic-write"));
  EXPECT_EQ(Contents(dir), std::set<std::string>{ "old" });
  EXPECT_EQ(dir.Entries().size(), 6u); // three temporaries of the dead writer
  std::string problem;
  ASSERT_TRUE(bender::AtomicWriteText(dir / "other.txt", "x", problem)) << problem;
  EXPECT_EQ(dir.Entries(), (std::set<std::string>{ "a.stl", "b.stl", "c.stl", "other.txt" }));
  EXPECT_EQ(Contents(dir), std::set<std::string>{ "old" });
}

// Killed after the first file was published: each file is whole (old or new), and recovery
// finishes the set from the journal (every new file was complete before the first rename).
TEST(AtomicWriteAll, KilledWhilePublishingIsFinishedByRecovery)
{
  TempDir dir;
  for (const char* name : { "a.stl", "b.stl", "c.stl" })
  {
    WriteText(dir / name, "old");
  }
  ASSERT_TRUE(KillWriterAt(dir, "atomic-publish"));
  EXPECT_EQ(ReadText(dir / "a.stl"), "A");
  EXPECT_EQ(ReadText(dir / "b.stl"), "old");
  bender::RecoverInterruptedWrites(dir.path().string());
  EXPECT_EQ(ReadText(dir / "a.stl"), "A");
  EXPECT_EQ(ReadText(dir / "b.stl"), "B");
  EXPECT_EQ(ReadText(dir / "c.stl"), "C");
  EXPECT_EQ(dir.Entries(), (std::set<std::string>{ "a.stl", "b.stl", "c.stl" }));
}

// Killed half-way through a text: the target keeps its previous content.
TEST(AtomicWrite, KilledHalfWayThroughATextKeepsThePreviousFile)
{
  TempDir dir;
  WriteText(dir / "plan.json", "previous");
  const pid_t child = ::fork();
  if (child == 0)
  {
    ::setenv(bender::FaultInjectionVariable, "text-write", 1);
    std::string problem;
    bender::AtomicWriteText(dir / "plan.json", std::string(100000, 'x'), problem);
    std::_Exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  EXPECT_EQ(ReadText(dir / "plan.json"), "previous");
  bender::RecoverInterruptedWrites(dir.path().string());
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "plan.json" });
}

// Leftovers of a live writer (this process) are not touched.
TEST(AtomicWrite, RecoveryLeavesTheTemporariesOfLiveWriters)
{
  TempDir dir;
  const std::string mine = dir / (".a.tmp-" + std::to_string(::getpid()) + "-0.stl");
  WriteText(mine, "in progress");
  bender::RecoverInterruptedWrites(dir.path().string());
  EXPECT_EQ(dir.Entries().count(".a.tmp-" + std::to_string(::getpid()) + "-0.stl"), 1u);
}

} // namespace
