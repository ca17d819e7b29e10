// bender-cli check AFTER --before BEFORE: the lumen guard on the command line (issue 22). Both
// shapes' centerlines, each branch's minimal inscribed radius before and after; exit 1 when a
// branch the bend moved narrows by more than --max-narrowing (default 5 %).
#include "CfdVerificationTubes.h"
#include "CliPostTestUtilities.h"
#include "MeshIO.h"

#include <nlohmann/json.hpp>

#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cmath>
#include <functional>

using namespace clitest;

namespace
{

using Map = std::function<std::array<double, 3>(double x, double y, double z)>;

// An open tube along +x (radius 2, length 40, 81 rings of 32 points: the one tube generator,
// CfdVerificationTubes.h) written as OFF, its points mapped by `map`.
void WriteTube(const std::string& path, const Map& map)
{
  const vtkSmartPointer<vtkPolyData> tube =
    bender::SweepOpenTube(bender::StraightCentreline(0.0, 40.0, 80), 2.0, 32);
  vtkPoints* points = tube->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    const std::array<double, 3> q = map(p[0], p[1], p[2]);
    points->SetPoint(i, q.data());
  }
  bender::WriteMesh(tube, path);
}

const Map Straight = [](double x, double y, double z) { return std::array<double, 3>{ x, y, z }; };

// A waist of 15 % at x = 25.
const Map Waist = [](double x, double y, double z)
{
  const double u = (x - 25.0) / 3.0;
  const double s = 1.0 - 0.15 * std::exp(-u * u);
  return std::array<double, 3>{ x, s * y, s * z };
};

// Bent into an arc of radius 30: every cross-section kept.
const Map Arc = [](double x, double y, double z)
{
  const double a = x / 30.0;
  return std::array<double, 3>{ (30.0 - y) * std::sin(a), 30.0 - (30.0 - y) * std::cos(a), z };
};

class CliLumen : public ScratchTest
{
protected:
  void SetUp() override
  {
    ScratchTest::SetUp();
    WriteTube(Tmp("tube.off"), Straight);
    WriteTube(Tmp("pinched.off"), Waist);
    WriteTube(Tmp("bent.off"), Arc);
  }
};

} // namespace

TEST_F(CliLumen, APinchedPairFailsAndSaysWhere)
{
  const Result r = Run("check " + Q(Tmp("pinched.off")) + " --before " + Q(Tmp("tube.off")) +
    " --json --no-self-intersections");
  ASSERT_EQ(r.status, 1) << r.output << r.errors;
  const auto report = nlohmann::json::parse(r.output);
  // The surface itself is clean: the lumen alone fails it.
  EXPECT_EQ(report.at("flippedTriangles"), 0);
  const auto& lumen = report.at("lumen");
  EXPECT_EQ(lumen.at("checked"), true);
  EXPECT_EQ(lumen.at("passed"), false);
  EXPECT_DOUBLE_EQ(lumen.at("maxNarrowing").get<double>(), 0.05);
  ASSERT_FALSE(lumen.at("problems").empty());
  bool found = false;
  for (const auto& branch : lumen.at("branches"))
  {
    if (branch.at("tooNarrow").get<bool>())
    {
      found = true;
      EXPECT_GT(branch.at("narrowing").get<double>(), 0.05);
      EXPECT_LT(
        branch.at("afterMinRadius").get<double>(), branch.at("beforeMinRadius").get<double>());
      EXPECT_NEAR(branch.at("narrowest")[0].get<double>(), 25.0, 2.0);
    }
  }
  EXPECT_TRUE(found) << r.output;

  // The text names the branch and its radii; a larger threshold lets the same pair pass.
  const Result text = Run("check " + Q(Tmp("pinched.off")) + " --before " + Q(Tmp("tube.off")));
  EXPECT_EQ(text.status, 1);
  EXPECT_NE(text.output.find("narrowed by"), std::string::npos) << text.output;
  const Result lenient = Run(
    "check " + Q(Tmp("pinched.off")) + " --before " + Q(Tmp("tube.off")) + " --max-narrowing 30");
  EXPECT_EQ(lenient.status, 0) << lenient.output;
  // Without the lumen guard the pinch goes unseen: what the guard adds.
  const Result blind = Run(
    "check " + Q(Tmp("pinched.off")) + " --before " + Q(Tmp("tube.off")) + " --no-lumen --json");
  EXPECT_EQ(blind.status, 0) << blind.output;
  EXPECT_FALSE(nlohmann::json::parse(blind.output).contains("lumen"));
}

TEST_F(CliLumen, AnUnpinchedBendPasses)
{
  const Result r = Run("check " + Q(Tmp("bent.off")) + " --before " + Q(Tmp("tube.off")) +
    " --json --no-self-intersections");
  ASSERT_EQ(r.status, 0) << r.output << r.errors;
  const auto report = nlohmann::json::parse(r.output);
  const auto& lumen = report.at("lumen");
  EXPECT_EQ(lumen.at("checked"), true);
  EXPECT_EQ(lumen.at("passed"), true);
  ASSERT_FALSE(lumen.at("branches").empty());
  for (const auto& branch : lumen.at("branches"))
  {
    EXPECT_TRUE(branch.at("moved").get<bool>());
    EXPECT_LT(std::fabs(branch.at("narrowing").get<double>()), 0.05);
  }
}

TEST_F(CliLumen, AThresholdOutOfRangeIsAUsageError)
{
  const Result r = Run(
    "check " + Q(Tmp("pinched.off")) + " --before " + Q(Tmp("tube.off")) + " --max-narrowing 150");
  EXPECT_EQ(r.status, 2) << r.output;
}
