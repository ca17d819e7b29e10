// The grading of a case's mesh by the local width of the lumen (issue 23, "cells where they are
// needed"), without OpenFOAM: the lumen's diameter measured on the wall, the levels that give
// the cells across asked for and no more, the regions and levels written for snappyHexMesh, the
// cells across stated in the report and the JSON, and a convergence study's finer meshes
// keeping mesh-1's levels.

#include "BenderErrors.h"
#include "CfdCase.h"
#include "CfdDictionaries.h"
#include "CfdMeshGrading.h"
#include "CfdTestUtilities.h"
#include "LabelledSurface.h"
#include "MeshIO.h"
#include "PatchLabels.h"

#include <vtkPolyData.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using bender::test::ReadText;

namespace
{

vtkPolyData* Aneurysm()
{
  static vtkSmartPointer<vtkPolyData> surface = bender::test::CappedAneurysm(false);
  return surface;
}

const bender::CfdPatch& Patch(const bender::CfdCaseResult& r, const std::string& name)
{
  for (const bender::CfdPatch& p : r.patches)
  {
    if (p.name == name)
    {
      return p;
    }
  }
  throw std::runtime_error("no patch " + name);
}

TEST(CfdGrading, TheLumensDiameterOfATubeIsMeasuredOnEveryWallTriangle)
{
  // A tube of radius 2 mm, 32 sides: the chord through the axis between two opposite facets
  // is 2 R cos(pi / 32).
  vtkSmartPointer<vtkPolyData> tube = bender::test::CappedTube(40.0, 2.0, 41, 32);
  const std::vector<int> ids = bender::CellPatchIds(tube);
  std::vector<bool> wall(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    wall[i] = ids[i] == bender::kWallEntityId;
  }
  const std::vector<double> d = bender::LocalLumenDiameters(tube, wall);
  ASSERT_EQ(d.size(), ids.size());
  const double expected = 4.0 * std::cos(M_PI / 32.0);
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    if (wall[i])
    {
      EXPECT_NEAR(d[i], expected, 0.01 * expected) << i;
    }
    else
    {
      EXPECT_EQ(d[i], 0.0) << i; // the caps are not measured
    }
  }
}

TEST(CfdGrading, EachLevelGivesTheCellsAcrossAskedForAndNoMore)
{
  const double h = 1e-3;
  for (const double across : { 4.0, 8.0, 10.0 })
  {
    for (double d = 0.1e-3; d < 40e-3; d *= 1.07)
    {
      const int level = bender::CfdRefinementLevel(d, h, across);
      ASSERT_GE(level, 1);
      ASSERT_LE(level, 1 + bender::kCfdMaxExtraLevels);
      const double cells = d / bender::CfdLevelCellSize(level, h);
      if (level < 1 + bender::kCfdMaxExtraLevels)
      {
        EXPECT_GE(cells, across * (1.0 - 1e-9)) << d;
      }
      if (level > 1)
      {
        // One level coarser would not do.
        EXPECT_LT(d / bender::CfdLevelCellSize(level - 1, h), across) << d;
      }
    }
  }
  // Exactly the cells asked for: no refinement.
  EXPECT_EQ(bender::CfdRefinementLevel(8e-3, 1e-3, 8.0), 1);
}

