// bender-cli compare end to end on two real runs (issue 23), label `cfd`: two generated tubes
// of the same length at the same inlet flow, B narrower than A, meshed, solved and mapped by
// OpenFOAM (RunOpenFoamCase), then compared in-process. The narrower tube must show a higher
// pressure drop and wall shear stress, highlighted; the same flow; its smaller radius in the
// bend measures; a PDF whose every page pdftoppm renders, and the PNGs.

#include "CfdCase.h"
#include "CfdFlowResults.h"
#include "CfdTestUtilities.h"
#include "InProcessCli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;

namespace
{
constexpr double kLengthMm = 40.0;
constexpr double kRadiusA = 2.0;
constexpr double kRadiusB = 1.7;
// 0.05 m/s mean in A's section (Re about 60), the same flow in B.
const double kFlowRate = 0.05 * M_PI * std::pow(kRadiusA * 1e-3, 2);

const nlohmann::json& Row(const nlohmann::json& report, const std::string& key)
{
  for (const auto& row : report.at("rows"))
  {
    if (row.at("key") == key)
    {
      return row;
    }
  }
  ADD_FAILURE() << "no row " << key;
  static const nlohmann::json none;
  return none;
}
} // namespace

TEST(CfdCompareRun, TheNarrowerTubeHasTheHigherDropAndStressInTheReport)
{
  BENDER_REQUIRE_PROGRAM("simpleFoam");
  BENDER_REQUIRE_PROGRAM("snappyHexMesh");
  ASSERT_FALSE(bender::FindExecutable("pdftoppm").empty())
    << "pdftoppm is not installed (scripts/setup installs poppler-utils)";
  bender::test::TemporaryFolder folder("compare-run");
  const std::string a = folder.Path() + "/wide", b = folder.Path() + "/narrow";
  const auto start = std::chrono::steady_clock::now();
  for (const auto& [dir, radius] : { std::pair{ a, kRadiusA }, std::pair{ b, kRadiusB } })
  {
    bender::CfdCaseOptions options;
    options.caseDirectory = dir;
    options.flowRate = kFlowRate;
    options.iterations = 400;
    bender::WriteOpenFoamCase(bender::test::CappedTube(kLengthMm, radius, 81, 32), options);
    ASSERT_NO_THROW(bender::RunOpenFoamCase(dir)) << bender::test::ReadText(dir + "/log.Allrun");
  }
  std::printf("[ timing ] two tube cases meshed, solved and mapped in %.1f s\n",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

  const std::string pdf = folder.Path() + "/report.pdf";
  const bendertest::CliRun r = bendertest::RunInProcess(
    { "compare", a, b, "-o", pdf, "--json", "--png", folder.Path() + "/pictures" });
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);

  // The same flow in both (prescribed by flow rate), not highlighted.
  const nlohmann::json& inflow = Row(report, "inlet.flowRate");
  EXPECT_LT(std::abs(inflow.at("relativeDifference").get<double>()), 0.05) << inflow.dump();
  EXPECT_FALSE(inflow.at("highlighted").get<bool>());
  // Every outlet's pressure drop and the mean WSS are higher in the narrower tube, and said so.
  int outlets = 0;
  for (const auto& row : report.at("rows"))
  {
    const std::string key = row.at("key");
    if (key.rfind("pressureDrop.", 0) == 0 || key == "wss.mean" || key == "wss.p99")
    {
      ++outlets;
      ASSERT_FALSE(row.at("a").is_null() || row.at("b").is_null()) << row.dump();
      EXPECT_GT(row.at("relativeDifference").get<double>(), 0.2) << row.dump();
      EXPECT_TRUE(row.at("highlighted").get<bool>()) << row.dump();
    }
  }
  EXPECT_GE(outlets, 3);
  // Both runs converged (or the table says they did not).
  const nlohmann::json& run = Row(report, "run.iterations");
  EXPECT_EQ(run.at("highlighted").get<bool>(),
    run.at("stateA").get<std::string>().rfind("converged", 0) != 0 ||
      run.at("stateB").get<std::string>().rfind("converged", 0) != 0);
  // The straight tubes' one branch: hardly bent, B's minimal radius smaller by about 1.7 / 2.
  ASSERT_EQ(report.at("bends").size(), 1u) << report.at("unavailable").dump();
  const nlohmann::json& tube = report.at("bends")[0];
  EXPECT_LT(tube.at("bendAngleA_deg").get<double>(), 10.0);
  EXPECT_NEAR(tube.at("minRadiusB_mm").get<double>() / tube.at("minRadiusA_mm").get<double>(),
    kRadiusB / kRadiusA,
    0.1);

  // The PDF: every page renders; the PNGs are there.
  const int pages = report.at("report").at("pages").get<int>();
  ASSERT_GE(pages, 3);
  int status = 0;
  const std::string log =
    bender::test::RunIn(folder.Path(), "pdftoppm -r 30 -png report.pdf page && ls page*", status);
  ASSERT_EQ(status, 0) << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), pages) << log;
  for (const auto& png : report.at("report").at("pngs"))
  {
    EXPECT_GT(fs::file_size(png.get<std::string>()), 10000u) << png;
  }
  EXPECT_EQ(report.at("report").at("pngs").size(), 4u);
}
