// The flow study really run (issue 23, label cfd): a small tube prepared for CFD and bent, its
// original and current shape solved by OpenFOAM on a coarse mesh with few iterations. The
// solver's iterations arrive while it runs; the same inputs again are found in the cache (no
// second solve: the case folder is untouched); a changed plan is a new case; both shapes run at
// once give what each gives alone; a shape that fails does not stop the other.

#include "BenderErrors.h"
#include "CfdTestUtilities.h"
#include "FlowCaseCache.h"
#include "FlowStudy.h"
#include "LogicTestUtilities.h"
#include "ProcessRunner.h"

#include <gtest/gtest.h>

#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <vector>

using namespace bender;
namespace fs = std::filesystem;

namespace
{
fs::file_time_type Stamp(const std::string& caseDirectory)
{
  return fs::last_write_time(fs::path(caseDirectory) / "log.simpleFoam");
}

/// A coarse case (a few thousand cells, 25 iterations) in the cache folder `cache`.
FlowStudyOptions CoarseStudy(const std::string& cache)
{
  FlowStudyOptions options;
  options.cacheDirectory = cache;
  options.caseOptions.cellSize = 1.6e-3;
  options.caseOptions.iterations = 25;
  return options;
}

/// Puts first on PATH a snappyHexMesh that fails the first time it is started (whichever shape
/// that is) and runs the real one afterwards; the PATH is restored when it goes.
class FirstMeshingFails
{
public:
  explicit FirstMeshingFails(const std::string& bin)
    : Bin(bin)
    , Path(std::getenv("PATH") ? std::getenv("PATH") : "")
  {
    const std::string real = FindExecutable("snappyHexMesh");
    std::ofstream(Bin + "/snappyHexMesh")
      << "#!/bin/sh\nif mkdir \"" << Bin << "/failed\" 2>/dev/null; then\n"
      << "    echo 'made to fail by the test' >&2\n    exit 1\nfi\nexec \"" << real
      << "\" \"$@\"\n";
    fs::permissions(Bin + "/snappyHexMesh", fs::perms::owner_all);
    setenv("PATH", (Bin + ":" + Path).c_str(), 1);
  }
  ~FirstMeshingFails() { setenv("PATH", Path.c_str(), 1); }
  FirstMeshingFails(const FirstMeshingFails&) = delete;
  FirstMeshingFails& operator=(const FirstMeshingFails&) = delete;

private:
  std::string Bin;
  std::string Path;
};

/// The study's failure: its type, its message.
template<typename Run>
std::string FailureOf(Run run)
{
  try
  {
    run();
  }
  catch (const InputError& e)
  {
    return std::string("InputError: ") + e.what();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no failure";
}
} // namespace

TEST(FlowStudyCfd, AShapeIsSolvedOnceAndAChangedPlanIsANewCase)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  BENDER_REQUIRE_PROGRAM("snappyHexMesh");
  const std::string cache = test::TemporaryFolder("flow_study_cfd");
  FlowStudyOptions options = CoarseStudy(cache);
  std::mutex mutex;
  std::vector<int> iterations;
  options.onIteration = [&](const CfdIteration& it)
  {
    std::lock_guard<std::mutex> lock(mutex);
    iterations.push_back(it.iteration);
  };
  std::vector<std::string> stages;
  options.progress.onProgress = [&](const std::string& stage, double)
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (stages.empty() || stages.back() != stage)
    {
      stages.push_back(stage);
    }
  };

  const FlowStudyInput input = test::PreparedThenBentTube(15);
  const FlowShapeResult current = RunFlowShape(input, FlowShape::Current, options);
  EXPECT_FALSE(current.cached);
  ASSERT_TRUE(current.surface);
  EXPECT_NE(current.surface->GetPointData()->GetArray(kPressureArrayName), nullptr);
  EXPECT_NE(current.surface->GetPointData()->GetArray(kWallShearStressMagnitudeArrayName), nullptr);
  EXPECT_GT(current.results.run.iterations, 0);
  // Streamlines from the inlet, inside the vessel's box.
  ASSERT_TRUE(current.streamlines) << current.streamlineProblem;
  EXPECT_GT(current.streamlines->GetNumberOfLines(), 0);
  double box[6], lines[6];
  current.surface->GetBounds(box);
  current.streamlines->GetBounds(lines);
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_GE(lines[2 * k], box[2 * k] - 0.5);
    EXPECT_LE(lines[2 * k + 1], box[2 * k + 1] + 0.5);
  }
  // The solver's iterations, each once, in order, as many as it ran.
  ASSERT_FALSE(iterations.empty());
  EXPECT_EQ(static_cast<int>(iterations.size()), current.results.run.iterations);
  for (std::size_t i = 1; i < iterations.size(); ++i)
  {
    EXPECT_GT(iterations[i], iterations[i - 1]);
  }
  EXPECT_NE(std::find(stages.begin(), stages.end(), "solve"), stages.end());
  EXPECT_NE(std::find(stages.begin(), stages.end(), "mesh: snappyHexMesh"), stages.end());

  // The same inputs: found in the cache, the folder untouched, the same numbers, the same plot.
  const auto stamp = Stamp(current.caseDirectory);
  iterations.clear();
  const FlowShapeResult again = RunFlowShape(input, FlowShape::Current, options);
  EXPECT_TRUE(again.cached);
  EXPECT_EQ(again.caseDirectory, current.caseDirectory);
  EXPECT_EQ(Stamp(again.caseDirectory), stamp);
  EXPECT_EQ(CfdFlowResultsToJson(again.results), CfdFlowResultsToJson(current.results));
  EXPECT_EQ(static_cast<int>(iterations.size()), current.results.run.iterations);

  // A changed plan (the bend swung further): a new case, solved.
  const FlowShapeResult changed =
    RunFlowShape(test::PreparedThenBentTube(25), FlowShape::Current, options);
  EXPECT_FALSE(changed.cached);
  EXPECT_NE(changed.key, current.key);
  EXPECT_EQ(Stamp(current.caseDirectory), stamp);
}