TEST(CfdGrading, TheDefaultCaseGradesEachEndAndTheWallAndSaysSo)
{
  bender::test::TemporaryFolder folder("cfd-grading");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  const bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  const bender::CfdMeshGrading& g = r.grading;

  // The base cell from the largest end; every end with at least 8 cells across, at the
  // coarsest level that gives them.
  double largest = 0.0;
  for (const bender::CfdPatch& p : r.patches)
  {
    largest = p.type == bender::PatchType::Wall ? largest : std::max(largest, p.diameter);
  }
  EXPECT_DOUBLE_EQ(g.cellsAcross, bender::kCfdDefaultCellsAcross);
  EXPECT_NEAR(r.cellSize, largest / 8.0, 1e-12);
  ASSERT_EQ(g.ends.size(), 3u);
  bool refinedEnd = false;
  for (const bender::CfdEndCells& e : g.ends)
  {
    const double d = Patch(r, e.name).diameter;
    EXPECT_NEAR(e.cellsAcross, d / e.cellSize, 1e-9) << e.name;
    EXPECT_GE(e.cellsAcross, 0.99 * 8.0) << e.name; // within 1 %
    EXPECT_LT(e.cellsAcross, 16.0) << e.name;
    EXPECT_DOUBLE_EQ(e.cellSize, r.cellSize / std::pow(2.0, e.level - 1)) << e.name;
    refinedEnd = refinedEnd || e.level > 1;
  }
  EXPECT_TRUE(refinedEnd) << "the aneurysm's ends differ by more than their 8 cells allow";

  // The wall: at least 0.9 x 8 cells across everywhere, the narrowest place inside the
  // surface's bounds.
  EXPECT_GE(g.wallCellsAcross, bender::kCfdWallCellsMargin * 8.0 * (1.0 - 1e-9));
  EXPECT_GE(g.narrowestCellsAcross, g.wallCellsAcross);
  EXPECT_GT(g.narrowestDiameter, 0.0);
  EXPECT_LT(g.narrowestDiameter, largest);
  double bounds[6];
  Aneurysm()->GetBounds(bounds);
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_GE(1e3 * g.narrowestAt[k], bounds[2 * k] - 1e-6) << k;
    EXPECT_LE(1e3 * g.narrowestAt[k], bounds[2 * k + 1] + 1e-6) << k;
  }

  // snappyHexMesh: each end at its level, each region's surface (metres) refined at its level
  // within its distance.
  const std::string snappy = ReadText(options.caseDirectory + "/system/snappyHexMeshDict");
  for (const bender::CfdEndCells& e : g.ends)
  {
    const std::string level = std::to_string(e.level);
    EXPECT_NE(
      snappy.find(e.name + " { level (" + level + " " + level + "); patchInfo { type patch"),
      std::string::npos)
      << e.name << "\n"
      << snappy;
  }
  EXPECT_NE(snappy.find("wall { level (1 1); patchInfo { type wall"), std::string::npos);
  ASSERT_FALSE(g.regions.empty()) << "the branches are narrower than the inlet";
  long long previous = -1;
  for (const bender::CfdRefinementRegion& region : g.regions)
  {
    EXPECT_NE(snappy.find(region.name + ".stl { type triSurfaceMesh; name " + region.name),
      std::string::npos)
      << region.name;
    EXPECT_NE(snappy.find(region.name + " { mode distance; levels ((" +
                bender::CfdNumber(region.distance) + " " + std::to_string(region.level) + ")); }"),
      std::string::npos)
      << region.name;
    // A finer region holds fewer triangles (those of its level or finer).
    EXPECT_TRUE(previous < 0 || region.triangles <= previous) << region.name;
    previous = region.triangles;
    const std::string stl = options.caseDirectory + "/constant/triSurface/" + region.name + ".stl";
    ASSERT_TRUE(fs::is_regular_file(stl)) << stl;
    // Read back (in millimetres, the unit the file states): the region's triangles.
    vtkSmartPointer<vtkPolyData> part = bender::ReadMesh(stl);
    EXPECT_EQ(part->GetNumberOfCells(), region.triangles) << region.name;
    // Written in metres: the aneurysm spans ~55 mm.
    std::istringstream text(ReadText(stl));
    std::string word;
    while (text >> word && word != "vertex")
    {
    }
    double x = 1.0;
    ASSERT_TRUE(text >> x) << region.name;
    EXPECT_LT(std::abs(x), 0.1) << region.name;
    EXPECT_LE(region.distance, 0.5 * largest);
    EXPECT_DOUBLE_EQ(region.cellSize, r.cellSize / std::pow(2.0, region.level - 1));
  }

  // The report and bender-case.json state the cells across.
  const std::string report = bender::FormatCfdCase(r);
  EXPECT_NE(report.find("wall cells across each end"), std::string::npos) << report;
  EXPECT_NE(report.find("cells across everywhere on the wall"), std::string::npos) << report;
  std::ifstream in(options.caseDirectory + "/bender-case.json");
  const nlohmann::json json = nlohmann::json::parse(in);
  ASSERT_TRUE(json.contains("grading"));
  EXPECT_EQ(json["grading"]["ends"].size(), 3u);
  EXPECT_DOUBLE_EQ(json["grading"]["wallCellsAcrossMin"].get<double>(), g.wallCellsAcross);
  const nlohmann::json run = nlohmann::json::parse(bender::CfdToJson(r, nullptr));
  EXPECT_EQ(run["grading"]["regions"].size(), g.regions.size());
}

