// CfdFlowResults without OpenFOAM: the wall shear stress statistics on synthetic surfaces with
// known answers, the weighted percentile, flow.json's round trip and its errors.

#include "CfdFlowResults.h"
#include "BenderErrors.h"
#include "CfdTestUtilities.h"
#include "PatchLabels.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace
{

/// Squares in the plane z = 0, each its own points (two triangles), with a uniform WSS
/// magnitude on its corners and a patch id: {x0, side, wss, id}.
struct Square
{
  double x0;
  double side;
  double wss;
  int id;
};

vtkSmartPointer<vtkPolyData> Squares(const std::vector<Square>& squares)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkDoubleArray> wss;
  wss->SetName(bender::kWallShearStressMagnitudeArrayName);
  std::vector<int> ids;
  for (const auto& s : squares)
  {
    const vtkIdType first = points->GetNumberOfPoints();
    points->InsertNextPoint(s.x0, 0, 0);
    points->InsertNextPoint(s.x0 + s.side, 0, 0);
    points->InsertNextPoint(s.x0 + s.side, s.side, 0);
    points->InsertNextPoint(s.x0, s.side, 0);
    for (int k = 0; k < 4; ++k)
    {
      wss->InsertNextValue(s.wss);
    }
    const vtkIdType t1[3] = { first, first + 1, first + 2 };
    const vtkIdType t2[3] = { first, first + 2, first + 3 };
    triangles->InsertNextCell(3, t1);
    triangles->InsertNextCell(3, t2);
    ids.push_back(s.id);
    ids.push_back(s.id);
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetPolys(triangles);
  surface->GetPointData()->AddArray(wss);
  bender::WritePatchLabels(surface,
    ids,
    { { 1, "wall", bender::PatchType::Wall },
      { 2, "inlet", bender::PatchType::Inlet },
      { 3, "outlet_1", bender::PatchType::Outlet } });
  return surface;
}

TEST(CfdFlowResults, UniformWallShearStress)
{
  const auto surface = Squares({ { 0.0, 10.0, 2.0, 1 } });
  const bender::CfdWallShearStats s = bender::ComputeWallShearStats(surface);
  EXPECT_NEAR(s.wallAreaMm2, 100.0, 1e-9);
  EXPECT_NEAR(s.meanPa, 2.0, 1e-12);
  EXPECT_NEAR(s.maxPa, 2.0, 1e-12);
  EXPECT_NEAR(s.percentile99Pa, 2.0, 1e-12);
  EXPECT_EQ(s.lowAreaMm2, 0.0);
  EXPECT_EQ(s.highAreaMm2, 0.0);
}

TEST(CfdFlowResults, AreaWeightedStatisticsAndThresholdsOverTheWallOnly)
{
  // 60 mm^2 at 0.1 Pa (low), 36 mm^2 at 5 Pa, 4 mm^2 at 20 Pa (high); the ends carry 100 Pa
  // and 0.01 Pa, which the wall statistics must ignore.
  const auto surface = Squares({ { 0.0, std::sqrt(60.0), 0.1, 1 },
    { 20.0, 6.0, 5.0, 1 },
    { 40.0, 2.0, 20.0, 1 },
    { 60.0, 3.0, 100.0, 2 },
    { 80.0, 3.0, 0.01, 3 } });
  const bender::CfdWallShearStats s = bender::ComputeWallShearStats(surface);
  EXPECT_NEAR(s.wallAreaMm2, 100.0, 1e-9);
  EXPECT_NEAR(s.meanPa, (60.0 * 0.1 + 36.0 * 5.0 + 4.0 * 20.0) / 100.0, 1e-12);
  EXPECT_NEAR(s.maxPa, 20.0, 1e-12);
  EXPECT_NEAR(s.lowAreaMm2, 60.0, 1e-9);
  EXPECT_NEAR(s.highAreaMm2, 4.0, 1e-9);
  // 96 % of the wall is at or below 5 Pa: the 99th percentile is in the 20 Pa part.
  EXPECT_NEAR(s.percentile99Pa, 20.0, 1e-12);
  // Shrink the 20 Pa part below 1 % of the wall: the 99th percentile drops to 5 Pa.
  const auto small =
    Squares({ { 0.0, std::sqrt(60.0), 0.1, 1 }, { 20.0, 6.0, 5.0, 1 }, { 40.0, 0.5, 20.0, 1 } });
  EXPECT_NEAR(bender::ComputeWallShearStats(small).percentile99Pa, 5.0, 1e-12);
}

TEST(CfdFlowResults, ALinearFieldHasItsExactMean)
{
  // WSS = x on a strip 0 <= x <= 10 made of unit squares sharing their corners: a linear
  // field's triangle mean (of the corners) is exact, so the area-weighted mean is 5; of the
  // first column's two triangles (corner means 2/3 and 1/3) one is below 0.4 Pa.
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkDoubleArray> wss;
  wss->SetName(bender::kWallShearStressMagnitudeArrayName);
  for (int i = 0; i <= 10; ++i)
  {
    for (int j = 0; j <= 1; ++j)
    {
      points->InsertNextPoint(i, j, 0);
      wss->InsertNextValue(i);
    }
  }
  for (vtkIdType i = 0; i < 10; ++i)
  {
    const vtkIdType a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    const vtkIdType t1[3] = { a, c, d };
    const vtkIdType t2[3] = { a, d, b };
    triangles->InsertNextCell(3, t1);
    triangles->InsertNextCell(3, t2);
  }
  vtkNew<vtkPolyData> strip;
  strip->SetPoints(points);
  strip->SetPolys(triangles);
  strip->GetPointData()->AddArray(wss);
  const bender::CfdWallShearStats s = bender::ComputeWallShearStats(strip);
  EXPECT_NEAR(s.wallAreaMm2, 10.0, 1e-12);
  EXPECT_NEAR(s.meanPa, 5.0, 1e-12);
  EXPECT_NEAR(s.maxPa, 10.0, 1e-12);
  EXPECT_NEAR(s.lowAreaMm2, 0.5, 1e-12);
  EXPECT_EQ(s.highAreaMm2, 0.0);
  EXPECT_THROW(bender::ComputeWallShearStats(nullptr), bender::InputError);
  strip->GetPointData()->RemoveArray(bender::kWallShearStressMagnitudeArrayName);
  EXPECT_THROW(bender::ComputeWallShearStats(strip), bender::InputError);
}

TEST(CfdFlowResults, WeightedPercentile)
{
  std::vector<std::pair<double, double>> equal;
  for (int v = 100; v >= 1; --v)
  {
    equal.emplace_back(v, 1.0);
  }
  EXPECT_EQ(bender::WeightedPercentile(equal, 99.0), 99.0);
  EXPECT_EQ(bender::WeightedPercentile(equal, 50.0), 50.0);
  EXPECT_EQ(bender::WeightedPercentile(equal, 100.0), 100.0);
  // The weights, not the count: 1 with 99 % of the weight.
  EXPECT_EQ(bender::WeightedPercentile({ { 1.0, 99.0 }, { 7.0, 1.0 } }, 99.0), 1.0);
  EXPECT_EQ(bender::WeightedPercentile({ { 1.0, 98.0 }, { 7.0, 2.0 } }, 99.0), 7.0);
  EXPECT_EQ(bender::WeightedPercentile({}, 99.0), 0.0);
}

bender::CfdFlowResults Example()
{
  bender::CfdFlowResults r;
  r.time = 412;
  r.run.iterations = 412;
  r.run.iterationLimit = 1000;
  r.run.converged = true;
  r.run.residuals = { { "Ux", 9.5e-6 }, { "p", 8.25e-5 } };
  r.run.status = "converged in 412 iterations";
  r.ends = { { "inlet", bender::PatchType::Inlet, 660.5, 100.0, 52.25, 0.0 },
    { "outlet_1", bender::PatchType::Outlet, 400.125, 60.58, 0.5, 51.75 },
    { "outlet_2", bender::PatchType::Outlet, 260.375, 39.42, -0.75, 53.0 } };
  r.inletFlowRateMlPerMin = 660.5;
  r.massImbalancePercent = 1.5e-4;
  r.wallShearStress = { 1.75, 12.5, 8.25, 120.5, 3.25, 2150.75 };
  r.meshCells = 123456;
  r.settings = { 1060.0, 3.5e-6, 660.0, 0.2, 480.5, 0.35, 2 };
  return r;
}

TEST(CfdFlowResults, FlowJsonRoundTripsWithUnits)
{
  bender::test::TemporaryFolder folder("cfd-flow-json");
  const bender::CfdFlowResults r = Example();
  const std::string text = bender::CfdFlowResultsToJson(r);
  fs::create_directories(folder.Path() + "/results");
  std::ofstream(folder.Path() + "/results/flow.json") << text;
  const bender::CfdFlowResults back = bender::ReadCfdFlowResults(folder.Path());
  EXPECT_EQ(bender::CfdFlowResultsToJson(back), text);
  EXPECT_EQ(back.caseDirectory, folder.Path());
  ASSERT_EQ(back.ends.size(), 3u);
  EXPECT_EQ(back.ends[2].name, "outlet_2");
  EXPECT_EQ(back.ends[2].role, bender::PatchType::Outlet);
  EXPECT_EQ(back.run.residuals, r.run.residuals);
  // Every number has its unit: in its key, or in "units" for the free ones.
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["format"], "bender-flow-results");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["units"]["wallShearStress"], "Pa");
  EXPECT_DOUBLE_EQ(j["wallShearStress"]["lowThreshold_Pa"].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(j["wallShearStress"]["highThreshold_Pa"].get<double>(), 15.0);
  EXPECT_DOUBLE_EQ(j["ends"][1]["pressureDrop_Pa"].get<double>(), 51.75);
  const std::string summary = bender::FormatCfdFlowResults(back);
  EXPECT_NE(summary.find("converged in 412 iterations"), std::string::npos) << summary;
  EXPECT_NE(summary.find("99th percentile 8.25 Pa"), std::string::npos) << summary;
}

