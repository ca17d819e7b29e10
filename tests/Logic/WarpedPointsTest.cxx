// Points carried through a plan's warps (WarpedPoints.h): back and forth they return where they
// were, and a Prepare for CFD step chosen on the bent shape cuts the original at the same ends
// (the Flow panel's original after "bend, then Prepare for CFD").

#include "WarpedPoints.h"
#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "BenderSession.h"
#include "FlowStudy.h"
#include "LogicTestUtilities.h"
#include "PrepareForCfd.h"

#include <gtest/gtest.h>

#include <vtkPolyData.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

using namespace bender;

namespace
{
std::vector<Vec3*> Pointers(std::vector<Vec3>& points)
{
  std::vector<Vec3*> out;
  for (Vec3& p : points)
  {
    out.push_back(&p);
  }
  return out;
}
} // namespace

TEST(WarpedPoints, BackThenForwardAndForwardThenBackReturnEveryPoint)
{
  // Two chained swings that do not fold the space (their motion is gentle for their R, as a
  // committed bend's is); points inside both regions of influence, at their edge and outside.
  const std::vector<WarpSpec> warps = { test::Swing(0, 15, 25, 10), test::Swing(-10, 5, -20, 9) };
  std::vector<Vec3> given;
  for (double x = -16; x <= 24; x += 4)
  {
    for (double r : { 0.0, 3.0, 5.0, 7.9 })
    {
      given.push_back({ x, r, 0.5 * r });
    }
  }
  std::vector<Vec3> there = given;
  CarryForward(Pointers(there), warps, warps.size());
  double moved = 0.0;
  for (std::size_t i = 0; i < given.size(); ++i)
  {
    moved = std::max(moved, Distance(given[i], there[i]));
  }
  EXPECT_GT(moved, 5.0) << "the warps must move some points for the test to mean anything";

  // Back: a point the warps carry there. Along the wires (x in [-8, 12]) the warps are one to
  // one, so it is the point given; past a wire's end (every point there is bound to the end
  // frame) they need not be, and any point they carry there is right.
  std::vector<Vec3> back = there;
  CarryBack(Pointers(back), warps, warps.size());
  std::vector<Vec3> again = back;
  CarryForward(Pointers(again), warps, warps.size());
  for (std::size_t i = 0; i < given.size(); ++i)
  {
    EXPECT_LT(Distance(again[i], there[i]), 1e-6) << "point " << i;
    if (given[i].x >= -8 && given[i].x <= 12)
    {
      EXPECT_LT(Distance(back[i], given[i]), 1e-5) << "point " << i;
    }
  }
  // And the other way: a point given after the warps goes back, then forward to itself.
  std::vector<Vec3> after = given;
  CarryBack(Pointers(after), warps, warps.size());
  CarryForward(Pointers(after), warps, warps.size());
  for (std::size_t i = 0; i < given.size(); ++i)
  {
    EXPECT_LT(Distance(after[i], given[i]), 1e-6) << "point " << i;
  }
  // Only the first warp: count is honoured.
  std::vector<Vec3> one = given;
  CarryForward(Pointers(one), warps, 1);
  std::vector<Vec3> both = given;
  CarryForward(Pointers(both), warps, 2);
  double differ = 0.0;
  for (std::size_t i = 0; i < given.size(); ++i)
  {
    differ = std::max(differ, Distance(one[i], both[i]));
  }
  EXPECT_GT(differ, 1.0);
}

TEST(WarpedPoints, APrepareStepChosenOnTheBentShapeCutsTheOriginalAtTheSameEnds)
{
  // The right end (x = 30) lies in the swing's region of influence: the bend moves it.
  const vtkSmartPointer<vtkPolyData> tube = test::MakeTube(-30, 30, 4, 61, 32);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(tube, "tube"));
  ASSERT_TRUE(session.ApplyWarp(test::Swing(0, 28, 30, 8)));

  // Prepare for CFD on the bent shape, as the Export panel does: every end written out.
  CfdStep step;
  step.inletExtension = 2.0;
  step.outletExtension = 1.0;
  const PrepareForCfdResult bent = ApplyCfdStep(session.GetSurface(), step);
  const CfdStep resolved = ResolvedCfdStep(step, bent);
  ASSERT_TRUE(session.CommitCfdStep(resolved, bent.surface, false));
  double farthest = 0.0;
  for (const CfdStepEnd& end : resolved.ends)
  {
    farthest = std::max(farthest, std::abs(end.position.y));
  }
  ASSERT_GT(farthest, 2.0) << "the bend must move an end off the tube's axis";

  FlowStudyInput input;
  input.first = tube;
  input.plan = session.GetPlan();
  input.current = session.GetSurface();
  input.name = "tube";
  const LabelledSurface original = FlowReadySurface(input, FlowShape::Original);
  const LabelledSurface current = FlowReadySurface(input, FlowShape::Current);
  // The same ends, each with the same role (tables in any order: the tube's ends are alike).
  const auto roles = [](const LabelledSurface& labelled)
  {
    std::vector<std::pair<std::string, int>> out;
    for (const PatchLabel& patch : labelled.patches)
    {
      out.emplace_back(patch.name, static_cast<int>(patch.type));
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(roles(original), roles(current));

  // The original is the step with its positions carried back, applied to the straight tube:
  // its ends are cut on the tube's axis, as far from each end as on the bent shape.
  CfdStep back = resolved;
  CarryBack(CfdStepPoints(back), input.plan.warps, resolved.afterWarps);
  back.afterWarps = 0;
  const PrepareForCfdResult straight = ApplyCfdStep(tube, back);
  EXPECT_EQ(test::MaxDifference(straight.surface, original.surface), 0.0);
  ASSERT_EQ(straight.ends.size(), bent.ends.size());
  for (const CfdEnd& end : bent.ends)
  {
    const auto same = std::find_if(straight.ends.begin(),
      straight.ends.end(),
      [&end](const CfdEnd& e) { return e.name == end.name; });
    ASSERT_NE(same, straight.ends.end()) << end.name;
    EXPECT_EQ(same->type, end.type) << end.name;
    EXPECT_LT(std::abs(same->clipCentre[1]), 0.05) << end.name;
    EXPECT_LT(std::abs(same->clipCentre[2]), 0.05) << end.name;
    EXPECT_NEAR(same->clipDistance, end.clipDistance, 0.05) << end.name;
    // The same physical end: the bend moved only the end at +x.
    EXPECT_EQ(same->clipCentre[0] > 0, end.clipCentre[0] > 0) << end.name;
  }
}
