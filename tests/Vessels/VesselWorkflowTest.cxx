// The Logic vessel workflows on files: centerlines written and read back with their arrays,
// and the demo plan measured before and after (issue 10: the bend reported by measure --plan
// equals the angle between the plan's initial and final end tangents within 2 degrees).

#include "BenderErrors.h"
#include "BenderSession.h"
#include "CenterlineRibbonPlacement.h"
#include "DemoPipeline.h"
#include "MeshIO.h"
#include "VesselArrayNames.h"
#include "VesselMeasureTable.h"
#include "VesselSession.h"
#include "VesselTestUtilities.h"
#include "VesselWorkflows.h"
#include "WarpPlanIO.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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
  EXPECT_EQ(result.measures.branches.size(), 3u);
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
  // The vessel beyond the ribbon's end moves rigidly with the plan's end frame (the rotation
  // taking the initial end frame to the final one). The demo ribbon lies on the trunk's
  // centerline and ends at its open end, so the centerline's end tangent is the ribbon's and
  // turns by the plan's angle (40 degrees; the issue asks within 2). The branch's bend angle
  // (between its two end tangents) grows by what that rotation does to the measured tangents.
  const auto frameOf = [](const RibbonEnd& end)
  {
    const Vec3 t = Normalized(end.tangent);
    const Vec3 n = Normalized(end.normal - Dot(end.normal, t) * t);
    return std::array<Vec3, 3>{ { t, n, Cross(t, n) } };
  };
  const auto from = frameOf(plan.warps[0].initial.end);
  const auto to = frameOf(plan.warps[0].final.end);
  const auto move = [&](const Point3& p)
  {
    const Vec3 v{ p[0], p[1], p[2] };
    return Dot(v, from[0]) * to[0] + Dot(v, from[1]) * to[1] + Dot(v, from[2]) * to[2];
  };
  const auto vec = [](const Point3& p) { return Vec3{ p[0], p[1], p[2] }; };
  const bool atStart = bent->startTurn > bent->endTurn;
  const Point3& endBefore = atStart ? bent->before->startTangent : bent->before->endTangent;
  const Point3& otherBefore = atStart ? bent->before->endTangent : bent->before->startTangent;
  const double rigidTurn = AngleDegrees(vec(endBefore), move(endBefore));
  const double rigidBendChange = AngleDegrees(move(endBefore), vec(otherBefore)) -
    AngleDegrees(vec(endBefore), vec(otherBefore));
  std::printf("bent branch: turn %.2f (plan %.2f, rigid %.2f), bend change %.2f (rigid %.2f)\n",
    std::max(bent->startTurn, bent->endTurn),
    planned,
    rigidTurn,
    bent->after->bendAngle - bent->before->bendAngle,
    rigidBendChange);
  EXPECT_NEAR(std::max(bent->startTurn, bent->endTurn), rigidTurn, 2.0);
  EXPECT_NEAR(std::max(bent->startTurn, bent->endTurn), planned, 2.0);
  EXPECT_NEAR(bent->after->bendAngle - bent->before->bendAngle, rigidBendChange, 2.0);
  for (const auto& c : result.branches)
  {
    if (&c != bent)
    {
      EXPECT_LT(std::max(c.startTurn, c.endTurn), 2.0);
      EXPECT_NEAR(c.after->length, c.before->length, 0.02 * c.before->length);
    }
  }
  const std::string json = MeasurementsToJson(result);
  EXPECT_NE(json.find("\"comparison\""), std::string::npos);
  EXPECT_FALSE(MeasurementsToText(result).empty());
}

