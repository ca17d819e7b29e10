#include "WarpHistory.h"
#include "LogicTestUtilities.h"

#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace bender;

TEST(WarpHistory, KeepsDeepCopiesAndTruncatesRedo)
{
  auto original = test::MakeTube(0, 10, 1, 5, 8);
  WarpHistory history;
  EXPECT_TRUE(history.Empty());
  EXPECT_EQ(history.Current(), nullptr);
  history.Reset(original);
  // Changing the caller's surface afterwards does not change the history.
  original->GetPoints()->SetPoint(0, 100, 100, 100);
  double p[3];
  history.Current()->GetPoint(0, p);
  EXPECT_EQ(p[0], 0.0);

  auto moved = test::MakeTube(0, 10, 2, 5, 8);
  WarpSpec warp;
  warp.radius = 3;
  history.Commit(warp, moved);
  EXPECT_TRUE(history.CanUndo());
  EXPECT_FALSE(history.CanRedo());
  EXPECT_EQ(history.CommittedWarps().size(), 1u);
  ASSERT_TRUE(history.Undo());
  EXPECT_EQ(history.CommittedWarps().size(), 0u);
  EXPECT_TRUE(history.CanRedo());
  warp.radius = 4;
  history.Commit(warp, moved);
  EXPECT_FALSE(history.CanRedo());
  ASSERT_EQ(history.CommittedWarps().size(), 1u);
  EXPECT_EQ(history.CommittedWarps()[0].radius, 4.0);
  EXPECT_EQ(history.Size(), 1u);
  EXPECT_FALSE(history.Redo());
}

// A Prepare for CFD step is a step like a warp (issue 22): undone and redone with the exact
// surfaces, in the committed plan at its place among the warps, and the surface the current one
// is compared with (flips, ghost, vessels) is the one it made, not the unclipped one.
TEST(WarpHistory, APrepareForCfdStepIsAStepOfThePlan)
{
  auto first = test::MakeTube(0, 10, 1, 5, 8);
  auto bent = test::MakeTube(0, 10, 1.5, 5, 8);
  auto prepared = test::MakeTube(0, 12, 1, 7, 8); // other points and cells
  auto bentAgain = test::MakeTube(0, 12, 2, 7, 8);
  WarpHistory history;
  history.Reset(first);
  WarpSpec warp;
  warp.radius = 3;
  history.Commit(warp, bent);
  EXPECT_EQ(history.Original(), history.First());
  CfdStep step;
  step.afterWarps = 7; // set by the history: the warps before it
  step.names.push_back({ { 1, 2, 3 }, "aorta", true });
  history.Commit(step, prepared);
  EXPECT_EQ(history.Position(), 2u);
  EXPECT_EQ(history.Original(), history.Current()); // a new start for the comparisons
  EXPECT_NE(history.First(), history.Original());
  EXPECT_EQ(history.CfdStepOf(2)->names.front().name, "aorta");
  EXPECT_EQ(history.WarpOf(2), nullptr);
  ASSERT_NE(history.WarpOf(1), nullptr);
  EXPECT_EQ(history.Previous()->GetNumberOfPoints(), bent->GetNumberOfPoints());
  warp.radius = 5;
  history.Commit(warp, bentAgain);
  EXPECT_EQ(history.Original()->GetNumberOfPoints(), prepared->GetNumberOfPoints());

  const WarpPlan plan = history.CommittedPlan();
  ASSERT_EQ(plan.warps.size(), 2u);
  ASSERT_EQ(plan.cfdSteps.size(), 1u);
  EXPECT_EQ(plan.cfdSteps[0].afterWarps, 1u);
  EXPECT_EQ(plan.warps[1].radius, 5.0);
  EXPECT_EQ(history.CommittedWarps().size(), 2u);
  // From step 1: the CFD step comes first there.
  EXPECT_EQ(history.CommittedPlan(1).cfdSteps[0].afterWarps, 0u);
  EXPECT_EQ(history.CommittedPlan(1).warps.size(), 1u);

  // Undo twice: back before the step, to the bent surface with its exact points.
  ASSERT_TRUE(history.Undo());
  ASSERT_TRUE(history.Undo());
  EXPECT_EQ(history.Current()->GetNumberOfPoints(), bent->GetNumberOfPoints());
  double p[3], q[3];
  history.Current()->GetPoint(3, p);
  bent->GetPoint(3, q);
  EXPECT_EQ(p[1], q[1]);
  EXPECT_EQ(history.Original(), history.First());
  EXPECT_TRUE(history.CommittedPlan().cfdSteps.empty());
  ASSERT_TRUE(history.Redo());
  EXPECT_EQ(history.Current()->GetNumberOfPoints(), prepared->GetNumberOfPoints());
  EXPECT_EQ(history.CommittedPlan().cfdSteps.size(), 1u);
}

