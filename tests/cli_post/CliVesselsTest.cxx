// bender-cli centerline and measure, in-process through the command library: the gmsh aneurysm's
// three open ends, the written centerlines with the arrays other vessel tools read, the JSON
// report, the demo plan's bend seen by `measure --plan`, and one-line errors for bad input.

#include "CliCommands.h"
#include "InProcessCli.h"
#include "MeshIO.h"
#include "VesselArrayNames.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

using bendertest::CliRun;

CliRun RunCli(const std::vector<std::string>& args)
{
  return bendertest::RunInProcess(args);
}

std::string Aneurysm()
{
  return std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
}

fs::path ScratchFolder(const std::string& name)
{
  const fs::path folder = fs::temp_directory_path() / ("bender-cli-vessels-" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

double Angle(const nlohmann::json& a, const nlohmann::json& b)
{
  double dot = 0.0, na = 0.0, nb = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    dot += a[k].get<double>() * b[k].get<double>();
    na += a[k].get<double>() * a[k].get<double>();
    nb += b[k].get<double>() * b[k].get<double>();
  }
  return std::acos(std::max(-1.0, std::min(1.0, dot / std::sqrt(na * nb)))) * 180.0 / M_PI;
}
} // namespace

TEST(CliVessels, CenterlinesOfTheAneurysmWithTheirArraysAndJson)
{
  ASSERT_TRUE(fs::exists(Aneurysm())) << Aneurysm() << " is missing: run scripts/fetch-data";
  const fs::path folder = ScratchFolder("centerline");
  const std::string out = (folder / "centerlines.vtp").string();
  const CliRun r = RunCli({ "centerline", Aneurysm(), "-o", out, "--json" });
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  ASSERT_EQ(report.at("endpoints").size(), 3u);
  int inlets = 0;
  for (const auto& endpoint : report.at("endpoints"))
  {
    inlets += endpoint.at("inlet").get<bool>() ? 1 : 0;
    EXPECT_TRUE(endpoint.at("reached").get<bool>());
    EXPECT_GT(endpoint.at("radius").get<double>(), 1.0);
  }
  EXPECT_EQ(inlets, 1);
  EXPECT_EQ(report.at("bifurcations").size(), 1u);
  EXPECT_EQ(report.at("branches").size(), 3u);

  vtkSmartPointer<vtkPolyData> lines = bender::ReadMesh(out);
  ASSERT_GT(lines->GetNumberOfLines(), 0);
  vtkDataArray* radius =
    lines->GetPointData()->GetArray(bender::VesselArrays::MaximumInscribedSphereRadius);
  ASSERT_NE(radius, nullptr);
  ASSERT_NE(lines->GetPointData()->GetArray(bender::VesselArrays::Abscissa), nullptr);
  ASSERT_NE(lines->GetCellData()->GetArray(bender::VesselArrays::BranchId), nullptr);
  double range[2];
  radius->GetRange(range);
  // The gmsh vessels are 2 to 6 mm in radius: an inscribed sphere outside that is a wrong line.
  EXPECT_GT(range[0], 1.0);
  EXPECT_LT(range[1], 8.0);
  fs::remove_all(folder);
}

TEST(CliVessels, MeasureWithThePlanSeesItsBend)
{
  const std::string plan = std::string(BENDER_SOURCE_DIR) + "/data/demo/demo.bender.json";
  const CliRun r = RunCli({ "measure", Aneurysm(), "--plan", plan, "--json" });
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  const nlohmann::json planJson = nlohmann::json::parse(std::ifstream(plan));
  const auto& warp = planJson.at("warps").at(0);
  // The plan turns its end tangent by this angle; one matched branch turns by the same.
  const double planTurn =
    Angle(warp.at("initial").at("end").at("tangent"), warp.at("final").at("end").at("tangent"));
  // The branch the ribbon holds turns at one end by the plan's angle; the others stay.
  double largestTurn = 0.0;
  int turned = 0;
  for (const auto& branch : report.at("comparison"))
  {
    const auto& change = branch.at("change");
    const double turn =
      std::max(change.at("startTurn").get<double>(), change.at("endTurn").get<double>());
    largestTurn = std::max(largestTurn, turn);
    turned += turn > 2.0 ? 1 : 0;
  }
  EXPECT_GT(planTurn, 10.0);
  // The demo plan's ribbon lies on the trunk's centerline and ends at its open end: the vessel's
  // end turns with the ribbon's end frame, by the plan's angle (issue 10: within 2 degrees).
  EXPECT_NEAR(largestTurn, planTurn, 2.0) << "the plan turns its end by " << planTurn << " deg";
  EXPECT_EQ(turned, 1);
}

TEST(CliVessels, BadInputGetsOneLineAndNoFile)
{
  const fs::path folder = ScratchFolder("bad");
  CliRun r =
    RunCli({ "centerline", (folder / "missing.stl").string(), "-o", (folder / "c.vtp").string() });
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("missing.stl"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = RunCli({ "centerline", Aneurysm(), "-o", (folder / "c.stl").string() });
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("c.stl"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(folder / "c.stl"));
  r = RunCli({ "measure", Aneurysm(), "--plan", (folder / "nope.bender.json").string() });
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("nope.bender.json"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(folder));
  fs::remove_all(folder);
}
