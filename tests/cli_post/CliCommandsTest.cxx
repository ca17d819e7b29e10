// The command library (bender_cli_commands) in-process: every command answers --help with its
// own generated help and exit 0, and refuses an unknown option with one line naming it and exit
// 2 (CLI11 subcommands, the same contract for all).

#include "CliCommands.h"
#include "InProcessCli.h"
#include "MeshFormats.h"
#include "MeshIO.h"

#include <nlohmann/json.hpp>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using bendertest::RunInProcess;
using Captured = bendertest::CliRun;

TEST(CliCommands, EveryCommandHasItsOwnHelp)
{
  ASSERT_GE(bender::CliCommandNames().size(), 12u);
  for (const std::string& command : bender::CliCommandNames())
  {
    const Captured help = RunInProcess({ command, "--help" });
    EXPECT_EQ(help.status, 0) << command << "\n" << help.err;
    EXPECT_EQ(help.out.rfind("usage: bender-cli " + command, 0), 0u) << command << ": " << help.out;
    EXPECT_NE(help.out.find("-h,--help"), std::string::npos) << command << ": " << help.out;
    EXPECT_TRUE(help.err.empty()) << command << ": " << help.err;
    const Captured shortHelp = RunInProcess({ command, "-h" });
    EXPECT_EQ(shortHelp.status, 0) << command;
    EXPECT_EQ(shortHelp.out, help.out) << command;
  }
}

TEST(CliCommands, EveryCommandRefusesAnUnknownOptionWithExitTwo)
{
  for (const std::string& command : bender::CliCommandNames())
  {
    const Captured r = RunInProcess({ command, "--no-such-option" });
    EXPECT_EQ(r.status, 2) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("--no-such-option"), std::string::npos) << command << ": " << r.err;
    EXPECT_EQ(r.err.rfind("bender-cli " + command + ": ", 0), 0u) << command << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << command << ": " << r.err;
    EXPECT_NE(r.err.find("bender-cli " + command + " --help"), std::string::npos) << r.err;
  }
}

TEST(CliCommands, TheToolItself)
{
  Captured r = RunInProcess({});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("usage: bender-cli COMMAND"), std::string::npos);
  r = RunInProcess({ "--help" });
  EXPECT_EQ(r.status, 0);
  for (const std::string& command : bender::CliCommandNames())
  {
    EXPECT_NE(r.out.find("\n  " + command + " "), std::string::npos) << command << "\n" << r.out;
  }
  const Captured help = RunInProcess({ "help" });
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out, r.out);
  r = RunInProcess({ "frobnicate" });
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown command 'frobnicate'"), std::string::npos) << r.err;
  r = RunInProcess({ "--version" });
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("bender-cli "), std::string::npos);
}

TEST(CliCommands, TheHelpIsGeneratedFromTheRegisteredOptions)
{
  // The usage line names the positionals and the required options; every option is listed
  // with its value, its choices and its default.
  const Captured help = RunInProcess({ "export", "--help" });
  ASSERT_EQ(help.status, 0) << help.err;
  EXPECT_EQ(help.out.rfind("usage: bender-cli export IN_MESH -o OUT [options]\n", 0), 0u)
    << help.out;
  for (const char* option : { "-o,--output OUT",
         "--cap",
         "--planarity F",
         "--patches single|solids|files",
         "--unit mm|m",
         "--frame lps|ras",
         "--patches-json",
         "--quiet",
         "(default 0.1)",
         "(default single)",
         "exit status:" })
  {
    EXPECT_NE(help.out.find(option), std::string::npos) << option << "\n" << help.out;
  }
  const Captured warp = RunInProcess({ "warp", "--help" });
  EXPECT_EQ(warp.out.rfind("usage: bender-cli warp IN_MESH PLAN OUT_MESH [options]\n", 0), 0u)
    << warp.out;
  // The tool's own help: its options and every command with its summary.
  const Captured tool = RunInProcess({ "--help" });
  for (const char* option : { "-h,--help", "--version", "--data-dir" })
  {
    EXPECT_NE(tool.out.find(option), std::string::npos) << option << "\n" << tool.out;
  }
  // No line of any help is wider than a terminal.
  for (const std::string& command : bender::CliCommandNames())
  {
    std::istringstream lines(RunInProcess({ command, "--help" }).out);
    for (std::string line; std::getline(lines, line);)
    {
      EXPECT_LE(line.size(), 100u) << command << ": " << line;
    }
  }
}

