// "Reduce R" (issue 22, item 6): the radius proposed is the largest of those tried that passes
// the commit guard's own checks (both guards), never below the vessel's radius; none is
// proposed when none passes.
#include "RadiusSearch.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "LogicTestUtilities.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

using namespace bender;
using bender::test::Bent;
using bender::test::MakeTube;
using bender::test::StraightRibbon;

namespace
{

constexpr double TubeRadius = 3.0;

WarpSpec Warp(double degrees, double radius)
{
  WarpSpec warp;
  warp.initial = StraightRibbon(20, 40);
  warp.final = Bent(warp.initial, degrees);
  warp.radius = radius;
  return warp;
}

RadiusSearchOptions Options(bool lumen)
{
  RadiusSearchOptions options;
  options.lowest = TubeRadius;
  options.check.spaceInversionRule = false;
  options.check.lumen.enabled = lumen;
  return options;
}

// Every radius tried lies in [lowest, R), largest first.
void ExpectTriedWithinTheRange(const RadiusSearchResult& result, double radius, double lowest)
{
  for (std::size_t i = 0; i < result.tried.size(); ++i)
  {
    EXPECT_LT(result.tried[i].first, radius);
    EXPECT_GE(result.tried[i].first, lowest * (1 - 1e-12));
    if (i > 0)
    {
      EXPECT_LT(result.tried[i].first, result.tried[i - 1].first);
    }
  }
}

}

TEST(RadiusSearch, TheRadiusFoundPassesTheSameChecksAndLargerOnesTriedDoNot)
{
  auto tube = MakeTube(0, 60, TubeRadius);
  // A crushing bend with a large R (the tube folds onto itself).
  const WarpSpec warp = Warp(170, 12);
  for (bool lumen : { false, true })
  {
    const RadiusSearchOptions options = Options(lumen);
    const RadiusSearchResult result = FindPassingRadius(tube, warp, options);
    ASSERT_FALSE(result.tried.empty());
    ExpectTriedWithinTheRange(result, warp.radius, options.lowest);
    if (!result.found)
    {
      EXPECT_FALSE(result.check.Passed());
      continue;
    }
    EXPECT_EQ(result.tried.back().first, result.radius);
    // Checked again from scratch, the bend at that radius passes both guards.
    WarpSpec reduced = warp;
    reduced.radius = result.radius;
    const CommitCheck check = CheckCommit(tube, ApplyWarp(tube, reduced), reduced, options.check);
    EXPECT_TRUE(check.Passed()) << check.Summary();
    // Every larger radius tried failed.
    for (std::size_t i = 0; i + 1 < result.tried.size(); ++i)
    {
      EXPECT_NE(result.tried[i].second, "no problems");
    }
  }
}

TEST(RadiusSearch, AMildBendPassesAtTheFirstRadiusTried)
{
  // The tube's free end swung by 20 degrees about the ribbon's start, a plateau wider than the
  // tube at every radius tried: the cross-sections move as a whole, nothing is left behind
  // the ribbon's end to shear.
  auto tube = MakeTube(0, 60, TubeRadius);
  WarpSpec warp;
  warp.initial = StraightRibbon(35, 60);
  warp.final = Bent(warp.initial, 20);
  warp.radius = 9;
  warp.decay.shape = DecayShape::Plateau;
  warp.decay.plateau = 0.6;
  const RadiusSearchResult result = FindPassingRadius(tube, warp, Options(true));
  ASSERT_TRUE(result.found) << (result.tried.empty() ? "" : result.tried.front().second);
  ASSERT_EQ(result.tried.size(), 1u) << result.tried.front().second;
  EXPECT_LT(result.radius, warp.radius);
  EXPECT_GE(result.radius, TubeRadius);
}

TEST(RadiusSearch, NothingBelowTheVesselsRadius)
{
  auto tube = MakeTube(0, 60, TubeRadius);
  RadiusSearchOptions options = Options(false);
  const RadiusSearchResult none = FindPassingRadius(tube, Warp(170, TubeRadius), options);
  EXPECT_FALSE(none.found);
  EXPECT_TRUE(none.tried.empty());
  options.lowest = 0.0;
  EXPECT_THROW(FindPassingRadius(tube, Warp(170, 12), options), InputError);
  options.lowest = TubeRadius;
  EXPECT_THROW(FindPassingRadius(nullptr, Warp(170, 12), options), InputError);
}
