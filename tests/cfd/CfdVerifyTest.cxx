// bender-cli cfd-verify's cases with OpenFOAM (label cfd): the generated straight tube against
// Shah's developing-flow pressure drop and Poiseuille's wall shear stress, through the command,
// and the curved tube against White's friction ratio, through the workflow. Each figure must
// lie within its stated tolerance; the measured deviations are printed. And cfd-case
// --convergence's three meshes on a short, coarse tube.

#include "CfdTestUtilities.h"
#include "CfdVerification.h"
#include "CfdVerificationTubes.h"
#include "MeshIO.h"

#include "../cli_post/InProcessCli.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{

TEST(CfdVerify, TheStraightTubeMatchesShahAndPoiseuille)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  const auto start = std::chrono::steady_clock::now();
  const auto run = bendertest::RunInProcess({ "cfd-verify", "--only", "straight", "--json" });
  std::printf("straight tube: %.0f s\n",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  ASSERT_FALSE(run.out.empty()) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  ASSERT_EQ(j.at("cases").size(), 1u);
  const nlohmann::json& figures = j.at("cases").at(0).at("figures");
  ASSERT_EQ(figures.size(), 2u);
  for (const auto& f : figures)
  {
    std::printf("  %s: %+.2f %% (tolerance %.0f %%)\n",
      f.at("name").get<std::string>().c_str(),
      f.at("deviationPercent").get<double>(),
      f.at("tolerancePercent").get<double>());
    EXPECT_TRUE(f.at("passed").get<bool>()) << f.dump();
  }
  EXPECT_TRUE(j.at("cases").at(0).at("converged").get<bool>());
  EXPECT_EQ(run.status, 0) << run.err;
}

TEST(CfdVerify, TheCurvedTubeMatchesWhitesFrictionRatio)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  bender::test::TemporaryFolder folder("cfd-verify");
  bender::CfdVerificationOptions options;
  options.folder = folder.Path() + "/cases";
  options.straight = false;
  const auto start = std::chrono::steady_clock::now();
  const bender::CfdVerificationResult result = bender::RunCfdVerification(options);
  std::printf("curved tube: %.0f s\n%s",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
    bender::FormatCfdVerification(result).c_str());
  ASSERT_EQ(result.cases.size(), 1u);
  EXPECT_TRUE(result.cases[0].converged);
  ASSERT_EQ(result.cases[0].figures.size(), 1u);
  EXPECT_TRUE(result.Passed());
  // The cases stay in the folder given: the surface and the mapped results.
  EXPECT_FALSE(bender::test::ReadText(options.folder + "/curved-tube/results/flow.json").empty());
}

TEST(CfdVerify, ConvergenceRunsThreeMeshesAndExtrapolatesEachQuantity)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  bender::test::TemporaryFolder folder("cfd-convergence");
  const std::string surface = folder.Path() + "/tube.vtp";
  bender::WriteMesh(
    bender::SweepClosedTube(bender::StraightCentreline(40.0, 1.0), 2.0, 48), surface);
  const std::string study = folder.Path() + "/study";
  // About 6 wall cells across the 4 mm tube.
  const double h = 6.5e-4;
  const auto start = std::chrono::steady_clock::now();
  const auto run = bendertest::RunInProcess({ "cfd-case",
    surface,
    "-o",
    study,
    "--convergence",
    "--cell-size",
    "6.5e-4",
    "--flow-rate",
    "1.1e-6",
    "--json" });
  std::printf("three meshes: %.0f s\n",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j.at("format"), "bender-mesh-convergence");
  const nlohmann::json& meshes = j.at("meshes");
  ASSERT_EQ(meshes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i)
  {
    // H, H / 1.3, H / 1.69: finer meshes, more cells, each with its mapped results.
    EXPECT_NEAR(meshes[i].at("cellSize_m").get<double>(), h / std::pow(1.3, i), 1e-12);
    if (i > 0)
    {
      EXPECT_GT(
        meshes[i].at("meshCells").get<long long>(), meshes[i - 1].at("meshCells").get<long long>());
    }
    EXPECT_FALSE(
      bender::test::ReadText(study + "/mesh-" + std::to_string(i + 1) + "/results/flow.json")
        .empty());
  }
  // One outlet: its pressure drop and the mean WSS, no split (always 100 %).
  const nlohmann::json& quantities = j.at("quantities");
  ASSERT_EQ(quantities.size(), 2u);
  EXPECT_EQ(quantities[0].at("name"), "pressure drop to outlet_1");
  EXPECT_EQ(quantities[1].at("name"), "mean wall shear stress");
  for (const auto& q : quantities)
  {
    std::printf("  %s\n", q.dump().c_str());
    for (const auto& v : q.at("values"))
    {
      EXPECT_GT(v.get<double>(), 0.0);
    }
    // A monotone study has its extrapolation, order and GCI; any other says why it has none.
    const bool monotone = q.at("convergence") == "monotone";
    EXPECT_EQ(q.at("extrapolated").is_number(), monotone);
    EXPECT_EQ(q.at("order").is_number(), monotone);
    EXPECT_FALSE(q.at("note").get<std::string>().empty());
    // mesh-1 (the default mesh) against the best estimate: the extrapolated value, or mesh-3's
    // where nothing is extrapolated; none when the values diverge.
    const std::vector<double> values = q.at("values").get<std::vector<double>>();
    if (q.at("convergence") == "diverging")
    {
      EXPECT_TRUE(q.at("mesh1DeviationPercent").is_null());
      continue;
    }
    const double reference = monotone ? q.at("extrapolated").get<double>() : values[2];
    EXPECT_EQ(q.at("mesh1DeviationFrom"), monotone ? "extrapolated" : "mesh-3");
    EXPECT_NEAR(q.at("mesh1DeviationPercent").get<double>(),
      100.0 * (values[0] - reference) / std::fabs(reference),
      1e-9);
  }
}

} // namespace
