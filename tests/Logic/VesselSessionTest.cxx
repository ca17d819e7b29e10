// VesselSession on the gmsh aneurysm (data/external/aneurysm_data.stl): centerlines as a job of
// the committed surface, the ribbon on the centerline (a pick on the sac refused), the held
// branch measured live with the live warp, and the before/after comparison after a release.

#include "VesselSession.h"
#include "BenderSession.h"
#include "VesselArrayNames.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>
#include <iostream>
#include <memory>

using namespace bender;

namespace
{
const std::string Aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
constexpr double Degrees = 180.0 / 3.14159265358979323846;

double TangentAngle(const RibbonSpec& ribbon)
{
  return std::acos(std::clamp(Dot(ribbon.start.tangent, ribbon.end.tangent), -1.0, 1.0)) * Degrees;
}

class VesselSessionTest : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    Session = new BenderSession;
    ASSERT_TRUE(Session->LoadSurface(Aneurysm));
    Vessels = new VesselSession;
    EXPECT_FALSE(Vessels->IsUpToDate(*Session));
    auto job = Vessels->BeginCenterlines(*Session);
    ASSERT_TRUE(job);
    job->Run({});
    std::string message;
    ASSERT_TRUE(Vessels->Finish(*job, message)) << message;
  }
  static void TearDownTestSuite()
  {
    delete Vessels;
    delete Session;
  }

  /// A point on the wall beside sample i of the first path (pushed out by the radius).
  static Vec3 WallPick(vtkIdType i)
  {
    vtkPolyData* paths = Vessels->GetPaths();
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    paths->GetLines()->GetCellAtId(0, n, ids);
    double p[3], nn[3];
    paths->GetPoint(ids[i], p);
    paths->GetPointData()->GetArray(VesselArrays::FrenetNormal)->GetTuple(ids[i], nn);
    const double r = paths->GetPointData()
                       ->GetArray(VesselArrays::MaximumInscribedSphereRadius)
                       ->GetComponent(ids[i], 0);
    return { p[0] + r * nn[0], p[1] + r * nn[1], p[2] + r * nn[2] };
  }

  static BenderSession* Session;
  static VesselSession* Vessels;
};
BenderSession* VesselSessionTest::Session = nullptr;
VesselSession* VesselSessionTest::Vessels = nullptr;
} // namespace

TEST_F(VesselSessionTest, CentrelinesOfTheLoadedSurface)
{
  ASSERT_TRUE(Vessels->HasCenterlines());
  EXPECT_TRUE(Vessels->IsUpToDate(*Session));
  EXPECT_FALSE(Vessels->BeginCenterlines(*Session)) << "up to date: no new job";
  EXPECT_EQ(Vessels->GetPaths()->GetNumberOfCells(), 2);
  EXPECT_GE(Vessels->GetMeasures().branches.size(), 3u);
  EXPECT_FALSE(Vessels->GetComparison()) << "nothing bent yet";
}

TEST_F(VesselSessionTest, RibbonOnTheCenterlineAndTheSacRefused)
{
  const RibbonPlacement placed = Vessels->PlaceRibbon(WallPick(30), WallPick(150));
  EXPECT_GT(placed.vesselRadius, 1.0);
  // The sac: the surface point farthest from the centerlines relative to the local radius.
  vtkPolyData* surface = Session->GetSurface();
  vtkPolyData* paths = Vessels->GetPaths();
  vtkDataArray* radius =
    paths->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius);
  Vec3 sac{ 0, 0, 0 };
  double worst = 0.0;
  for (vtkIdType s = 0; s < surface->GetNumberOfPoints(); s += 3)
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
      sac = { q[0], q[1], q[2] };
    }
  }
  EXPECT_THROW(Vessels->PlaceRibbon(sac, WallPick(150)), RibbonPlacementError);
  EXPECT_FALSE(Vessels->IsOnVessel(sac));
  EXPECT_TRUE(Vessels->IsOnVessel(WallPick(30)));
  EXPECT_TRUE(Vessels->IsOnVessel(WallPick(150)));
  VesselSession empty;
  EXPECT_THROW(empty.PlaceRibbon(WallPick(30), WallPick(150)), RibbonPlacementError);
}

