// bender::AtomicWrite / AtomicWriteAll: the content appears whole or not at all, the previous
// files survive every failure, and no temporary file is left behind.

#include "AtomicFile.h"

#include "IOTestUtilities.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

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

} // namespace
