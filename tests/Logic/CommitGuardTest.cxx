// The commit guard (issue 12, item 4): before a warp is committed, the region it changed is
// checked (flipped triangles, new self-intersections, the space-inversion rule R < r_min); a
// failed check holds the commit with the problem triangles named, until the user reduces R,
// cancels or keeps it. One r_min everywhere, cleared when a new ribbon is placed; the ribbon
// returns onto the surface after a cancel or an undo; unsaved work is known.
#include "CommitGuard.h"
#include "ApplyPlan.h"
#include "BenderMeshCheck.h"
#include "BenderSession.h"
#include "LogicTestUtilities.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

using namespace bender;
using bender::test::Bent;
using bender::test::MakeTube;
using bender::test::MaxDifference;
using bender::test::StraightRibbon;

namespace
{

WarpSpec Warp(const RibbonSpec& initial, const RibbonSpec& final, double radius)
{
  WarpSpec warp;
  warp.initial = initial;
  warp.final = final;
  warp.radius = radius;
  return warp;
}

}

TEST(CommitGuard, AMildBendPasses)
{
  auto tube = MakeTube(0, 60, 3);
  const WarpSpec warp = Warp(StraightRibbon(20, 40), Bent(StraightRibbon(20, 40), 30), 6);
  auto after = ApplyWarp(tube, warp);
  const CommitCheck check = CheckCommit(tube, after, warp);
  EXPECT_TRUE(check.checked);
  EXPECT_TRUE(check.Passed()) << check.Summary();
  EXPECT_GT(check.movedPoints, 100);
  EXPECT_LT(check.movedPoints, tube->GetNumberOfPoints());
  EXPECT_GT(check.regionTriangles, 0);
  EXPECT_EQ(check.flippedTriangles, 0);
  EXPECT_EQ(check.newSelfIntersections, 0);
  EXPECT_FALSE(check.spaceInversionRisk);
  EXPECT_TRUE(check.problemCells.empty());
  EXPECT_EQ(check.Summary(), "no problems");
}

TEST(CommitGuard, ACrushingWarpFailsAndNamesTheTriangles)
{
  // The end swung by 170 degrees with R = 10 (the tube's radius is 3): the tube folds onto
  // itself.
  auto tube = MakeTube(0, 60, 3);
  const WarpSpec warp = Warp(StraightRibbon(20, 40), Bent(StraightRibbon(20, 40), 170), 10);
  auto after = ApplyWarp(tube, warp);
  CommitCheckOptions options;
  options.spaceInversionRule = false; // only what is measured on the surface
  const CommitCheck check = CheckCommit(tube, after, warp, options);
  EXPECT_FALSE(check.Passed());
  EXPECT_GT(check.flippedTriangles, 0) << check.Summary();
  EXPECT_GT(check.newSelfIntersections, 0) << check.Summary();
  ASSERT_FALSE(check.problemCells.empty());
  EXPECT_TRUE(std::is_sorted(check.problemCells.begin(), check.problemCells.end()));
  // The triangles named lie in the changed region, and the same triangles are drawn.
  ASSERT_TRUE(check.problemTriangles);
  EXPECT_EQ(
    check.problemTriangles->GetNumberOfPolys(), static_cast<vtkIdType>(check.problemCells.size()));
  for (vtkIdType cell : check.problemCells)
  {
    double before[3];
    tube->GetPoint(tube->GetCell(cell)->GetPointId(0), before);
    EXPECT_GT(before[0], 20.0 - 10.0 - 1e-9);
    EXPECT_LT(before[0], 40.0 + 10.0 + 1e-9);
  }
  // The export check counts the same problems on the whole surface (the tube crossed nothing
  // before).
  const MeshCheckReport report = CheckMesh(after, tube);
  EXPECT_EQ(report.flippedTriangles, check.flippedTriangles);
  EXPECT_EQ(report.selfIntersections, check.newSelfIntersections);
}

TEST(CommitGuard, TheSpaceInversionRuleQuotesTheOneMinimumRadius)
{
  auto tube = MakeTube(0, 60, 3);
  const WarpSpec warp = Warp(StraightRibbon(20, 40), Bent(StraightRibbon(20, 40), 150), 6);
  auto after = ApplyWarp(tube, warp);
  const CommitCheck check = CheckCommit(tube, after, warp);
  EXPECT_TRUE(check.spaceInversionRisk);
  EXPECT_LT(check.minimumRadius, 6.0);
  EXPECT_FALSE(check.Passed());
  std::ostringstream rmin;
  rmin.precision(3);
  rmin << check.minimumRadius;
  EXPECT_NE(check.Summary().find("r_min = " + rmin.str()), std::string::npos) << check.Summary();
}

