// The stages of a run timed (issue 23, "Speed"; CfdStageTimes.h): snappyHexMesh's own phase
// times read from its log, the Allrun's steps grouped into mesh, layers and solve, and the
// clock that times the steps from the Allrun's lines. No OpenFOAM needed.

#include "CfdStageTimes.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{

double Sum(const std::vector<std::pair<std::string, double>>& steps)
{
  double sum = 0.0;
  for (const auto& step : steps)
  {
    sum += step.second;
  }
  return sum;
}

TEST(CfdStageTimes, SnappyPhasesAreReadFromItsLog)
{
  // The last of each line counts (snappyHexMesh writes some twice); other lines are ignored.
  const std::string log = "Mesh refined in = 1.5 s.\nWrote mesh in = 0.2 s.\n"
                          "Mesh refined in = 6.45 s.\nMesh snapped in = 4.72 s.\n"
                          "Layers added in = 3.99 s.\nFinished meshing in = 16.92 s.\n";
  const bender::SnappyPhaseTimes t = bender::ParseSnappyPhaseTimes(log);
  EXPECT_DOUBLE_EQ(t.refine, 6.45);
  EXPECT_DOUBLE_EQ(t.snap, 4.72);
  EXPECT_DOUBLE_EQ(t.layers, 3.99);
  const bender::SnappyPhaseTimes none = bender::ParseSnappyPhaseTimes("no layers here\n");
  EXPECT_EQ(none.refine + none.snap + none.layers, 0.0);
}

TEST(CfdStageTimes, StepsGroupIntoStagesThatAddUpToThem)
{
  const std::vector<std::pair<std::string, double>> steps = { { "blockMesh", 1.0 },
    { "surfaceFeatureExtract", 0.5 },
    { "snappyHexMesh", 10.0 },
    { "checkMesh", 1.5 },
    { "decomposePar", 2.0 },
    { "mpirun", 20.0 },
    { "reconstructPar", 3.0 } };
  const std::string log =
    "Mesh refined in = 2 s.\nMesh snapped in = 2 s.\nLayers added in = 4 s.\n";
  const bender::CfdStageTimes t = bender::GroupCfdStages(steps, log);
  // snappyHexMesh's wall time split by its own clock: half of it added the layers.
  EXPECT_DOUBLE_EQ(t.layers, 5.0);
  EXPECT_DOUBLE_EQ(t.mesh, 1.0 + 0.5 + 5.0 + 1.5);
  EXPECT_DOUBLE_EQ(t.solve, 25.0);
  EXPECT_EQ(t.map, 0.0);
  EXPECT_DOUBLE_EQ(t.Total(), Sum(steps));
  EXPECT_EQ(t.steps, steps);
  // Without its log (a solve-only run, or layers off) snappyHexMesh is all mesh.
  const bender::CfdStageTimes plain = bender::GroupCfdStages(steps, "");
  EXPECT_EQ(plain.layers, 0.0);
  EXPECT_DOUBLE_EQ(plain.Total(), Sum(steps));
  EXPECT_NE(bender::FormatCfdStageTimes(t).find("layers 5 s"), std::string::npos)
    << bender::FormatCfdStageTimes(t);
}

TEST(CfdStageTimes, TheClockTimesEachStepFromTheAllrunsLines)
{
  const auto start = std::chrono::steady_clock::now();
  bender::CfdStepClock clock;
  clock.Line("something before the first step");
  clock.Line("bender Allrun: blockMesh");
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  clock.Line("bender Allrun: snappyHexMesh -overwrite");
  clock.Line("bender Allrun: snappyHexMesh failed, see log.snappyHexMesh:");
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  clock.Finish();
  clock.Finish(); // nothing more to close
  const double elapsed =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& steps = clock.Steps();
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].first, "blockMesh");
  EXPECT_EQ(steps[1].first, "snappyHexMesh");
  EXPECT_GE(steps[0].second, 0.015);
  EXPECT_GE(steps[1].second, 0.015);
  EXPECT_LE(Sum(steps), elapsed);
}

} // namespace
