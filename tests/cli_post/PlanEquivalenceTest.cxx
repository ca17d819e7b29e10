// Every plan of examples/ applied through bender-cli (the warp command, in-process through
// bender_cli_commands) and through BenderSession (ReplayPlan, and ApplyWarp one warp at a time)
// gives exactly the same coordinates: one rule for applying a plan (bender::ApplyPlan).

#include "ApplyPlan.h"
#include "BenderSession.h"
#include "CliCommands.h"
#include "MeshIO.h"
#include "WarpPlanIO.h"

#include <gtest/gtest.h>

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace
{
const std::string Source = BENDER_SOURCE_DIR;

// The mesh each example plan was made for (docs/gallery.md).
std::string MeshFor(const std::string& plan)
{
  const std::pair<const char*, std::string> table[] = {
    { "cow", Source + "/data/external/cow.off" },
    { "bunny", Source + "/data/external/bunny00.off" },
    { "display", Source + "/data/external/bunny00.off" },
    { "sphere", Source + "/data/external/sphere.off" },
    { "tube", Source + "/tests/data/conformance/tube.off" },
    { "plane", Source + "/data/external/plane.off" },
    { "aneurysm", Source + "/data/external/aneurysm_data.stl" },
  };
  for (const auto& entry : table)
  {
    if (plan.find(entry.first) != std::string::npos)
    {
      return entry.second;
    }
  }
  return {};
}

// Exact equality of two surfaces: same points (bit for bit) and same polygons.
::testing::AssertionResult SameSurface(vtkPolyData* a, vtkPolyData* b)
{
  if (!a || !b)
  {
    return ::testing::AssertionFailure() << "missing surface";
  }
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints() ||
    a->GetNumberOfPolys() != b->GetNumberOfPolys())
  {
    return ::testing::AssertionFailure()
      << a->GetNumberOfPoints() << " points / " << a->GetNumberOfPolys() << " polygons vs "
      << b->GetNumberOfPoints() << " / " << b->GetNumberOfPolys();
  }
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2])
    {
      return ::testing::AssertionFailure()
        << "point " << i << " differs: (" << p[0] << ", " << p[1] << ", " << p[2] << ") vs ("
        << q[0] << ", " << q[1] << ", " << q[2] << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

std::vector<fs::path> ExamplePlans()
{
  std::vector<fs::path> plans;
  for (const auto& entry : fs::directory_iterator(Source + "/examples"))
  {
    const std::string name = entry.path().filename().string();
    if (name.size() > 12 && name.compare(name.size() - 12, 12, ".bender.json") == 0)
    {
      plans.push_back(entry.path());
    }
  }
  std::sort(plans.begin(), plans.end());
  return plans;
}
} // namespace

TEST(PlanEquivalence, EveryExamplePlanGivesTheSameCoordinatesInTheCliAndTheSession)
{
  const std::vector<fs::path> plans = ExamplePlans();
  ASSERT_GE(plans.size(), 20u) << "examples/ lost its plans";
  const fs::path scratch =
    fs::temp_directory_path() / ("bender-plan-equivalence-" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  int compared = 0;
  for (const fs::path& planPath : plans)
  {
    const std::string name = planPath.filename().string();
    SCOPED_TRACE(name);
    const std::string meshPath = MeshFor(name);
    ASSERT_FALSE(meshPath.empty()) << "no mesh known for " << name << ": extend MeshFor";
    ASSERT_TRUE(fs::exists(meshPath)) << meshPath << " missing: run scripts/fetch-data";

    // bender-cli warp, in-process; VTP keeps the double coordinates bit for bit.
    const std::string out = (scratch / (name + ".vtp")).string();
    ASSERT_EQ(bender::RunBenderCli({ "warp", meshPath, planPath.string(), out, "--quiet" }), 0);
    const vtkSmartPointer<vtkPolyData> cli = bender::ReadMesh(out);

    const vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(meshPath);
    const bender::WarpPlan plan = bender::ReadWarpPlan(planPath.string());

    // The session replaying the plan (the GUI's Load plan).
    bender::BenderSession replay;
    ASSERT_TRUE(replay.SetSurface(mesh, name));
    ASSERT_TRUE(replay.ReplayPlan(plan, name));
    EXPECT_TRUE(SameSurface(cli, replay.GetSurface())) << "CLI vs BenderSession::ReplayPlan";

    // The session applying the warps one at a time (one undo step each).
    bender::BenderSession stepwise;
    ASSERT_TRUE(stepwise.SetSurface(mesh, name));
    for (const bender::WarpSpec& warp : plan.warps)
    {
      ASSERT_TRUE(stepwise.ApplyWarp(warp));
    }
    EXPECT_TRUE(SameSurface(cli, stepwise.GetSurface())) << "CLI vs BenderSession::ApplyWarp";

    // And the workflow itself.
    EXPECT_TRUE(SameSurface(cli, bender::ApplyPlan(mesh, plan).output)) << "CLI vs ApplyPlan";
    ++compared;
  }
  EXPECT_EQ(compared, static_cast<int>(plans.size()));
  std::error_code ignored;
  fs::remove_all(scratch, ignored);
}

TEST(PlanEquivalence, TheWarpCommandRefusesABadPlanAndWritesNothing)
{
  // The comparison above must be able to fail: a plan that does not parse is an error (1)
  // and leaves no output behind.
  const fs::path scratch =
    fs::temp_directory_path() / ("bender-plan-refused-" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  const fs::path bad = scratch / "bad.bender.json";
  {
    FILE* f = std::fopen(bad.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("{\"format\": \"bender-warps\", \"version\": 1, \"warps\": [{}]}", f);
    std::fclose(f);
  }
  const fs::path out = scratch / "out.vtp";
  EXPECT_EQ(bender::RunBenderCli({ "warp",
              Source + "/tests/data/conformance/tube.off",
              bad.string(),
              out.string(),
              "--quiet" }),
    1);
  EXPECT_FALSE(fs::exists(out));
  std::error_code ignored;
  fs::remove_all(scratch, ignored);
}