TEST(CommitGuard, MismatchedSurfacesAreRefused)
{
  auto tube = MakeTube(0, 60, 3);
  auto other = MakeTube(0, 60, 3, 41, 16);
  EXPECT_THROW(CheckCommit(tube, other, Warp(StraightRibbon(20, 40), StraightRibbon(20, 40), 6)),
    std::exception);
}

class GuardedSessionTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Tube = MakeTube(0, 60, 3);
    ASSERT_TRUE(this->Session.SetSurface(this->Tube, "tube"));
    WarpParameters parameters;
    parameters.radius = 6.0;
    ASSERT_TRUE(this->Session.SetParameters(parameters));
  }
  BenderSession Session;
  vtkSmartPointer<vtkPolyData> Tube;
};

TEST_F(GuardedSessionTest, AFailedCheckHoldsTheCommitUntilTheUserKeepsIt)
{
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 170)));
  EXPECT_FALSE(this->Session.Release());
  // Held: nothing committed, the grab and the live warp go on, the problem is named.
  EXPECT_TRUE(this->Session.IsCommitHeld());
  EXPECT_EQ(this->Session.GetState(), GrabState::Grabbed);
  EXPECT_EQ(this->Session.GetHistoryPosition(), 0u);
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), this->Tube), 0.0);
  EXPECT_GT(MaxDifference(this->Session.GetDisplaySurface(), this->Tube), 1.0);
  const CommitCheck& check = this->Session.GetHeldCheck();
  EXPECT_FALSE(check.Passed());
  EXPECT_FALSE(check.problemCells.empty());
  EXPECT_FALSE(this->Session.GetMessages().empty());
  EXPECT_NE(this->Session.GetMessages().back().text.find("Commit held"), std::string::npos);
  // Keep: committed as it was computed.
  ASSERT_TRUE(this->Session.KeepHeldCommit());
  EXPECT_FALSE(this->Session.IsCommitHeld());
  EXPECT_EQ(this->Session.GetHistoryPosition(), 1u);
  auto expected = ApplyWarp(this->Tube, this->Session.GetPlan().warps.front());
  EXPECT_LE(MaxDifference(this->Session.GetSurface(), expected), 1e-12);
  EXPECT_FALSE(this->Session.KeepHeldCommit()); // nothing held any more
}

TEST_F(GuardedSessionTest, ReducingRDropsTheHeldResultAndTheRetryPasses)
{
  // A 90 degree swing with R = 6: r_min of the final wire (4.2 mm) is below R, although the
  // surface shows no flip yet: held only when the rule alone holds (off by default).
  const RibbonSpec initial = StraightRibbon(20, 40);
  {
    BenderSession unruled;
    ASSERT_TRUE(unruled.SetSurface(this->Tube, "tube"));
    ASSERT_TRUE(unruled.SetParameters(this->Session.GetParameters()));
    ASSERT_TRUE(unruled.Grab(initial));
    ASSERT_TRUE(unruled.MoveFinal(Bent(initial, 90)));
    EXPECT_TRUE(unruled.GetSpaceInversionRisk());
    EXPECT_TRUE(unruled.Release());
    EXPECT_EQ(unruled.GetHistoryPosition(), 1u);
  }
  this->Session.SetCommitGuardRule(true);
  ASSERT_TRUE(this->Session.Grab(initial));
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 90)));
  EXPECT_FALSE(this->Session.Release());
  ASSERT_TRUE(this->Session.IsCommitHeld());
  const double rmin = this->Session.GetHeldCheck().minimumRadius;
  EXPECT_DOUBLE_EQ(rmin, this->Session.GetMinimumRadius());
  WarpParameters parameters = this->Session.GetParameters();
  parameters.radius = 0.9 * rmin;
  ASSERT_TRUE(this->Session.SetParameters(parameters));
  EXPECT_FALSE(this->Session.IsCommitHeld());
  EXPECT_FALSE(this->Session.GetSpaceInversionRisk());
  EXPECT_TRUE(this->Session.Release()) << this->Session.GetMessages().back().text;
  EXPECT_EQ(this->Session.GetHistoryPosition(), 1u);
  EXPECT_DOUBLE_EQ(this->Session.GetPlan().warps[0].radius, 0.9 * rmin);
}