// The held stretch measured live follows the plan: its bend angle changes by the change of the
// angle between the ribbon's end tangents; after the release, the whole-plan comparison.
TEST_F(VesselSessionTest, HeldBranchFollowsTheBendAndThePlanIsCompared)
{
  const RibbonPlacement placed = Vessels->PlaceRibbon(WallPick(40), WallPick(160));
  ASSERT_TRUE(Vessels->HoldBranch(placed.ribbon, Session->GetSurface()));
  const HeldBranchMeasures before = Vessels->MeasureHeld();
  ASSERT_TRUE(before.valid);
  EXPECT_GT(before.length, Distance(placed.ribbon.start.position, placed.ribbon.end.position));
  EXPECT_GT(before.minRadius, 0.5 * placed.vesselRadius);
  EXPECT_LT(before.minRadius, 1.2 * placed.vesselRadius);
  // Unchanged by the identity warp.
  WarpParameters parameters = Session->GetParameters();
  parameters.radius = placed.suggestedRadius;
  ASSERT_TRUE(Session->SetParameters(parameters));
  ASSERT_TRUE(Session->Grab(placed.ribbon));
  const HeldBranchMeasures still = Vessels->MeasureHeld(LiveWarpOf(*Session));
  EXPECT_NEAR(still.bendAngle, before.bendAngle, 0.5);
  EXPECT_NEAR(still.length, before.length, 0.01 * before.length);
  EXPECT_NEAR(still.minRadius, before.minRadius, 0.01 * before.minRadius);
  // Turn the end frame by 30 degrees about the start normal, around the start.
  RibbonSpec bent = placed.ribbon;
  const Vec3 axis = Normalized(placed.ribbon.start.normal);
  const double angle = 30.0 / Degrees;
  const Vec3 arm = bent.end.position - bent.start.position;
  bent.end.position = bent.start.position + Rotate(axis, angle, arm);
  bent.end.tangent = Rotate(axis, angle, bent.end.tangent);
  bent.end.normal = Rotate(axis, angle, bent.end.normal);
  ASSERT_TRUE(Session->MoveFinal(bent)) << Session->GetLiveProblem();
  const double plan = TangentAngle(Session->GetFinalRibbon()) - TangentAngle(placed.ribbon);
  ASSERT_GT(std::abs(plan), 10.0);
  const HeldBranchMeasures live = Vessels->MeasureHeld(LiveWarpOf(*Session));
  ASSERT_TRUE(live.valid);
  EXPECT_NEAR(live.bendAngle - before.bendAngle, plan, 4.0);
  // The carried axis to the carried wall: positive, no wider than before this bend.
  EXPECT_GT(live.minRadius, 0.0);
  EXPECT_LT(live.minRadius, 1.05 * before.minRadius);
  std::cout << "held stretch: bend " << before.bendAngle << " -> " << live.bendAngle
            << " deg (plan " << plan << "), min radius " << before.minRadius << " -> "
            << live.minRadius << " mm\n";

  // The drawn centerline follows the bend: its points moved, the ribbon's start stays.
  auto warped = Vessels->WarpedPaths(LiveWarpOf(*Session));
  ASSERT_TRUE(warped);
  ASSERT_EQ(warped->GetNumberOfPoints(), Vessels->GetPaths()->GetNumberOfPoints());
  double moved = 0;
  for (vtkIdType i = 0; i < warped->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    warped->GetPoint(i, p);
    Vessels->GetPaths()->GetPoint(i, q);
    moved = std::max(moved, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
  }
  EXPECT_GT(moved, 0.2 * Distance(placed.ribbon.start.position, placed.ribbon.end.position));

  ASSERT_TRUE(Session->Release());
  EXPECT_FALSE(Vessels->IsUpToDate(*Session)) << "the committed surface changed";
  auto job = Vessels->BeginCenterlines(*Session);
  ASSERT_TRUE(job);
  job->Run({});
  std::string message;
  ASSERT_TRUE(Vessels->Finish(*job, message)) << message;
  ASSERT_TRUE(Vessels->GetComparison());
  const VesselComparison& comparison = *Vessels->GetComparison();
  ASSERT_FALSE(comparison.pairs.empty());
  double largestTurn = 0;
  for (const BranchChange& pair : comparison.pairs)
  {
    if (pair.beforeIndex >= 0 && pair.afterIndex >= 0)
    {
      const auto& b = comparison.before.branches[pair.beforeIndex];
      const auto& a = comparison.after.branches[pair.afterIndex];
      largestTurn = std::max(largestTurn,
        std::acos(std::clamp(Dot(Vec3{ b.endTangent[0], b.endTangent[1], b.endTangent[2] },
                               Vec3{ a.endTangent[0], a.endTangent[1], a.endTangent[2] }),
          -1.0,
          1.0)) *
          Degrees);
    }
  }
  EXPECT_GT(largestTurn, 5.0) << "a branch end turned with the bend";
  // Undo: back to the original surface, whose centerlines need no comparison.
  ASSERT_TRUE(Session->Undo());
  auto back = Vessels->BeginCenterlines(*Session);
  ASSERT_TRUE(back);
  back->Run({});
  ASSERT_TRUE(Vessels->Finish(*back, message)) << message;
  EXPECT_FALSE(Vessels->GetComparison());
}