// Issue 25: a long session's history stays within its memory limit (the oldest steps' surfaces
// let go, undo stopping at the oldest kept), while the plan keeps every step and the surfaces
// the window compares with (the first, and those around a Prepare for CFD step) stay.
TEST(WarpHistory, MemoryStaysWithinTheLimitOverHundredsOfSteps)
{
  auto first = test::MakeTube(0, 10, 1, 21, 16);
  WarpHistory history;
  history.Reset(first);
  const std::size_t one = history.MemoryBytes();
  ASSERT_GT(one, 0u);
  const std::size_t limit = 8 * one;
  history.SetMemoryLimit(limit);
  // At most the limit, plus what is never let go: the first surface, the current one, the one
  // before it, and the two around the Prepare for CFD step.
  const std::size_t bound = limit + 5 * one;
  CfdStep step;
  step.names.push_back({ { 1, 2, 3 }, "aorta", true });
  std::size_t atCap = 0;
  for (int i = 1; i <= 300; ++i)
  {
    auto result = test::MakeTube(0, 10, 1 + 0.001 * i, 21, 16);
    WarpSpec warp;
    warp.radius = i;
    if (i == 40)
    {
      history.Commit(step, result);
    }
    else
    {
      history.Commit(warp, result);
    }
    // Undo and redo on the way, as a user does.
    if (i % 7 == 0)
    {
      ASSERT_TRUE(history.Undo());
      ASSERT_TRUE(history.Redo());
    }
    ASSERT_LE(history.MemoryBytes(), bound) << "step " << i;
    if (i == 100)
    {
      atCap = history.MemoryBytes();
    }
  }
  // Past the limit it does not grow.
  EXPECT_LE(history.MemoryBytes(), atCap);
  EXPECT_EQ(history.Position(), 300u);
  const WarpPlan plan = history.CommittedPlan();
  EXPECT_EQ(plan.warps.size(), 299u);
  ASSERT_EQ(plan.cfdSteps.size(), 1u);
  EXPECT_EQ(plan.cfdSteps[0].afterWarps, 39u);
  ASSERT_NE(history.First(), nullptr);
  EXPECT_EQ(history.First()->GetNumberOfPoints(), first->GetNumberOfPoints());
  ASSERT_NE(history.Original(), nullptr);

  // Undo goes back as far as surfaces are kept, each restored exactly, then stops.
  const std::size_t undoable = history.UndoableSteps();
  EXPECT_GE(undoable, 2u);
  EXPECT_LT(undoable, 300u);
  for (std::size_t k = 0; k < undoable; ++k)
  {
    ASSERT_TRUE(history.Undo()) << k;
    double p[3];
    history.Current()->GetPoint(1, p);
    const double radius = 1 + 0.001 * double(history.Position());
    EXPECT_NEAR(std::hypot(p[1], p[2]), radius, 1e-12);
  }
  EXPECT_FALSE(history.CanUndo());
  EXPECT_FALSE(history.Undo());
  EXPECT_EQ(history.Position(), 300u - undoable);
  while (history.Redo())
  {
  }
  EXPECT_EQ(history.Position(), 300u);

  // With no room at all, all that may go goes: one step can still be undone.
  history.SetMemoryLimit(0);
  EXPECT_LE(history.MemoryBytes(), 5 * one);
  EXPECT_EQ(history.UndoableSteps(), 1u);
  EXPECT_NE(history.Original(), nullptr);
  EXPECT_EQ(history.CommittedPlan().warps.size(), 299u);
}