// The demo segmentation (closed, from the MRA-like phantom of the gmsh aneurysm): the vessel
// tips found on a closed surface, the sac rejected, and its centerlines close to those of the
// gmsh surface it was made from, away from the ends and the bifurcation region.
TEST(VesselWorkflow, SegmentationPhantomCenterlinesFollowTheSourceSurface)
{
  const DemoVessel demo = SegmentDemoVessel(DemoVesselPath());
  CenterlineResult segmented = ComputeCenterlines(demo.surface);
  ASSERT_TRUE(segmented.ok) << segmented.message;
  ASSERT_EQ(segmented.endpoints.size(), 3u) << "the aneurysm's sac must not be a vessel end";
  for (const auto& end : segmented.endpoints)
  {
    EXPECT_EQ(end.kind, EndpointKind::VoronoiTip);
  }
  EXPECT_EQ(segmented.bifurcations.size(), 1u);
  const CenterlineResult source = ComputeCenterlines(ReadMesh(Aneurysm));
  ASSERT_TRUE(source.ok) << source.message;
  // Distance from each segmented centerline point to the source's centerlines, skipping two
  // end radii around the ends (a closed tip stops about one radius before the cut) and around
  // the bifurcation.
  double largest = 0.0;
  for (const auto& end : source.endpoints)
  {
    largest = std::max(largest, end.radius);
  }
  std::vector<Point3> excluded;
  for (const auto& end : segmented.endpoints)
  {
    excluded.push_back(end.position);
  }
  for (const auto& b : segmented.bifurcations)
  {
    excluded.push_back(b);
  }
  std::vector<std::vector<Point3>> sourceLines;
  {
    vtkCellArray* cells = source.paths->GetLines();
    cells->InitTraversal();
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    while (cells->GetNextCell(n, ids))
    {
      std::vector<Point3> line(static_cast<std::size_t>(n));
      for (vtkIdType k = 0; k < n; ++k)
      {
        source.paths->GetPoint(ids[k], line[k].data());
      }
      sourceLines.push_back(line);
    }
  }
  double worst = 0.0;
  int checked = 0;
  for (vtkIdType i = 0; i < segmented.paths->GetNumberOfPoints(); ++i)
  {
    Point3 p;
    segmented.paths->GetPoint(i, p.data());
    bool skip = false;
    for (const auto& x : excluded)
    {
      skip = skip || std::hypot(p[0] - x[0], p[1] - x[1], p[2] - x[2]) < 2.0 * largest;
    }
    if (skip)
    {
      continue;
    }
    double best = 1e300;
    for (const auto& polyline : sourceLines)
    {
      best = std::min(best, test::DistanceToPolyline(p, polyline));
    }
    worst = std::max(worst, best);
    ++checked;
  }
  EXPECT_GT(checked, 100);
  std::printf(
    "segmented vs source centerlines: %d points, largest distance %.3f mm\n", checked, worst);
  // Issue 10's target: 0.3 mm. Measured 0.095 mm (centerlines on the centroids of the
  // cross-sections, which the segmentation's smoothing moves little).
  EXPECT_LT(worst, 0.3);
}

