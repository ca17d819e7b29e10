// The case's mesh and inlet with OpenFOAM on a small generated tube (label `cfd`): prism layers
// on the wall, their coverage read from snappyHexMesh's report, checkMesh's "Mesh OK", and the
// developed inlet profile (timeVaryingMappedFixedValue) carrying the prescribed flow.

#include "CfdCase.h"
#include "CfdMeshing.h"
#include "CfdTestUtilities.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace
{

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

TEST(CfdLayers, ATubeMeshedWithPrismLayersPassesCheckMeshAndCarriesThePrescribedFlow)
{
  for (const char* program :
    { "blockMesh", "surfaceFeatureExtract", "snappyHexMesh", "checkMesh", "simpleFoam" })
  {
    BENDER_REQUIRE_PROGRAM(program);
  }
  bender::test::TemporaryFolder folder("cfd-layers");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.sourceName = "tube";
  options.iterations = 40;
  options.flowRate = 2e-6; // 120 ml/min in a 4 mm tube: Re ~ 180
  const bender::CfdCaseResult written =
    bender::WriteOpenFoamCase(bender::test::CappedTube(24.0, 2.0, 49, 32), options);
  ASSERT_EQ(written.layers, 3);

  // The whole Allrun: the mesh (with its report), then simpleFoam.
  const auto start = std::chrono::steady_clock::now();
  bender::CfdRunResult run;
  ASSERT_NO_THROW(run = bender::RunOpenFoamCase(options.caseDirectory))
    << bender::test::ReadText(options.caseDirectory + "/log.Allrun");
  std::printf(
    "[ timing ] tube mesh with layers and %d iterations %.1f s\n", run.iterations, Seconds(start));
  const bender::CfdMeshReport& report = run.mesh;
  std::printf("%s", bender::FormatCfdMeshReport(report).c_str());
  EXPECT_TRUE(report.meshOk) << report.failedChecks;
  EXPECT_GT(report.cells, 1000);
  EXPECT_EQ(report.layersRequested, 3);
  ASSERT_EQ(report.layers.size(), 1u);
  EXPECT_EQ(report.layers[0].name, "wall");
  // A straight tube: layers nearly everywhere (the rims of the ends may lose a few).
  EXPECT_GT(report.layers[0].coveragePercent, 90.0);
  EXPECT_LE(report.layers[0].coveragePercent, 100.0);
  ASSERT_GT(report.facesToExtrude, 0);
  EXPECT_GT(100.0 * report.facesExtruded / report.facesToExtrude, 90.0);
  EXPECT_EQ(report.facesToExtrude, report.layers[0].faces);

  // The Poiseuille profile, mapped onto the snapped inlet and held to the mean that carries the
  // flow there (the Allrun's mesh step), carries the prescribed flow exactly: to 1e-4.
  EXPECT_NEAR(run.inletFlowRate, options.flowRate, 1e-4 * options.flowRate);
  EXPECT_LT(run.massImbalance, 0.01);
}

} // namespace
