// The Logic vessel workflows on files: centerlines written and read back with their arrays,
// and the demo plan measured before and after (issue 10: the bend reported by measure --plan
// equals the angle between the plan's initial and final end tangents within 2 degrees).

#include "BenderErrors.h"
#include "MeshIO.h"
#include "VesselArrayNames.h"
#include "VesselWorkflows.h"
#include "WarpPlanIO.h"

#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace bender;

namespace
{
const std::string Aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
const std::string DemoPlan = std::string(BENDER_SOURCE_DIR) + "/data/demo/demo.bender.json";

double AngleDegrees(const Vec3& a, const Vec3& b)
{
  const double c = Dot(a, b) / (Norm(a) * Norm(b));
  return std::acos(std::max(-1.0, std::min(1.0, c))) * 180.0 / 3.14159265358979323846;
}
} // namespace

TEST(VesselWorkflow, CenterlinesWrittenWithTheirArrays)
{
  const std::string out =
    (std::filesystem::temp_directory_path() / "bender_vessels_centerlines.vtp").string();
  std::remove(out.c_str());
  CenterlineWorkflowOptions options;
  options.input = Aneurysm;
  options.output = out;
  const CenterlineWorkflowResult result = ComputeCenterlinesOfFile(options);
  EXPECT_EQ(result.measures.Branches.size(), 3u);
  auto lines = ReadMesh(out);
  EXPECT_EQ(lines->GetNumberOfLines(), 3);
  for (const char* name : { VesselArrays::MaximumInscribedSphereRadius,
         VesselArrays::Abscissa,
         VesselArrays::FrenetTangent,
         VesselArrays::FrenetNormal,
         VesselArrays::Curvature,
         VesselArrays::Torsion })
  {
    EXPECT_NE(lines->GetPointData()->GetArray(name), nullptr) << name;
  }
  for (const char* name : { VesselArrays::BranchId,
         VesselArrays::ParentBranchId,
         VesselArrays::StartBifurcationId,
         VesselArrays::EndBifurcationId,
         VesselArrays::EndpointId })
  {
    EXPECT_NE(lines->GetCellData()->GetArray(name), nullptr) << name;
  }
  std::remove(out.c_str());
  const std::string json = CenterlinesToJson(result);
  EXPECT_NE(json.find("\"endpoints\""), std::string::npos);
  EXPECT_NE(json.find("\"tortuosity\""), std::string::npos);
}

TEST(VesselWorkflow, BadInputsAreOneLineErrors)
{
  CenterlineWorkflowOptions options;
  options.input = "/nonexistent/vessel.stl";
  EXPECT_THROW(ComputeCenterlinesOfFile(options), InputError);
  options.input = Aneurysm;
  options.output = "/tmp/centerlines.stl";
  EXPECT_THROW(ComputeCenterlinesOfFile(options), InputError);
  options.output = Aneurysm;
  EXPECT_THROW(ComputeCenterlinesOfFile(options), InputError);
  EXPECT_THROW(ParsePoint("1,2", "--seeds"), InputError);
  EXPECT_THROW(ParsePoint("1,2,x", "--seeds"), InputError);
  EXPECT_THROW(ParsePoint("1,2,nan", "--seeds"), InputError);
  const Point3 p = ParsePoint("1.5,-2,3e1", "--seeds");
  EXPECT_DOUBLE_EQ(p[2], 30.0);
  MeasureWorkflowOptions measure;
  measure.input = Aneurysm;
  measure.after = Aneurysm;
  measure.plan = DemoPlan;
  EXPECT_THROW(MeasureVessels(measure), InputError);
}

TEST(VesselWorkflow, DemoPlanBendAngleMatchesThePlanWithinTwoDegrees)
{
  const WarpPlan plan = ReadWarpPlan(DemoPlan);
  ASSERT_EQ(plan.warps.size(), 1u);
  const double planned =
    AngleDegrees(plan.warps[0].initial.end.tangent, plan.warps[0].final.end.tangent);
  MeasureWorkflowOptions options;
  options.input = Aneurysm;
  options.plan = DemoPlan;
  const MeasureWorkflowResult result = MeasureVessels(options);
  ASSERT_TRUE(result.after.has_value());
  ASSERT_EQ(result.branches.size(), 3u);
  // The plan bends the inlet branch: its free end turns by the plan's angle, the other
  // branches do not move.
  const BranchComparison* bent = nullptr;
  for (const auto& c : result.branches)
  {
    ASSERT_TRUE(c.before && c.after);
    const double turn = std::max(c.startTurn, c.endTurn);
    if (!bent || turn > std::max(bent->startTurn, bent->endTurn))
    {
      bent = &c;
    }
  }
  ASSERT_NE(bent, nullptr);
  EXPECT_NEAR(std::max(bent->startTurn, bent->endTurn), planned, 2.0);
  EXPECT_NEAR(bent->after->BendAngle - bent->before->BendAngle, planned, 2.0);
  for (const auto& c : result.branches)
  {
    if (&c != bent)
    {
      EXPECT_LT(std::max(c.startTurn, c.endTurn), 2.0);
      EXPECT_NEAR(c.after->Length, c.before->Length, 0.02 * c.before->Length);
    }
  }
  const std::string json = MeasurementsToJson(result);
  EXPECT_NE(json.find("\"comparison\""), std::string::npos);
  EXPECT_FALSE(MeasurementsToText(result).empty());
}