TEST(CfdGrading, AFinerMeshOfAConvergenceStudyKeepsTheLevelsOfMeshOne)
{
  bender::test::TemporaryFolder folder("cfd-grading-study");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/mesh-1";
  const bender::CfdCaseResult coarse = bender::WriteOpenFoamCase(Aneurysm(), options);
  options.caseDirectory = folder.Path() + "/mesh-2";
  options.cellSize = coarse.cellSize / 1.3;
  options.cellsAcross = coarse.grading.cellsAcross * 1.3;
  const bender::CfdCaseResult fine = bender::WriteOpenFoamCase(Aneurysm(), options);
  ASSERT_EQ(fine.grading.ends.size(), coarse.grading.ends.size());
  for (std::size_t i = 0; i < fine.grading.ends.size(); ++i)
  {
    EXPECT_EQ(fine.grading.ends[i].level, coarse.grading.ends[i].level);
    EXPECT_NEAR(fine.grading.ends[i].cellSize * 1.3, coarse.grading.ends[i].cellSize, 1e-15);
    EXPECT_NEAR(fine.grading.ends[i].cellsAcross, 1.3 * coarse.grading.ends[i].cellsAcross, 1e-9);
  }
  ASSERT_EQ(fine.grading.regions.size(), coarse.grading.regions.size());
  for (std::size_t i = 0; i < fine.grading.regions.size(); ++i)
  {
    EXPECT_EQ(fine.grading.regions[i].triangles, coarse.grading.regions[i].triangles);
    EXPECT_DOUBLE_EQ(fine.grading.regions[i].distance, coarse.grading.regions[i].distance);
  }
}

TEST(CfdGrading, AGivenCellSizeKeepsItsCellsAcrossTheSmallestEnd)
{
  bender::test::TemporaryFolder folder("cfd-grading-size");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.cellSize = 1e-3;
  const bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  double smallest = 1.0;
  for (const bender::CfdPatch& p : r.patches)
  {
    smallest = p.type == bender::PatchType::Wall ? smallest : std::min(smallest, p.diameter);
  }
  EXPECT_DOUBLE_EQ(r.cellSize, 1e-3);
  EXPECT_NEAR(r.grading.cellsAcross, smallest / 1e-3, 1e-9);
  for (const bender::CfdEndCells& e : r.grading.ends)
  {
    EXPECT_EQ(e.level, 1) << e.name; // every end at least as wide as the smallest
  }
  // Asking for more cells across refines the ends that lack them.
  options.caseDirectory = folder.Path() + "/finer";
  options.cellsAcross = 2.0 * r.grading.cellsAcross;
  const bender::CfdCaseResult finer = bender::WriteOpenFoamCase(Aneurysm(), options);
  for (const bender::CfdEndCells& e : finer.grading.ends)
  {
    EXPECT_GE(e.cellsAcross, 0.99 * options.cellsAcross) << e.name;
    EXPECT_GE(e.level, 2) << e.name;
  }
  // Out of range.
  options.cellsAcross = 1.0;
  EXPECT_THROW(bender::WriteOpenFoamCase(Aneurysm(), options), bender::InputError);
}

} // namespace
