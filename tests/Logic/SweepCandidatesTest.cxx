// The candidates of a what-if sweep (issue 24) without OpenFOAM: --vary parsing, the values,
// a warp taken to a fraction of its motion along the screw, the content hash, and a row
// through its state.json and the summary.

#include "SweepCandidates.h"
#include "BenderErrors.h"
#include "Sweep.h"
#include "WarpPlanIO.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace bender;

namespace
{
constexpr double Pi = 3.14159265358979323846;

WarpPlan Bend90()
{
  return ReadWarpPlan(
    std::string(BENDER_SOURCE_DIR) + "/tests/data/conformance/bend90.bender.json");
}

double AngleDegrees(const Vec3& a, const Vec3& b)
{
  return std::acos(std::clamp(Dot(Normalized(a), Normalized(b)), -1.0, 1.0)) * 180.0 / Pi;
}
} // namespace

TEST(SweepCandidates, VaryIsParsedAndBadTextNamed)
{
  const SweepVary fraction = ParseSweepVary("fraction=0:1.5:7");
  EXPECT_EQ(fraction.parameter, SweepParameter::Fraction);
  EXPECT_EQ(fraction.count, 7);
  const std::vector<double> values = SweepValues(fraction);
  ASSERT_EQ(values.size(), 7u);
  EXPECT_EQ(values.front(), 0.0);
  EXPECT_EQ(values.back(), 1.5);
  for (std::size_t i = 1; i < values.size(); ++i)
  {
    EXPECT_NEAR(values[i] - values[i - 1], 0.25, 1e-12);
  }
  EXPECT_EQ(ParseSweepVary("radius=8:16:5").parameter, SweepParameter::Radius);
  EXPECT_EQ(SweepValues(ParseSweepVary("radius=8:8:1")), std::vector<double>{ 8.0 });
  for (const char* bad : { "fraction",
         "angle=0:1:3",
         "fraction=0:1",
         "fraction=0:1:x",
         "fraction=0:1:2.5",
         "fraction=0:1:0",
         "fraction=0:1:1",
         "fraction=0:9:3",
         "radius=0:4:3",
         "fraction=0:1:3:4" })
  {
    try
    {
      ParseSweepVary(bad);
      ADD_FAILURE() << bad << " was accepted";
    }
    catch (const InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(SweepCandidates, AFractionMovesTheEndsAlongTheScrew)
{
  const WarpSpec warp = Bend90().warps.front();
  // 0 and 1 are the plan's own frames, exactly.
  const WarpSpec none = WarpAtFraction(warp, 0.0);
  const WarpSpec all = WarpAtFraction(warp, 1.0);
  EXPECT_TRUE(SameRibbon(none.final, warp.initial));
  EXPECT_TRUE(SameRibbon(all.final, warp.final));
  EXPECT_TRUE(SameRibbon(none.initial, warp.initial));
  EXPECT_EQ(none.radius, warp.radius);
  // The end turns by 90 degrees in the plan: a fraction turns it by that fraction of 90.
  for (double f : { 0.25, 0.5, 0.75, 1.5 })
  {
    const RibbonEnd end = EndAtFraction(warp.initial.end, warp.final.end, f);
    EXPECT_NEAR(AngleDegrees(end.tangent, warp.initial.end.tangent), 90.0 * f, 1e-9) << f;
    EXPECT_NEAR(Norm(end.tangent), 1.0, 1e-12);
    EXPECT_NEAR(Dot(end.tangent, end.normal), 0.0, 1e-12);
    // One screw: half the motion, done twice, is the whole motion.
    const RibbonEnd half = EndAtFraction(warp.initial.end, warp.final.end, f / 2);
    const RibbonEnd twice = EndAtFraction(warp.initial.end, half, 2.0);
    EXPECT_NEAR(Distance(twice.position, end.position), 0.0, 1e-9) << f;
    EXPECT_NEAR(AngleDegrees(twice.tangent, end.tangent), 0.0, 1e-6) << f;
  }
  // The start does not move in this plan: every fraction keeps it.
  EXPECT_NEAR(Distance(EndAtFraction(warp.initial.start, warp.final.start, 0.7).position,
                warp.initial.start.position),
    0.0,
    1e-12);
  // Continuous at 1.
  const RibbonEnd nearOne = EndAtFraction(warp.initial.end, warp.final.end, 1.0 - 1e-9);
  EXPECT_NEAR(Distance(nearOne.position, warp.final.end.position), 0.0, 1e-6);
}

TEST(SweepCandidates, CandidatesOfAFractionARadiusAndPlans)
{
  const WarpPlan plan = Bend90();
  const auto fractions = MakeSweepCandidates(plan, "bend90", ParseSweepVary("fraction=0:1:3"));
  ASSERT_EQ(fractions.size(), 3u);
  EXPECT_TRUE(fractions[0].original);
  EXPECT_FALSE(fractions[1].original);
  EXPECT_EQ(fractions[2].id, "c02");
  EXPECT_TRUE(SameRibbon(fractions[2].plan.warps[0].final, plan.warps[0].final));
  EXPECT_TRUE(fractions[1].plan.cfdSteps.empty());

  const auto radii = MakeSweepCandidates(plan, "bend90", ParseSweepVary("radius=10:20:3"));
  ASSERT_EQ(radii.size(), 4u);
  EXPECT_EQ(radii[0].id, "original");
  EXPECT_TRUE(radii[0].original);
  EXPECT_EQ(radii[3].plan.warps[0].radius, 20.0);
  EXPECT_TRUE(SameRibbon(radii[3].plan.warps[0].final, plan.warps[0].final));

  const auto plans = MakePlanCandidates({ plan, plan }, { "a.json", "b.json" });
  ASSERT_EQ(plans.size(), 3u);
  EXPECT_TRUE(plans[0].original);
  EXPECT_EQ(plans[2].planName, "b.json");

  WarpPlan empty;
  EXPECT_THROW(MakeSweepCandidates(empty, "empty", ParseSweepVary("fraction=0:1:2")), InputError);
  EXPECT_THROW(MakePlanCandidates({ empty }, { "empty" }), InputError);
}

TEST(SweepCandidates, TheHashChangesWithEveryInputAndOnlyThen)
{
  const auto candidates = MakeSweepCandidates(Bend90(), "bend90", ParseSweepVary("fraction=0:1:3"));
  const CfdStep step;
  const CfdCaseOptions settings;
  const std::string surface = "solid tube\nendsolid tube\n";
  const std::string h = SweepCandidateHash(surface, candidates[1], step, settings);
  EXPECT_EQ(h.size(), 32u);
  EXPECT_EQ(h, SweepCandidateHash(surface, candidates[1], step, settings));
  EXPECT_NE(h, SweepCandidateHash(surface, candidates[2], step, settings));
  EXPECT_NE(h, SweepCandidateHash(surface + " ", candidates[1], step, settings));
  CfdStep otherStep;
  otherStep.outletExtension = 3.0;
  EXPECT_NE(h, SweepCandidateHash(surface, candidates[1], otherStep, settings));
  CfdCaseOptions otherSettings;
  otherSettings.iterations = 10;
  EXPECT_NE(h, SweepCandidateHash(surface, candidates[1], step, otherSettings));
  // Where the case is written is not an input.
  CfdCaseOptions elsewhere;
  elsewhere.caseDirectory = "/elsewhere";
  EXPECT_EQ(h, SweepCandidateHash(surface, candidates[1], step, elsewhere));
}

TEST(SweepCandidates, ARowRoundTripsAndTheSummaryNamesTheMissing)
{
  SweepRow solved;
  solved.id = "c01";
  solved.parameter = "fraction";
  solved.value = 0.5;
  solved.planName = "bend90.bender.json";
  solved.state = "solved";
  solved.hash = "0123456789abcdef0123456789abcdef";
  solved.measures.bendAngle = 44.5;
  solved.measures.lengthChange = -3.25;
  solved.pressureDrop = 12.5;
  solved.outlets = { { "outlet_1", 100.0, 12.5, 90.0 } };
  solved.meshCells = 12345;
  solved.iterations = 321;
  solved.converged = true;
  const SweepRow back = SweepRowFromJson(SweepRowToJson(solved), "state.json");
  EXPECT_EQ(back.id, solved.id);
  EXPECT_EQ(back.parameter, solved.parameter);
  EXPECT_EQ(back.value, solved.value);
  EXPECT_EQ(back.hash, solved.hash);
  EXPECT_EQ(back.measures.bendAngle, solved.measures.bendAngle);
  EXPECT_TRUE(std::isnan(back.measures.minRadius));
  EXPECT_EQ(back.pressureDrop, solved.pressureDrop);
  ASSERT_EQ(back.outlets.size(), 1u);
  EXPECT_EQ(back.outlets[0].name, "outlet_1");
  EXPECT_EQ(back.outlets[0].flowRate, 90.0);
  EXPECT_EQ(back.meshCells, solved.meshCells);
  EXPECT_EQ(back.iterations, solved.iterations);
  EXPECT_TRUE(back.converged);
  EXPECT_EQ(SweepRowToJson(back), SweepRowToJson(solved));
  EXPECT_THROW(SweepRowFromJson("{", "state.json"), InputError);

  SweepRow rejected = solved;
  rejected.id = "c02";
  rejected.state = "rejected";
  rejected.reason = "the warp folds the surface (3 flipped triangles)";
  const std::string csv = SweepSummaryCsv({ solved, rejected });
  EXPECT_NE(csv.find("split_outlet_1_percent"), std::string::npos);
  EXPECT_NE(csv.find(rejected.reason), std::string::npos);
  const std::string json = SweepSummaryJson({ solved, rejected }, "fraction");
  EXPECT_NE(json.find("\"missing\""), std::string::npos);
  EXPECT_NE(json.find(rejected.reason), std::string::npos);
  // A row not solved carries no numbers.
  EXPECT_EQ(csv.find("c02,fraction,0.5,bend90.bender.json,no,rejected"), csv.find("c02"));
}
