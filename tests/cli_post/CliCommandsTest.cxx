// The command library (bender_cli_commands) in-process: every command of the table answers
// --help with its own usage and exit 0, and refuses an unknown option with one line naming it
// and exit 2 (CLI11 parsing, the same contract for all).

#include "CliCommands.h"
#include "InProcessCli.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

using bendertest::RunInProcess;
using Captured = bendertest::CliRun;

TEST(CliCommands, EveryCommandHasItsOwnHelp)
{
  ASSERT_GE(bender::CliCommandTable().size(), 7u);
  for (const bender::CliCommand& command : bender::CliCommandTable())
  {
    const Captured help = RunInProcess({ command.name, "--help" });
    EXPECT_EQ(help.status, 0) << command.name << "\n" << help.err;
    EXPECT_NE(help.out.find(std::string("bender-cli ") + command.name), std::string::npos)
      << command.name << ": " << help.out;
    const Captured shortHelp = RunInProcess({ command.name, "-h" });
    EXPECT_EQ(shortHelp.status, 0) << command.name;
    EXPECT_EQ(shortHelp.out, help.out) << command.name;
  }
}

TEST(CliCommands, EveryCommandRefusesAnUnknownOptionWithExitTwo)
{
  for (const bender::CliCommand& command : bender::CliCommandTable())
  {
    const Captured r = RunInProcess({ command.name, "--no-such-option" });
    EXPECT_EQ(r.status, 2) << command.name << "\n" << r.err;
    EXPECT_NE(r.err.find("--no-such-option"), std::string::npos) << command.name << ": " << r.err;
    EXPECT_NE(r.err.find(std::string("bender-cli ") + command.name), std::string::npos)
      << command.name << ": " << r.err;
  }
}

TEST(CliCommands, TheToolItself)
{
  Captured r = RunInProcess({});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("usage: bender-cli COMMAND"), std::string::npos);
  r = RunInProcess({ "--help" });
  EXPECT_EQ(r.status, 0);
  for (const bender::CliCommand& command : bender::CliCommandTable())
  {
    EXPECT_NE(r.out.find(command.name), std::string::npos) << command.name;
  }
  r = RunInProcess({ "frobnicate" });
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown command 'frobnicate'"), std::string::npos) << r.err;
  r = RunInProcess({ "--version" });
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("bender-cli "), std::string::npos);
}

TEST(CliCommands, NumbersAndChoicesAreCheckedBeforeAnyWork)
{
  // Values parsed by CLI11 are range-checked by the commands: usage errors, exit 2.
  EXPECT_EQ(RunInProcess({ "warp", "a.off", "p.json", "o.off", "--precision", "fast" }).status, 2);
  EXPECT_EQ(RunInProcess({ "export", "a.off", "-o", "o.stl", "--planarity", "1.5" }).status, 2);
  EXPECT_EQ(RunInProcess({ "export", "a.off", "-o", "o.stl", "--frame", "xyz" }).status, 2);
  EXPECT_EQ(RunInProcess({ "render", "a.off", "-o", "o.png", "--size", "10x10" }).status, 2);
  EXPECT_EQ(RunInProcess({ "render", "a.off", "-o", "o.png", "--view", "sideways" }).status, 2);
  EXPECT_EQ(RunInProcess({ "check" }).status, 2);
  EXPECT_EQ(RunInProcess({ "segment", "in.nrrd", "-o", "o.stl", "--seed", "1,2" }).status, 2);
  EXPECT_EQ(RunInProcess({ "phantom", "in.stl", "-o", "o.nrrd", "--spacing", "abc" }).status, 2);
  EXPECT_EQ(RunInProcess({ "tracker", "--device", "sim", "--count", "0" }).status, 2);
}

TEST(CliCommands, ExportBlamesTheInputForAnInputWithoutTriangles)
{
  // Issue 13: a problem of the input is reported against the input, never the output.
  const std::filesystem::path folder =
    std::filesystem::temp_directory_path() / "bender-cli-export-points-only";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string input = (folder / "points-only.ply").string();
  std::ofstream(input) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  const Captured r = RunInProcess({ "export", input, "-o", (folder / "out.stl").string() });
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("points-only.ply: the surface has no triangles"), std::string::npos)
    << r.err;
  EXPECT_EQ(r.err.find("out.stl"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(folder / "out.stl"));
  std::filesystem::remove_all(folder);
}