// Two picks on the wall of the gmsh aneurysm's inlet branch place the ribbon on its centerline
// (ends on the centerline, tangents = the centerline's, R from the inscribed radius); a pick on
// the aneurysm's sac is refused.
TEST(VesselWorkflow, RibbonOnTheCenterlineFromTwoPicks)
{
  auto surface = ReadMesh(Aneurysm);
  const CenterlineResult result = ComputeCenterlines(surface);
  ASSERT_TRUE(result.ok) << result.message;
  vtkPolyData* paths = result.paths;
  vtkDataArray* radius =
    paths->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius);
  vtkDataArray* tangent = paths->GetPointData()->GetArray(VesselArrays::FrenetTangent);
  vtkDataArray* normal = paths->GetPointData()->GetArray(VesselArrays::FrenetNormal);
  // Picks on the wall: centerline points 30 and 150 of the first path pushed out by their radius.
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  paths->GetLines()->InitTraversal();
  paths->GetLines()->GetNextCell(npts, ids);
  ASSERT_GT(npts, 200);
  auto wallPick = [&](vtkIdType i)
  {
    double p[3], nn[3];
    paths->GetPoint(ids[i], p);
    normal->GetTuple(ids[i], nn);
    const double r = radius->GetComponent(ids[i], 0);
    return Vec3{ p[0] + r * nn[0], p[1] + r * nn[1], p[2] + r * nn[2] };
  };
  const RibbonPlacement placed = PlaceRibbonOnCenterline(paths, wallPick(30), wallPick(150));
  double p30[3], p150[3], t30[3], t150[3];
  paths->GetPoint(ids[30], p30);
  paths->GetPoint(ids[150], p150);
  tangent->GetTuple(ids[30], t30);
  tangent->GetTuple(ids[150], t150);
  EXPECT_LT(
    Distance(placed.ribbon.start.position, Vec3{ p30[0], p30[1], p30[2] }), 3 * result.step);
  EXPECT_LT(
    Distance(placed.ribbon.end.position, Vec3{ p150[0], p150[1], p150[2] }), 3 * result.step);
  EXPECT_GT(Dot(placed.ribbon.start.tangent, Vec3{ t30[0], t30[1], t30[2] }), 0.99);
  EXPECT_GT(Dot(placed.ribbon.end.tangent, Vec3{ t150[0], t150[1], t150[2] }), 0.99);
  EXPECT_NEAR(Dot(placed.ribbon.start.normal, placed.ribbon.start.tangent), 0.0, 1e-9);
  EXPECT_NEAR(Dot(placed.ribbon.end.normal, placed.ribbon.end.tangent), 0.0, 1e-9);
  EXPECT_NEAR(placed.suggestedRadius, 2.2 * placed.vesselRadius, 1e-12);
  EXPECT_GT(placed.vesselRadius, 2.0);
  // Reversed picks: the ribbon runs the other way.
  const RibbonPlacement reversed = PlaceRibbonOnCenterline(paths, wallPick(150), wallPick(30));
  EXPECT_LT(Dot(reversed.ribbon.start.tangent, Vec3{ t150[0], t150[1], t150[2] }), -0.99);
  // The sac: the surface point farthest from every centerline relative to the local radius.
  Vec3 sac{ 0, 0, 0 };
  double worst = 0.0;
  for (vtkIdType s = 0; s < surface->GetNumberOfPoints(); ++s)
  {
    double q[3];
    surface->GetPoint(s, q);
    double ratio = 1e300;
    for (vtkIdType k = 0; k < paths->GetNumberOfPoints(); k += 5)
    {
      double c[3];
      paths->GetPoint(k, c);
      ratio = std::min(
        ratio, std::hypot(q[0] - c[0], q[1] - c[1], q[2] - c[2]) / radius->GetComponent(k, 0));
    }
    if (ratio > worst)
    {
      worst = ratio;
      sac = Vec3{ q[0], q[1], q[2] };
    }
  }
  EXPECT_THROW(PlaceRibbonOnCenterline(paths, sac, wallPick(150)), RibbonPlacementError);
  EXPECT_THROW(PlaceRibbonOnCenterline(paths, wallPick(30), wallPick(31)), RibbonPlacementError);
  EXPECT_THROW(PlaceRibbonOnCenterline(nullptr, wallPick(30), wallPick(150)), RibbonPlacementError);
}

