#include "WarpHistory.h"
#include "LogicTestUtilities.h"

#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

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
