// Crash safety (issue 25): every operation that writes is killed with SIGKILL at each of its
// fault-injection points (BENDER_FAULT_AT, FaultInjection.h), in a process of its own
// (bender-cli or bender_fault_driver). Afterwards: no half-written file at any destination (each
// is the old one, the new one, or absent), the input unchanged, and the next start (the next
// write there, RecoverInterruptedWrites, Recover of the autosave, a replay) finds the last
// consistent state and no leftover.

#include "AtomicFileRecovery.h"
#include "BenderSession.h"
#include "HostileMeshes.h"
#include "ProcessRunner.h"
#include "ReplayTransport.h"
#include "SessionAutosave.h"
#include "WarpPlanIO.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
namespace fs = std::filesystem;

const std::string Cli = BENDER_CLI_PATH;
const std::string Driver = BENDER_FAULT_DRIVER;
const std::string Aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";

std::string ReadBytes(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

/// Every file under folder (relative path -> content), hidden ones included.
using FolderState = std::map<std::string, std::string>;
FolderState StateOf(const fs::path& folder)
{
  FolderState state;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
  {
    if (entry.is_regular_file())
    {
      state[fs::relative(entry.path(), folder).string()] = ReadBytes(entry.path());
    }
  }
  return state;
}

struct Outcome
{
  bender::ProcessResult result;
  std::vector<std::string> lines;
  bool Killed() const { return this->result.signal == SIGKILL; }
};

/// Runs argv with BENDER_FAULT_AT=point (none when empty).
Outcome RunAt(const std::string& point, std::vector<std::string> argv)
{
  Outcome run;
  bender::ProcessOptions options;
  options.argv = { "env", "BENDER_FAULT_AT=" + point };
  options.argv.insert(options.argv.end(), argv.begin(), argv.end());
  options.onLine = [&run](const std::string& line) { run.lines.push_back(line); };
  options.timeoutSeconds = 300;
  run.result = bender::RunProcess(options);
  return run;
}

class CrashSafety : public ::testing::Test
{
protected:
  void SetUp() override
  {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(name.begin(), name.end(), '/', '_');
    this->Dir =
      fs::temp_directory_path() / ("bender-crash-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(this->Dir);
    fs::create_directories(this->Dir);
  }
  void TearDown() override { fs::remove_all(this->Dir); }

  // The aneurysm capped and labelled (the input of the export and CFD tests).
  std::string Vessel()
  {
    const std::string vessel = (this->Dir / "vessel.vtp").string();
    const Outcome made = RunAt("", { Cli, "export", Aneurysm, "-o", vessel, "--cap" });
    EXPECT_TRUE(made.result.Succeeded()) << made.result.lastLine;
    return vessel;
  }

  fs::path Dir;
};

// ---------------------------------------------------------------------------------------
// Export: one STL per patch and the patches sidecar, written as one set.

class ExportCrash
  : public CrashSafety
  , public ::testing::WithParamInterface<const char*>
{
};

TEST_P(ExportCrash, LeavesEachFileWholeAndTheNextStartFinishesTheSet)
{
  if (!fs::exists(Aneurysm))
  {
    GTEST_SKIP() << Aneurysm << " is missing: run scripts/fetch-data";
  }
  const std::string vessel = this->Vessel();
  const std::string input = ReadBytes(vessel);
  const fs::path out = this->Dir / "out", fresh = this->Dir / "fresh";
  fs::create_directories(out);
  fs::create_directories(fresh);
  const auto exportTo =
    [&](const fs::path& folder, const std::string& frame, const std::string& point)
  {
    return RunAt(point,
      { Cli,
        "export",
        vessel,
        "-o",
        (folder / "o.stl").string(),
        "--patches",
        "files",
        "--frame",
        frame });
  };
  ASSERT_TRUE(exportTo(out, "ras", "").result.Succeeded());
  const FolderState before = StateOf(out);
  ASSERT_GE(before.size(), 3u); // a wall, at least two ends, the sidecar
  ASSERT_TRUE(exportTo(fresh, "lps", "").result.Succeeded());
  const FolderState after = StateOf(fresh);

  const Outcome killed = exportTo(out, "lps", GetParam());
  ASSERT_TRUE(killed.Killed()) << GetParam() << ": " << killed.result.lastLine;
  EXPECT_EQ(ReadBytes(vessel), input);
  // Each destination whole: its old content or its new one, never a part.
  for (const auto& [name, content] : before)
  {
    const std::string now = ReadBytes(out / name);
    EXPECT_TRUE(now == content || now == after.at(name)) << name << " is half-written";
  }
  // The next start: a published set is finished, a set not yet published stays old; either
  // way no leftover.
  bender::RecoverInterruptedWrites(out.string());
  const FolderState recovered = StateOf(out);
  EXPECT_TRUE(recovered == before || recovered == after) << GetParam();
  EXPECT_EQ(recovered == after, std::string(GetParam()) == "atomic-publish");
}

INSTANTIATE_TEST_SUITE_P(Points, ExportCrash, ::testing::Values("atomic-write", "atomic-publish"));

// ---------------------------------------------------------------------------------------
// Session: warps committed one by one, each followed by its autosave.

class SessionCrash
  : public CrashSafety
  , public ::testing::WithParamInterface<const char*>
{
};

TEST_P(SessionCrash, TheAutosaveHoldsTheLastCompleteStepAndRecovers)
{
  // A 10 mm cube, bent three times in a row.
  const std::string mesh = (this->Dir / "cube.stl").string();
  std::ofstream(mesh, std::ios::binary) << bendertest::CubeStl(4);
  const std::string input = ReadBytes(mesh);
  const std::string planPath = (this->Dir / "plan.bender.json").string();
  {
    const auto frame = [](double x, double y)
    {
      return nlohmann::json{
        { "position", { x, y, 5.0 } }, { "tangent", { 1, 0, 0 } }, { "normal", { 0, 0, 1 } }
      };
    };
    nlohmann::json warps = nlohmann::json::array();
    for (int k = 1; k <= 3; ++k)
    {
      warps.push_back({ { "initial", { { "start", frame(2, 5) }, { "end", frame(8, 5) } } },
        { "final", { { "start", frame(2, 5) }, { "end", frame(8, 5 + 0.5 * k) } } },
        { "radius", 3.0 } });
    }
    std::ofstream(planPath) << nlohmann::json{
      { "format", "bender-warps" }, { "version", 1 }, { "units", "mm" }, { "warps", warps }
    }.dump(2);
  }
  const bender::WarpPlan plan = bender::ReadWarpPlan(planPath);
  const std::string autosave = (this->Dir / "autosave.bender-session.json").string();

  const Outcome killed = RunAt(GetParam(), { Driver, "session", mesh, planPath, autosave });
  ASSERT_TRUE(killed.Killed()) << GetParam() << ": " << killed.result.lastLine;
  const std::size_t applied = killed.lines.size(); // "applied K", one per complete step
  ASSERT_GE(applied, 1u) << GetParam();
  EXPECT_EQ(ReadBytes(mesh), input);

  // The autosave is whole and holds exactly the complete steps, in order.
  const bender::SessionSnapshot snapshot = bender::ReadSessionFile(autosave);
  ASSERT_EQ(snapshot.plan.warps.size(), applied) << GetParam();
  bender::WarpPlan done;
  done.warps.assign(plan.warps.begin(), plan.warps.begin() + static_cast<long>(applied));
  EXPECT_EQ(
    bender::WarpPlanToJson(snapshot.plan, "autosave"), bender::WarpPlanToJson(done, "plan"));
  // The next start recovers it: the same steps, and no leftover beside the autosave.
  bender::BenderSession next;
  ASSERT_TRUE(next.Recover(autosave));
  EXPECT_EQ(next.GetHistoryPosition(), applied);
  EXPECT_EQ(
    bender::WarpPlanToJson(next.GetPlan(), "recovered"), bender::WarpPlanToJson(done, "plan"));
  bender::RecoverInterruptedWrites(this->Dir.string());
  for (const auto& entry : fs::directory_iterator(this->Dir))
  {
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
  }
}

// Killed in the second warp: after its commit (the autosave not yet written), half-way
// through the autosave's text, and with the autosave complete but not yet in place. The
// autosave written at load is the first visit of the two write points.
INSTANTIATE_TEST_SUITE_P(Points,
  SessionCrash,
  ::testing::Values("commit:2", "text-write:3", "atomic-write:3"));

// ---------------------------------------------------------------------------------------
// Tracker recording: killed between a chunk's bytes and its timestamp line.

TEST_F(CrashSafety, RecordingKeepsEveryListedChunk)
{
  const std::string file = (this->Dir / "session.fastrak").string();
  const Outcome killed = RunAt("recording:4", { Driver, "record", file, "10" });
  ASSERT_TRUE(killed.Killed()) << killed.result.lastLine;
  const std::size_t appended = killed.lines.size();
  EXPECT_EQ(appended, 3u);
  // Every timestamp line is whole and lists bytes that are in the file, as recorded.
  const std::string data = ReadBytes(file);
  std::istringstream times(ReadBytes(file + ".timestamps"));
  std::string line;
  std::size_t listed = 0, offset = 0;
  while (std::getline(times, line))
  {
    if (line.empty() || line[0] == '#')
    {
      continue;
    }
    std::istringstream fields(line);
    std::size_t at = 0, size = 0;
    double seconds = 0;
    ASSERT_TRUE(static_cast<bool>(fields >> at >> size >> seconds)) << line;
    EXPECT_EQ(at, offset);
    EXPECT_EQ(size, 100 + listed);
    ASSERT_LE(at + size, data.size());
    EXPECT_EQ(data.substr(at, size), std::string(size, static_cast<char>(listed + 1)));
    offset += size;
    ++listed;
  }
  EXPECT_EQ(listed, appended);
  // The chunk being written when the process died is on disk whole, unlisted.
  EXPECT_EQ(data.size(), offset + 100 + listed);
  // And the recording replays as it is: every byte, the unlisted chunk last.
  bender::ReplayTransport replay(file);
  EXPECT_EQ(replay.UnlistedBytes(), 100 + listed);
  std::string replayed;
  std::uint8_t buffer[256];
  while (!replay.AtEnd())
  {
    const std::size_t n = replay.Read(buffer, sizeof buffer, std::chrono::milliseconds(0));
    replayed.append(reinterpret_cast<const char*>(buffer), n);
  }
  EXPECT_TRUE(replayed == data);
}

// ---------------------------------------------------------------------------------------
// CFD case: killed half-way through writing the new case, and with the new case in place but
// the old one not yet removed.

class CfdCaseCrash
  : public CrashSafety
  , public ::testing::WithParamInterface<const char*>
{
};

TEST_P(CfdCaseCrash, TheCaseFolderIsTheOldOrTheNewCase)
{
  if (!fs::exists(Aneurysm))
  {
    GTEST_SKIP() << Aneurysm << " is missing: run scripts/fetch-data";
  }
  const std::string vessel = this->Vessel();
  const std::string input = ReadBytes(vessel);
  const fs::path cases = this->Dir / "cases";
  fs::create_directories(cases);
  const std::string target = (cases / "case").string();
  const auto write = [&](const std::string& iterations, const std::string& point)
  {
    return RunAt(
      point, { Cli, "cfd-case", vessel, "-o", target, "--force", "--iterations", iterations });
  };
  ASSERT_TRUE(write("111", "").result.Succeeded());
  const FolderState before = StateOf(target);
  const Outcome killed = write("222", GetParam());
  ASSERT_TRUE(killed.Killed()) << GetParam() << ": " << killed.result.lastLine;
  EXPECT_EQ(ReadBytes(vessel), input);
  const FolderState now = StateOf(target);
  const bool isNew =
    ReadBytes(fs::path(target) / "system/controlDict").find("222") != std::string::npos;
  if (!isNew)
  {
    EXPECT_EQ(now, before) << GetParam();
  }
  EXPECT_EQ(isNew, std::string(GetParam()) == "folder-replace");
  EXPECT_EQ(now.size(), before.size());
  // The next start: no leftover beside the case.
  bender::RecoverInterruptedWrites(cases.string());
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(cases))
  {
    names.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(names, std::vector<std::string>{ "case" });
  EXPECT_EQ(StateOf(target), now);
}

INSTANTIATE_TEST_SUITE_P(Points, CfdCaseCrash, ::testing::Values("cfd-case:3", "folder-replace"));

} // namespace