TEST(FlowStudyCfd, BothShapesRunAtOnceEachWithItsOwnIterationsAndTheirOwnResults)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  BENDER_REQUIRE_PROGRAM("snappyHexMesh");
  const std::string cache = test::TemporaryFolder("flow_study_both");
  FlowStudyOptions options = CoarseStudy(cache);
  std::mutex mutex;
  std::map<FlowShape, std::vector<int>> iterations;
  std::vector<std::string> stages;
  options.progress.onProgress = [&](const std::string& stage, double)
  {
    std::lock_guard<std::mutex> lock(mutex);
    stages.push_back(stage);
  };
  const auto onIteration = [&](FlowShape shape, const CfdIteration& it)
  {
    std::lock_guard<std::mutex> lock(mutex);
    iterations[shape].push_back(it.iteration);
  };

  const FlowStudyInput input = test::PreparedThenBentTube(15);
  const FlowStudyResult study = RunFlowStudy(input, options, onIteration, true);
  const FlowShapeResult& original = study.shapes[0];
  const FlowShapeResult& current = study.shapes[1];
  EXPECT_EQ(original.shape, FlowShape::Original);
  EXPECT_EQ(current.shape, FlowShape::Current);
  EXPECT_FALSE(original.cached);
  EXPECT_FALSE(current.cached);
  EXPECT_NE(original.key, current.key);
  // Each shape's iterations reach its own plot, each once, in order.
  for (const FlowShapeResult* r : { &original, &current })
  {
    const std::vector<int>& seen = iterations[r->shape];
    EXPECT_EQ(static_cast<int>(seen.size()), r->results.run.iterations) << FlowShapeName(r->shape);
    EXPECT_GT(r->results.run.iterations, 0);
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
    ASSERT_TRUE(r->surface);
  }
  // The stages are named after their shape.
  EXPECT_NE(std::find(stages.begin(), stages.end(), "original: solve"), stages.end());
  EXPECT_NE(std::find(stages.begin(), stages.end(), "current shape: solve"), stages.end());

  // Run at once, each is what it is alone: the original read back by RunFlowShape is the same
  // case with the same numbers, and the bend changed them.
  const FlowShapeResult alone = RunFlowShape(input, FlowShape::Original, options);
  EXPECT_TRUE(alone.cached);
  EXPECT_EQ(alone.caseDirectory, original.caseDirectory);
  EXPECT_EQ(CfdFlowResultsToJson(alone.results), CfdFlowResultsToJson(original.results));
  EXPECT_NE(CfdFlowResultsToJson(current.results), CfdFlowResultsToJson(original.results));

  // Again, one after the other: both found in the cache, nothing run.
  const FlowStudyResult again = RunFlowStudy(input, options, onIteration, false);
  EXPECT_TRUE(again.shapes[0].cached);
  EXPECT_TRUE(again.shapes[1].cached);
  EXPECT_EQ(again.shapes[1].caseDirectory, current.caseDirectory);
}