// A measure registered in the vessel measure table appears in every list the CLI prints
// (the JSON of `centerline --json` and `measure --json`, per branch and in the change, and
// the text tables of `measure`) without a change to the callers, and leaves them with it.
TEST(VesselWorkflow, ARegisteredMeasureAppearsInTheJsonAndTheTextTables)
{
  const test::Curve axis = [](double t) { return Point3{ { 0.0, 0.3 * t, t } }; };
  MeasureWorkflowResult result;
  result.before.surface = test::SweptTube(axis, 0.0, 30.0, 61, 32, 2.0);
  result.before.centerlines = ComputeCenterlines(result.before.surface);
  ASSERT_TRUE(result.before.centerlines.ok) << result.before.centerlines.message;
  result.before.measures = MeasureBranches(result.before.centerlines.branches);
  ASSERT_EQ(result.before.measures.branches.size(), 1u);
  result.after = result.before;
  BranchComparison same;
  same.before = result.before.measures.branches[0];
  same.after = result.after->measures.branches[0];
  result.branches.push_back(same);
  const double length = result.before.measures.branches[0].length;

  RegisterVesselMeasure(
    { "twiceTheLength", "Twice the length", "mm", 3, [](const BranchMeasures& b) {
       return 2.0 * b.length;
     } });
  const auto json = nlohmann::json::parse(MeasurementsToJson(result));
  const auto centerlineJson = nlohmann::json::parse(CenterlinesToJson(result.before));
  const std::string text = MeasurementsToText(result);
  EXPECT_TRUE(UnregisterVesselMeasure("twiceTheLength"));

  EXPECT_NEAR(json["before"]["branches"][0]["twiceTheLength"].get<double>(), 2 * length, 1e-4);
  EXPECT_NEAR(json["after"]["branches"][0]["twiceTheLength"].get<double>(), 2 * length, 1e-4);
  EXPECT_EQ(json["comparison"][0]["change"]["twiceTheLength"].get<double>(), 0.0);
  EXPECT_NEAR(centerlineJson["branches"][0]["twiceTheLength"].get<double>(), 2 * length, 1e-4);
  EXPECT_NE(text.find("Twice the length (mm)"), std::string::npos) << text;
  char value[32];
  std::snprintf(value, sizeof(value), "%.3f", 2 * length);
  EXPECT_NE(text.find(value), std::string::npos) << text;
  EXPECT_NE(text.find("+0.000"), std::string::npos) << text;
  // Every row of the table is in the JSON; unregistered, the dummy is gone.
  for (const VesselMeasure& m : VesselMeasureTable())
  {
    EXPECT_TRUE(centerlineJson["branches"][0].contains(m.key)) << m.key;
  }
  EXPECT_EQ(CenterlinesToJson(result.before).find("twiceTheLength"), std::string::npos);
  EXPECT_EQ(MeasurementsToText(result).find("Twice the length"), std::string::npos);
}

// The demo's bend on the demo surface: the live measures of the branch held under the ribbon
// (the panel) and the plan table's measures (MeasureBranches) of the same stretch agree, before
// the bend and during it: both follow the one end-window rule (VesselMeasures.h).
TEST(VesselWorkflow, LiveMeasuresAndThePlanTableAgreeOnTheDemo)
{
  const WarpPlan plan = ReadWarpPlan(DemoPlan);
  ASSERT_EQ(plan.warps.size(), 1u);
  const WarpSpec& demo = plan.warps[0];
  BenderSession session;
  ASSERT_TRUE(session.LoadSurface(Aneurysm));
  VesselSession vessels;
  auto job = vessels.BeginCenterlines(session);
  ASSERT_TRUE(job);
  job->Run({});
  std::string message;
  ASSERT_TRUE(vessels.Finish(*job, message)) << message;
  ASSERT_TRUE(vessels.HoldBranch(demo.initial, session.GetSurface()));
  const auto agree = [](const HeldBranchMeasures& live, vtkPolyData* stretch)
  {
    ASSERT_TRUE(live.valid);
    ASSERT_NE(stretch, nullptr);
    const VesselMeasurements table = MeasureBranches(stretch);
    ASSERT_EQ(table.branches.size(), 1u);
    for (const VesselMeasure& m : VesselMeasureTable())
    {
      EXPECT_NEAR(m.get(live), m.get(table.branches[0]), 1e-9 * (1.0 + std::abs(m.get(live))))
        << m.key;
    }
  };
  const HeldBranchMeasures before = vessels.MeasureHeld();
  agree(before, vessels.HeldStretch());

  WarpParameters parameters = session.GetParameters();
  parameters.radius = demo.radius;
  ASSERT_TRUE(session.SetParameters(parameters));
  ASSERT_TRUE(session.Grab(demo.initial));
  ASSERT_TRUE(session.MoveFinal(demo.final)) << session.GetLiveProblem();
  const WarpSpec live = LiveWarpOf(session);
  const HeldBranchMeasures now = vessels.MeasureHeld(live);
  agree(now, vessels.HeldStretch(live));
  std::printf("demo held stretch: length %.2f -> %.2f mm, bend %.2f -> %.2f deg\n",
    before.length,
    now.length,
    before.bendAngle,
    now.bendAngle);
  // The demo turns the ribbon's end frame: the held stretch is carried (it moved), so the
  // agreement above is that of a warped stretch.
  EXPECT_GT(std::abs(now.bendAngle - before.bendAngle) + std::abs(now.length - before.length), 0.1);
  session.CancelGrab("test done");
}