TEST_F(GuardedSessionTest, CancellingAHeldCommitPutsTheRibbonBackOnTheSurface)
{
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 170)));
  EXPECT_FALSE(this->Session.Release());
  ASSERT_TRUE(this->Session.IsCommitHeld());
  this->Session.CancelGrab("cancelled by the user");
  EXPECT_FALSE(this->Session.IsCommitHeld());
  EXPECT_EQ(this->Session.GetState(), GrabState::Idle);
  EXPECT_EQ(this->Session.GetHistoryPosition(), 0u);
  EXPECT_EQ(MaxDifference(this->Session.GetDisplaySurface(), this->Tube), 0.0);
  ASSERT_TRUE(this->Session.GetRibbon());
  EXPECT_EQ(this->Session.GetRibbon()->end.position.x, 40.0);
}

TEST_F(GuardedSessionTest, TheRibbonFollowsUndoAndRedo)
{
  const RibbonSpec initial = StraightRibbon(20, 40);
  const RibbonSpec bent = Bent(initial, 30);
  ASSERT_TRUE(this->Session.Grab(initial));
  ASSERT_TRUE(this->Session.MoveFinal(bent));
  ASSERT_TRUE(this->Session.Release());
  ASSERT_TRUE(this->Session.GetRibbon());
  EXPECT_LT(Distance(this->Session.GetRibbon()->end.position, bent.end.position), 1e-12);
  ASSERT_TRUE(this->Session.Undo());
  EXPECT_LT(Distance(this->Session.GetRibbon()->end.position, initial.end.position), 1e-12);
  ASSERT_TRUE(this->Session.Redo());
  EXPECT_LT(Distance(this->Session.GetRibbon()->end.position, bent.end.position), 1e-12);
  // A new surface has no ribbon.
  ASSERT_TRUE(this->Session.SetSurface(this->Tube, "tube again"));
  EXPECT_FALSE(this->Session.GetRibbon());
}

TEST_F(GuardedSessionTest, OneMinimumRadiusClearedWhenANewRibbonIsPlaced)
{
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 150)));
  ASSERT_TRUE(this->Session.GetSpaceInversionRisk());
  // The warning quotes the value the panel shows.
  std::ostringstream rmin;
  rmin.precision(3);
  rmin << this->Session.GetMinimumRadius();
  EXPECT_NE(
    this->Session.GetSpaceInversionWarning().find("r_min = " + rmin.str()), std::string::npos)
    << this->Session.GetSpaceInversionWarning();
  this->Session.CancelGrab("test");
  // A new straight ribbon: no r_min, no warning.
  ASSERT_TRUE(this->Session.PlaceRibbon(StraightRibbon(10, 30)));
  EXPECT_FALSE(this->Session.GetSpaceInversionRisk());
  EXPECT_TRUE(this->Session.GetSpaceInversionWarning().empty());
  EXPECT_FALSE(
    std::isfinite(this->Session.GetMinimumRadius()) && this->Session.GetMinimumRadius() < 1e6);
  // An invalid ribbon is refused with a message.
  RibbonSpec invalid = StraightRibbon(10, 30);
  invalid.end.position = invalid.start.position;
  EXPECT_FALSE(this->Session.PlaceRibbon(invalid));
  EXPECT_EQ(this->Session.GetMessages().back().severity, MessageSeverity::Error);
}

TEST_F(GuardedSessionTest, UnsavedWorkIsKnownUntilThePlanIsSaved)
{
  EXPECT_FALSE(this->Session.HasUnsavedChanges());
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  EXPECT_TRUE(this->Session.HasUnsavedChanges()); // a bend under way
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 30)));
  ASSERT_TRUE(this->Session.Release());
  EXPECT_TRUE(this->Session.HasUnsavedChanges());
  const std::string plan = test::TemporaryFolder("guard-unsaved") + "/plan.bender.json";
  ASSERT_TRUE(this->Session.SavePlan(plan));
  EXPECT_FALSE(this->Session.HasUnsavedChanges());
  ASSERT_TRUE(this->Session.Undo());
  EXPECT_TRUE(this->Session.HasUnsavedChanges());
  this->Session.MarkSaved(); // discarded explicitly
  EXPECT_FALSE(this->Session.HasUnsavedChanges());
}
