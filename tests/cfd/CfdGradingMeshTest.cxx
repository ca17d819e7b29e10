// The graded mesh with OpenFOAM (label cfd): the tube of CfdMissingEndTest, whose 1.2 mm side
// branch a single cell size set by the trunk loses, meshed with the default grading keeps every
// end, and the faces snappyHexMesh put on each end give it at least the cells across that the
// case states (the end's diameter over the side of its mean face).

#include "CfdCase.h"
#include "CfdTestUtilities.h"
#include "PrepareForCfd.h"
#include "ThinBranchTube.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

TEST(CfdGradingMesh, EveryEndOfATubeWithAThinBranchGetsTheCellsAcrossStated)
{
  BENDER_REQUIRE_PROGRAM("blockMesh");
  BENDER_REQUIRE_PROGRAM("snappyHexMesh");
  BENDER_REQUIRE_PROGRAM("checkMesh");
  const bender::PrepareForCfdResult prepared = bender::test::PreparedThinBranchTube();
  ASSERT_EQ(prepared.ends.size(), 3u);

  bender::test::TemporaryFolder folder("cfd-grading-mesh");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.cellsAcross = 4.0; // coarse: the trunk's cells 1.5 mm, the branch's H / 8
  options.layers = 0;
  options.iterations = 5;
  const bender::CfdCaseResult written =
    bender::WriteOpenFoamCase({ prepared.surface, prepared.patches }, options);
  std::printf("%s", bender::FormatCfdCase(written).c_str());
  ASSERT_EQ(written.grading.ends.size(), 3u);
  ASSERT_FALSE(written.grading.regions.empty()) << "the branch is narrower than the trunk";

  bender::CfdRunOptions run;
  run.steps = bender::CfdRunOptions::Steps::Mesh;
  bender::CfdRunResult meshed;
  ASSERT_NO_THROW(meshed = bender::RunOpenFoamCase(options.caseDirectory, run))
    << bender::test::ReadText(options.caseDirectory + "/log.Allrun");
  EXPECT_TRUE(meshed.mesh.meshOk) << meshed.mesh.failedChecks;
  std::printf("mesh: %lld cells\n", meshed.mesh.cells);

  const auto faces = bender::ReadMeshPatches(options.caseDirectory);
  for (const bender::CfdEndCells& end : written.grading.ends)
  {
    long long count = 0;
    for (const auto& [name, n] : faces)
    {
      count = name == end.name ? n : count;
    }
    double diameter = 0.0, area = 0.0;
    for (const bender::CfdPatch& p : written.patches)
    {
      diameter = p.name == end.name ? p.diameter : diameter;
      area = p.name == end.name ? p.area : area;
    }
    ASSERT_GT(count, 0) << end.name << " lost";
    const double measured = diameter / std::sqrt(area / static_cast<double>(count));
    std::printf("%s: %lld faces, %.2f cells across (%.2f stated, level %d)\n",
      end.name.c_str(),
      count,
      measured,
      end.cellsAcross,
      end.level);
    EXPECT_GE(end.cellsAcross, 0.99 * 4.0) << end.name; // within 1 %
    EXPECT_GE(measured, 0.9 * end.cellsAcross) << end.name;
  }
}