TEST(CfdFlowResults, ABadFlowJsonIsOneLineNamingTheFile)
{
  bender::test::TemporaryFolder folder("cfd-flow-json");
  const std::string path = folder.Path() + "/results/flow.json";
  auto expectError = [&](const std::string& what)
  {
    try
    {
      bender::ReadCfdFlowResults(folder.Path());
      ADD_FAILURE() << "no error for " << what;
    }
    catch (const bender::InputError& e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  };
  expectError("a missing file");
  fs::create_directories(folder.Path() + "/results");
  std::ofstream(path) << "{ not json";
  expectError("not JSON");
  std::ofstream(path) << R"({"format": "bender-cfd-case", "version": 1})";
  expectError("another format");
  nlohmann::json j = nlohmann::json::parse(bender::CfdFlowResultsToJson(Example()));
  j["version"] = 2;
  std::ofstream(path) << j.dump();
  expectError("another version");
  j["version"] = 1;
  j["wallShearStress"].erase("max_Pa");
  std::ofstream(path) << j.dump();
  expectError("a missing field");
  j = nlohmann::json::parse(bender::CfdFlowResultsToJson(Example()));
  j["ends"][0]["role"] = "sideways";
  std::ofstream(path) << j.dump();
  expectError("an unknown role");
}

} // namespace
