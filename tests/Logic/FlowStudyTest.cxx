// The flow study behind the Flow panel (issue 23), without running OpenFOAM: the solver's
// iterations read as they are written, the cache's content key and its store (a case with
// results is found again, a changed plan or option is another case), and the two CFD-ready
// shapes of a session (the original prepared as the plan says, ends named alike).

#include "FlowStudy.h"
#include "ApplyPlan.h"
#include "CfdFlowResults.h"
#include "FlowCacheTrim.h"
#include "FlowCaseCache.h"
#include "LogicTestUtilities.h"
#include "MeshIO.h"
#include "PatchLabels.h"

#include <gtest/gtest.h>

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

using namespace bender;
namespace fs = std::filesystem;

namespace
{
const char* Header = "# Solver information\n"
                     "# Time  U_solver Ux_initial Ux_final Ux_iters Uy_initial Uy_final Uy_iters "
                     "p_solver p_initial p_final p_iters\n";

std::string Row(int iteration, double ux, double uy, double p)
{
  return std::to_string(iteration) + "\tsmoothSolver\t" + std::to_string(ux) + "\t1e-5\t2\t" +
    std::to_string(uy) + "\t1e-5\t2\tGAMG\t" + std::to_string(p) + "\t1e-6\t8\n";
}

/// Writes results a finished run would leave (flow.json, surface.vtp) into a case folder.
void FakeResults(const std::string& caseDirectory, vtkPolyData* surface)
{
  const fs::path results = fs::path(caseDirectory) / kCfdResultsFolder;
  fs::create_directories(results);
  CfdFlowResults flow;
  flow.caseDirectory = caseDirectory;
  flow.run.iterations = 3;
  std::ofstream(results / kCfdFlowJson) << CfdFlowResultsToJson(flow);
  WriteMesh(surface, (results / kCfdSurfaceResults).string());
}

std::vector<std::string> Entries(const std::string& folder)
{
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// A case folder of `bytes` bytes in two files, last used `age` minutes ago.
std::string FakeCase(const std::string& cache, const std::string& name, int bytes, int age)
{
  const fs::path folder = fs::path(cache) / name;
  fs::create_directories(folder / "constant");
  std::ofstream(folder / "Allrun") << std::string(static_cast<std::size_t>(bytes / 2), 'a');
  std::ofstream(folder / "constant" / "mesh")
    << std::string(static_cast<std::size_t>(bytes - bytes / 2), 'm');
  fs::last_write_time(folder, fs::file_time_type::clock::now() - std::chrono::minutes(age));
  return folder.string();
}
} // namespace

TEST(FlowStudy, SolverInfoIsReadWholeLinesOnly)
{
  std::string text = Header;
  for (int i = 1; i <= 5; ++i)
  {
    text += Row(i, 1.0 / i, 0.5 / i, 0.1 / i);
  }
  // The line being written is left for the next read.
  const std::string partial = "6\tsmoothSolver\t0.1";
  const std::vector<CfdIteration> rows = ParseSolverInfo(text + partial);
  ASSERT_EQ(rows.size(), 5u);
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    EXPECT_EQ(rows[i].iteration, static_cast<int>(i + 1));
    ASSERT_EQ(rows[i].residuals.size(), 3u);
    EXPECT_EQ(rows[i].residuals[0].first, "Ux");
    EXPECT_EQ(rows[i].residuals[1].first, "Uy");
    EXPECT_EQ(rows[i].residuals[2].first, "p");
    EXPECT_NEAR(rows[i].residuals[0].second, 1.0 / (i + 1), 1e-6);
    EXPECT_NEAR(rows[i].residuals[2].second, 0.1 / (i + 1), 1e-6);
  }
  EXPECT_TRUE(ParseSolverInfo("").empty());
  EXPECT_TRUE(ParseSolverInfo(std::string(Header) + "x y z\n").empty());
}

