// What-if sweeps solved by OpenFOAM (issue 24, label cfd): the test tube (SweepTestTube.h) bent
// by 0, 45 and 90 degrees (bend90's fraction 0, 0.5, 1) on a coarse mesh (8.6 cells across, as
// the default's 8: at 6 the prism layers reach a third to half their thickness, and the 45-degree
// candidate's pressure drop comes out below the straight tube's). The sweep is
// interrupted once its first candidate is solved (as Ctrl+C does), run again (only what was
// missing runs), and once more (nothing runs); the pressure drop grows with the bend.

#include "CfdTestUtilities.h"

#include "BenderErrors.h"
#include "MeshIO.h"
#include "Sweep.h"
#include "SweepTestTube.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

using namespace bender;

namespace
{
const std::string Data = std::string(BENDER_SOURCE_DIR) + "/tests/data/sweep";

// The sweep of the test tube (SweepTestTube.h) written at `surface`.
SweepOptions TubeSweep(const std::string& surface, const std::string& folder)
{
  SweepOptions options;
  options.surface = surface;
  options.plans = { Data + "/bend90.bender.json" };
  options.vary = ParseSweepVary("fraction=0:1:3");
  options.output = folder;
  options.caseOptions.cellSize = 0.0007;
  options.caseOptions.iterations = 200;
  options.engine.jobs = 1;
  return options;
}

nlohmann::json CaseJson(const std::string& folder, const std::string& id)
{
  std::ifstream in(std::filesystem::path(folder) / id / "case" / "bender-case.json");
  return nlohmann::json::parse(in);
}

std::map<std::string, std::string> Roles(const nlohmann::json& caseJson)
{
  std::map<std::string, std::string> roles;
  for (const auto& patch : caseJson["patches"])
  {
    roles[patch["name"].get<std::string>()] = patch["type"].get<std::string>();
  }
  return roles;
}

std::vector<double> InletCentre(const nlohmann::json& caseJson)
{
  for (const auto& patch : caseJson["patches"])
  {
    if (patch["name"] == "inlet")
    {
      return patch["centre"].get<std::vector<double>>();
    }
  }
  return { 1e9, 1e9, 1e9 };
}

class SweepCfd : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    if (FindExecutable("simpleFoam").empty())
    {
      return;
    }
    Folder = std::make_unique<test::TemporaryFolder>("bender_sweep_cfd");
    const std::string dir = Folder->Path() + "/sweep";
    const std::string tube = Folder->Path() + "/tube.off";
    WriteMesh(bendertest::SweepTestTube(), tube);
    // Interrupted as soon as the first candidate is solved.
    std::atomic<bool> stop{ false };
    SweepOptions first = TubeSweep(tube, dir);
    first.progress.cancel = &stop;
    first.onLine = [&stop](const std::string& line)
    {
      if (line.find(": solved") != std::string::npos)
      {
        stop = true;
      }
    };
    try
    {
      RunSweep(first);
      Interrupted = false;
    }
    catch (const Cancelled&)
    {
      Interrupted = true;
    }
    Partial = std::make_unique<std::string>(test::ReadText(dir + "/summary.json"));
    Resumed = RunSweep(TubeSweep(tube, dir));
    Again = RunSweep(TubeSweep(tube, dir));
  }
  static void TearDownTestSuite() { Folder.reset(); }

  void SetUp() override
  {
    BENDER_REQUIRE_PROGRAM("simpleFoam");
    ASSERT_TRUE(Folder);
  }

  static std::unique_ptr<test::TemporaryFolder> Folder;
  static bool Interrupted;
  static std::unique_ptr<std::string> Partial;
  static SweepResult Resumed;
  static SweepResult Again;
};
std::unique_ptr<test::TemporaryFolder> SweepCfd::Folder;
bool SweepCfd::Interrupted = false;
std::unique_ptr<std::string> SweepCfd::Partial;
SweepResult SweepCfd::Resumed;
SweepResult SweepCfd::Again;
} // namespace

TEST_F(SweepCfd, AnInterruptedSweepFinishesOnlyWhatWasMissing)
{
  EXPECT_TRUE(Interrupted);
  // The interrupted sweep's summary says which rows are missing and why.
  const nlohmann::json partial = nlohmann::json::parse(*Partial);
  ASSERT_EQ(partial["rows"].size(), 3u);
  EXPECT_EQ(partial["rows"][0]["state"], "solved");
  ASSERT_EQ(partial["missing"].size(), 2u);
  for (const auto& missing : partial["missing"])
  {
    EXPECT_NE(missing["reason"].get<std::string>().find("cancelled"), std::string::npos);
  }
  // Run again: the solved one is kept, only the two missing ones run.
  EXPECT_EQ(Resumed.kept, 1u);
  EXPECT_EQ(Resumed.solved, 2u);
  for (const SweepRow& row : Resumed.rows)
  {
    EXPECT_EQ(row.state, "solved") << row.id << ": " << row.reason;
  }
  // Once more: nothing runs, the same rows.
  EXPECT_EQ(Again.kept, 3u);
  EXPECT_EQ(Again.solved, 0u);
  EXPECT_EQ(Again.prepared, 0u);
  EXPECT_EQ(SweepSummaryCsv(Again.rows), SweepSummaryCsv(Resumed.rows));
}

TEST_F(SweepCfd, ThePressureDropGrowsWithTheBend)
{
  const std::vector<SweepRow>& rows = Resumed.rows;
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_TRUE(rows[0].original);
  std::string drops; // each row's pressure drop and run, in a failure's message
  for (const SweepRow& row : rows)
  {
    drops += " " + std::to_string(row.pressureDrop) + " Pa (" + std::to_string(row.iterations) +
      (row.converged ? " iterations, converged)" : " iterations)");
  }
  for (std::size_t i = 1; i < rows.size(); ++i)
  {
    ASSERT_EQ(rows[i].state, "solved") << rows[i].id;
    EXPECT_GT(rows[i].pressureDrop, rows[i - 1].pressureDrop)
      << "fraction " << rows[i].value << " against " << rows[i - 1].value << ":" << drops;
    EXPECT_GT(rows[i].measures.bendAngle, rows[i - 1].measures.bendAngle);
  }
  // One outlet: it carries the whole flow.
  for (const SweepRow& row : rows)
  {
    ASSERT_EQ(row.outlets.size(), 1u);
    EXPECT_NEAR(row.outlets[0].splitPercent, 100.0, 1.0);
    EXPECT_GT(row.meshCells, 0);
  }
}

TEST_F(SweepCfd, EveryCandidateHasTheOriginalsSettings)
{
  const std::string dir = Folder->Path() + "/sweep";
  const nlohmann::json original = CaseJson(dir, "c00");
  for (const char* id : { "c01", "c02" })
  {
    const nlohmann::json candidate = CaseJson(dir, id);
    for (const char* key : { "cellSize", "inletFlowRate", "viscosity", "density", "iterations" })
    {
      ASSERT_TRUE(original.contains(key)) << key;
      EXPECT_EQ(candidate[key], original[key]) << id << " " << key;
    }
    // The same ends by name, each with its role (their ids follow their areas).
    EXPECT_EQ(Roles(candidate), Roles(original)) << id;
    // The bend moves the open end at x = 40 mm, not the inlet at x = -30 mm: the inlet is the
    // same end in every candidate.
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(InletCentre(candidate)[k], InletCentre(original)[k], 1e-6) << id;
    }
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/summary.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/sweep.json"));
}