TEST(CliCommands, AUsageErrorIsOneLineNamingTheOptionAndTheValue)
{
  const std::vector<std::vector<std::string>> cases = {
    { "export", "a.off", "-o", "o.stl", "--planarity", "1.5" },
    { "export", "a.off", "-o", "o.stl", "--frame", "xyz" },
    { "clip", "a.stl", "-o", "o.vtp", "--extend-inlet", "nan" },
    { "cfd-case", "a.vtp", "-o", "case", "--iterations", "2.5" },
    { "segment", "in.nrrd", "-o", "o.stl", "--seed", "1,2" },
  };
  for (const std::vector<std::string>& args : cases)
  {
    const Captured r = RunInProcess(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind("bender-cli " + args[0] + ": " + args[args.size() - 2] + ": ", 0), 0u)
      << r.err;
    EXPECT_NE(r.err.find(args.back()), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  // A missing required argument, and two options that exclude each other.
  Captured r = RunInProcess({ "export", "a.off" });
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--output is required"), std::string::npos) << r.err;
  r = RunInProcess({ "measure", "a.stl", "--after", "b.stl", "--plan", "p.json" });
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
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

TEST(CliCommands, FormatsListsTheRegistryAndExportWritesEveryWritableFormat)
{
  // A format registered through the table is listed by `formats` and written by `export`.
  const std::optional<bender::MeshFormat> off = bender::FindMeshFormatByName("off");
  ASSERT_TRUE(off);
  bender::MeshFormat dummy;
  dummy.name = "dummy";
  dummy.extensions = { ".dmy" };
  dummy.label = "Dummy mesh";
  dummy.read = off->read;
  dummy.write = off->write;
  const bender::ScopedMeshFormat registered(dummy);

  const Captured json = RunInProcess({ "formats", "--json" });
  ASSERT_EQ(json.status, 0) << json.err;
  const nlohmann::json list = nlohmann::json::parse(json.out).at("formats");
  const std::vector<bender::MeshFormat> formats = bender::MeshFormats();
  ASSERT_EQ(list.size(), formats.size());
  bool listed = false;
  for (std::size_t i = 0; i < list.size(); ++i)
  {
    const bender::MeshFormat& row = formats[i];
    EXPECT_EQ(list[i].at("name"), row.name);
    EXPECT_EQ(list[i].at("extensions").get<std::vector<std::string>>(), row.extensions);
    EXPECT_EQ(list[i].at("read").get<bool>(), row.CanRead());
    EXPECT_EQ(list[i].at("write").get<bool>(), row.CanWrite());
    listed = listed || list[i].at("name") == "dummy";
  }
  EXPECT_TRUE(listed) << json.out;
  const Captured table = RunInProcess({ "formats" });
  EXPECT_EQ(table.status, 0);
  EXPECT_NE(table.out.find("Dummy mesh"), std::string::npos) << table.out;

  // export writes every format marked writable, the dummy one included, and reads it back.
  const std::filesystem::path folder =
    std::filesystem::temp_directory_path() / "bender-cli-export-formats";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string input = (folder / "tetra.off").string();
  std::ofstream(input) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                          "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  for (const bender::MeshFormat& format : formats)
  {
    if (!format.CanWrite())
    {
      continue;
    }
    const std::string output = (folder / ("out" + format.extensions.front())).string();
    const Captured r = RunInProcess({ "export", input, "-o", output, "--quiet" });
    EXPECT_EQ(r.status, 0) << format.name << ": " << r.err;
    EXPECT_TRUE(std::filesystem::exists(output)) << format.name;
  }
  EXPECT_EQ(bender::ReadMesh((folder / "out.dmy").string())->GetNumberOfPolys(), 4);
  // An extension that no writable format has is a usage error naming the writable ones.
  const Captured refused = RunInProcess({ "export", input, "-o", (folder / "out.xyz").string() });
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find(".dmy"), std::string::npos) << refused.err;
  std::filesystem::remove_all(folder);
}