TEST(FlowStudyCfd, AShapeThatFailsDoesNotStopTheOther)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  BENDER_REQUIRE_PROGRAM("snappyHexMesh");
  const FlowStudyInput input = test::PreparedThenBentTube(15);
  for (const bool concurrent : { true, false })
  {
    SCOPED_TRACE(concurrent ? "both at once" : "one after the other");
    const std::string cache =
      test::TemporaryFolder(concurrent ? "flow_study_fail_both" : "flow_study_fail_serial");
    const FlowStudyOptions options = CoarseStudy(cache);
    std::string failure;
    {
      const FirstMeshingFails wrapper(test::TemporaryFolder("flow_study_fail_bin"));
      failure = FailureOf([&] { RunFlowStudy(input, options, nullptr, concurrent); });
    }
    // One line led by the shape that failed (one after the other: the original, run first),
    // naming the step and its log.
    const bool originalFailed = failure.rfind("original: ", 0) == 0;
    EXPECT_TRUE(originalFailed || failure.rfind("current shape: ", 0) == 0) << failure;
    if (!concurrent)
    {
      EXPECT_TRUE(originalFailed) << failure;
    }
    EXPECT_NE(failure.find("snappyHexMesh failed, see log.snappyHexMesh"), std::string::npos)
      << failure;
    EXPECT_EQ(failure.find('\n'), std::string::npos) << failure;

    // The other shape was solved all the same: run again, it is found in the cache and only the
    // failed one is run.
    const FlowStudyResult again = RunFlowStudy(input, options, nullptr, concurrent);
    const int failed = originalFailed ? 0 : 1;
    EXPECT_FALSE(again.shapes[failed].cached);
    EXPECT_TRUE(again.shapes[1 - failed].cached);
    EXPECT_GT(again.shapes[failed].results.run.iterations, 0);
  }
}

TEST(FlowStudyCfd, AFailedOriginalThatIsTheCurrentShapeIsNotRunTwice)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  BENDER_REQUIRE_PROGRAM("snappyHexMesh");
  // Nothing bent: both shapes are one case. Its first meshing fails; one after the other, the
  // current shape (the same case) is not run again, so the case stays without results.
  const FlowStudyInput input = test::PreparedThenBentTube(0);
  const std::string cache = test::TemporaryFolder("flow_study_fail_same");
  const FlowStudyOptions options = CoarseStudy(cache);
  std::string failure;
  {
    const FirstMeshingFails wrapper(test::TemporaryFolder("flow_study_fail_bin"));
    failure = FailureOf([&] { RunFlowStudy(input, options, nullptr, false); });
  }
  EXPECT_EQ(failure.rfind("original: ", 0), 0u) << failure;
  std::vector<fs::path> cases;
  for (const auto& entry : fs::directory_iterator(cache))
  {
    if (entry.is_directory())
    {
      cases.push_back(entry.path());
    }
  }
  ASSERT_EQ(cases.size(), 1u);
  EXPECT_FALSE(HasFlowResults(cases[0].string()));
}