TEST(FlowStudy, TheMonitorReportsEachIterationOnceInOrderAsItIsWritten)
{
  const std::string folder = test::TemporaryFolder("flow_monitor");
  const fs::path file = fs::path(folder) / "postProcessing" / "solverInfo" / "0" / "solverInfo.dat";
  std::mutex mutex;
  std::vector<int> seen;
  CfdResidualMonitor monitor(
    folder,
    [&](const CfdIteration& it)
    {
      std::lock_guard<std::mutex> lock(mutex);
      seen.push_back(it.iteration);
    },
    20);
  std::this_thread::sleep_for(std::chrono::milliseconds(60)); // no file yet: nothing
  fs::create_directories(file.parent_path());
  {
    std::ofstream out(file);
    out << Header << std::flush;
    for (int i = 1; i <= 20; ++i)
    {
      out << Row(i, 1.0 / i, 0.5 / i, 0.1 / i) << std::flush;
      if (i % 5 == 0)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(40));
      }
    }
  }
  monitor.Stop();
  ASSERT_EQ(seen.size(), 20u);
  for (std::size_t i = 0; i < seen.size(); ++i)
  {
    EXPECT_EQ(seen[i], static_cast<int>(i + 1));
  }
  EXPECT_EQ(monitor.Count(), 20);
  monitor.Stop(); // twice: nothing more
  EXPECT_EQ(seen.size(), 20u);
}

TEST(FlowStudy, TheOriginalIsPreparedAsThePlanSaysWithTheSameEnds)
{
  const FlowStudyInput input = test::PreparedThenBentTube(15);
  const LabelledSurface original = FlowReadySurface(input, FlowShape::Original);
  const LabelledSurface current = FlowReadySurface(input, FlowShape::Current);
  ASSERT_TRUE(original.surface && current.surface);
  // The step before the warp: the original is the history's prepared surface, point for point.
  const ApplyPlanResult replay = ApplyPlan(input.first, input.plan);
  EXPECT_EQ(test::MaxDifference(original.surface, replay.prepared.front().surface), 0.0);
  EXPECT_GT(test::MaxDifference(original.surface, current.surface), 0.1);
  ASSERT_EQ(original.patches.size(), current.patches.size());
  for (std::size_t i = 0; i < original.patches.size(); ++i)
  {
    EXPECT_EQ(original.patches[i].name, current.patches[i].name);
    EXPECT_EQ(original.patches[i].type, current.patches[i].type);
  }

  // A shape that is not prepared: one line, naming the surface.
  FlowStudyInput bare;
  bare.first = test::MakeTube(-20, 20, 5, 41, 32);
  bare.current = bare.first;
  bare.name = "bare tube";
  try
  {
    FlowReadySurface(bare, FlowShape::Original);
    FAIL() << "an unprepared surface was accepted";
  }
  catch (const InputError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("bare tube"), std::string::npos) << what;
    EXPECT_NE(what.find("Prepare for CFD"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(FlowStudy, TheCacheFindsASolvedCaseAndKeysAChangedPlanOrOptionApart)
{
  const std::string cache = test::TemporaryFolder("flow_cache");
  const FlowStudyInput input = test::PreparedThenBentTube(15);
  const LabelledSurface current = FlowReadySurface(input, FlowShape::Current);
  CfdCaseOptions options;
  options.iterations = 50;

  const CachedFlowCase first = StoreFlowCase(current, options, cache);
  EXPECT_FALSE(first.solved);
  EXPECT_EQ(first.key.size(), 32u);
  EXPECT_EQ(first.caseDirectory, (fs::path(cache) / first.key).string());
  EXPECT_TRUE(fs::exists(fs::path(first.caseDirectory) / "Allrun"));
  EXPECT_EQ(FlowCaseKey(first.written), first.key); // the key is the stored files' content

  // Not run yet: stored again, the same case, still to be solved (an interrupted run re-runs).
  const CachedFlowCase again = StoreFlowCase(current, options, cache);
  EXPECT_EQ(again.key, first.key);
  EXPECT_FALSE(again.solved);

  // Once its results are there, the same inputs find them: nothing to solve.
  EXPECT_FALSE(HasFlowResults(first.caseDirectory));
  FakeResults(first.caseDirectory, current.surface);
  ASSERT_TRUE(HasFlowResults(first.caseDirectory));
  const CachedFlowCase found = StoreFlowCase(current, options, cache);
  EXPECT_TRUE(found.solved);
  EXPECT_EQ(found.key, first.key);
  EXPECT_EQ(Entries(cache), std::vector<std::string>{ first.key }); // nothing else left there
  const FlowShapeResult read = ReadFlowShape(found.caseDirectory, FlowShape::Current);
  EXPECT_EQ(read.results.run.iterations, 3);
  ASSERT_TRUE(read.surface);
  EXPECT_EQ(read.surface->GetNumberOfCells(), current.surface->GetNumberOfCells());

  // Another bend (a changed plan) is another case; so is another option; the original too.
  const LabelledSurface bentMore =
    FlowReadySurface(test::PreparedThenBentTube(25), FlowShape::Current);
  const CachedFlowCase other = StoreFlowCase(bentMore, options, cache);
  EXPECT_NE(other.key, first.key);
  EXPECT_FALSE(other.solved);
  CfdCaseOptions longer = options;
  longer.iterations = 60;
  EXPECT_NE(StoreFlowCase(current, longer, cache).key, first.key);
  const LabelledSurface original = FlowReadySurface(input, FlowShape::Original);
  EXPECT_NE(StoreFlowCase(original, options, cache).key, first.key);
  EXPECT_EQ(Entries(cache).size(), 4u);

  // A cache folder that cannot be made: one line naming it.
  const std::string blocked = cache + "/" + first.key + "/Allrun/flow";
  EXPECT_THROW(StoreFlowCase(current, options, blocked), InputError);
}

TEST(FlowStudy, TheCacheIsTrimmedLeastRecentlyUsedFirstKeepingTheCasesShown)
{
  const std::string cache = test::TemporaryFolder("flow_cache_trim");
  // Five cases, the first the oldest; a folder that is not a case, a write under way.
  std::vector<std::string> cases;
  for (int i = 0; i < 5; ++i)
  {
    cases.push_back(FakeCase(cache, std::string(31, '0') + std::to_string(i), 1000, 50 - 10 * i));
  }
  // A case of an earlier version's cache (a 16-digit key), the least recently used.
  const std::string older = FakeCase(cache, "00000000000000ff", 1000, 60);
  fs::create_directories(fs::path(cache) / "notes");
  fs::create_directories(fs::path(cache) / ".incoming-1-1");
  EXPECT_EQ(FolderBytes(cases[0]), 1000u);
  EXPECT_EQ(FolderBytes(cache), 6000u);

  // Within the limits: nothing goes.
  FlowCacheTrimResult within = TrimFlowCache(cache, { 6, 6000 }, {});
  EXPECT_TRUE(within.removed.empty());
  EXPECT_EQ(within.casesLeft, 6);
  EXPECT_EQ(within.bytesLeft, 6000u);

  // Three cases at most: the two least recently used go, except a case on screen (the oldest);
  // a case used again (found in the cache) is the newest.
  MarkFlowCaseUsed(cases[1]);
  const FlowCacheTrimResult counted = TrimFlowCache(cache, { 3, 1u << 30 }, { cases[0] });
  EXPECT_EQ(counted.removed, (std::vector<std::string>{ older, cases[2], cases[3] }));
  EXPECT_EQ(counted.casesLeft, 3);
  EXPECT_EQ(counted.bytesLeft, 3000u);
  EXPECT_EQ(Entries(cache),
    (std::vector<std::string>{ ".incoming-1-1",
      std::string(31, '0') + "0",
      std::string(31, '0') + "1",
      std::string(31, '0') + "4",
      "notes" }));

  // By size: 2500 bytes hold two cases; the oldest not shown goes.
  const FlowCacheTrimResult sized = TrimFlowCache(cache, { 20, 2500 }, { cases[0] });
  EXPECT_EQ(sized.removed, (std::vector<std::string>{ cases[4] }));
  EXPECT_EQ(sized.casesLeft, 2);
  EXPECT_LE(sized.bytesLeft, 2500u);

  // The cases shown stay even when they alone are over the limits.
  const FlowCacheTrimResult shown = TrimFlowCache(cache, { 1, 10 }, { cases[0], cases[1] });
  EXPECT_TRUE(shown.removed.empty());
  EXPECT_EQ(shown.casesLeft, 2);
  EXPECT_TRUE(fs::exists(cases[0]) && fs::exists(cases[1]));

  // No cache folder yet: nothing to trim.
  const FlowCacheTrimResult none = TrimFlowCache(cache + "/missing", {}, {});
  EXPECT_TRUE(none.removed.empty());
  EXPECT_EQ(none.casesLeft, 0);
}
