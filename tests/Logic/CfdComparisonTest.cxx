// The comparison table of two flow results (CfdComparison.h) on hand-made results: matched
// outlets, outlets of one case only, the highlight rule, antisymmetry, the JSON and the text.

#include "CfdComparison.h"
#include "CfdFlowResults.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

namespace
{
bender::CfdEndFlow End(const std::string& name,
  bender::PatchType role,
  double flow,
  double split,
  double drop)
{
  bender::CfdEndFlow end;
  end.name = name;
  end.role = role;
  end.flowRateMlPerMin = flow;
  end.splitPercent = split;
  end.meanPressurePa = -drop;
  end.pressureDropPa = drop;
  return end;
}

// A bifurcation: 600 ml/min in, 60 / 40 % out, a few tens of Pa.
bender::CfdFlowResults Results()
{
  bender::CfdFlowResults r;
  r.run.iterations = 420;
  r.run.iterationLimit = 1000;
  r.run.converged = true;
  r.ends = { End("inlet", bender::PatchType::Inlet, 600, 100, 0),
    End("outlet_1", bender::PatchType::Outlet, 360, 60, 42.0),
    End("outlet_2", bender::PatchType::Outlet, 240, 40, 55.0) };
  r.inletFlowRateMlPerMin = 600;
  r.wallShearStress.meanPa = 2.4;
  r.wallShearStress.maxPa = 11.0;
  r.wallShearStress.percentile99Pa = 7.5;
  r.wallShearStress.lowAreaMm2 = 30.0;
  r.wallShearStress.highAreaMm2 = 0.0;
  r.wallShearStress.wallAreaMm2 = 2500.0;
  r.meshCells = 120000;
  return r;
}

const bender::CfdComparisonRow& Find(const bender::CfdComparison& c, const std::string& key)
{
  for (const bender::CfdComparisonRow& row : c.rows)
  {
    if (row.key == key)
    {
      return row;
    }
  }
  ADD_FAILURE() << "no row " << key;
  static const bender::CfdComparisonRow none;
  return none;
}
} // namespace

TEST(CfdComparison, TheSameResultsDifferNowhere)
{
  const bender::CfdComparison c = bender::CompareCfdResults(Results(), Results());
  ASSERT_FALSE(c.rows.empty());
  for (const bender::CfdComparisonRow& row : c.rows)
  {
    ASSERT_TRUE(row.a && row.b) << row.key;
    EXPECT_EQ(*row.a, *row.b) << row.key;
    ASSERT_TRUE(row.difference) << row.key;
    EXPECT_EQ(*row.difference, 0.0) << row.key;
    EXPECT_FALSE(row.highlighted) << row.key;
  }
  EXPECT_EQ(bender::CountHighlighted(c), 0);
  // Every outlet has its pressure drop, split and flow rate; the inlet is no outlet row.
  for (const char* key : { "pressureDrop.outlet_1",
         "pressureDrop.outlet_2",
         "split.outlet_1",
         "split.outlet_2",
         "flowRate.outlet_1",
         "flowRate.outlet_2",
         "wss.mean",
         "wss.max",
         "wss.p99",
         "wss.lowArea",
         "wss.highArea",
         "mesh.cells",
         "run.iterations" })
  {
    EXPECT_EQ(Find(c, key).key, key);
  }
  for (const bender::CfdComparisonRow& row : c.rows)
  {
    EXPECT_EQ(row.key.find(".inlet"), std::string::npos) << row.key;
  }
}

TEST(CfdComparison, DifferencesAndRelativeDifferencesAreBMinusA)
{
  bender::CfdFlowResults a = Results(), b = Results();
  b.ends[1].pressureDropPa *= 1.10;
  b.wallShearStress.meanPa *= 0.8;
  const bender::CfdComparison c = bender::CompareCfdResults(a, b);
  const bender::CfdComparisonRow& drop = Find(c, "pressureDrop.outlet_1");
  EXPECT_NEAR(*drop.difference, *drop.b - *drop.a, 1e-12);
  EXPECT_NEAR(*drop.relative, 0.10, 1e-12);
  EXPECT_TRUE(drop.highlighted);
  const bender::CfdComparisonRow& mean = Find(c, "wss.mean");
  EXPECT_NEAR(*mean.relative, -0.2, 1e-12);
  EXPECT_TRUE(mean.highlighted);
  EXPECT_FALSE(Find(c, "pressureDrop.outlet_2").highlighted);
  EXPECT_EQ(bender::CountHighlighted(c), 2);
}

TEST(CfdComparison, SwappingTheCasesNegatesEveryDifference)
{
  bender::CfdFlowResults a = Results(), b = Results();
  b.ends[1].pressureDropPa = 61.0;
  b.ends[1].splitPercent = 52.0;
  b.ends[2].splitPercent = 48.0;
  b.wallShearStress.highAreaMm2 = 4.0;
  b.meshCells = 150000;
  const bender::CfdComparison ab = bender::CompareCfdResults(a, b);
  const bender::CfdComparison ba = bender::CompareCfdResults(b, a);
  ASSERT_EQ(ab.rows.size(), ba.rows.size());
  for (size_t i = 0; i < ab.rows.size(); ++i)
  {
    EXPECT_EQ(ab.rows[i].key, ba.rows[i].key);
    ASSERT_TRUE(ab.rows[i].difference && ba.rows[i].difference) << ab.rows[i].key;
    EXPECT_EQ(*ab.rows[i].difference, -*ba.rows[i].difference) << ab.rows[i].key;
  }
}

TEST(CfdComparison, TheHighlightRuleNeedsBothTheRelativeStepAndTheFloor)
{
  const bender::CfdHighlightRule rule;
  bender::CfdFlowResults a = Results(), b = Results();
  // Just under 5 %: not highlighted; just over: highlighted.
  b.ends[1].pressureDropPa = a.ends[1].pressureDropPa * (1.0 + rule.relative * 0.9);
  b.ends[2].pressureDropPa = a.ends[2].pressureDropPa * (1.0 + rule.relative * 1.1);
  // 50 % more of a tiny area, below the area floor: not highlighted.
  a.wallShearStress.highAreaMm2 = 0.2;
  b.wallShearStress.highAreaMm2 = 0.3;
  // From zero: the floor alone decides (no relative difference).
  b.wallShearStress.lowAreaMm2 = a.wallShearStress.lowAreaMm2;
  a.wallShearStress.maxPa = 0.0;
  b.wallShearStress.maxPa = 10.0 * rule.stressFloor;
  // Mesh cells and the wall area are never highlighted.
  b.meshCells = 2 * a.meshCells;
  b.wallShearStress.wallAreaMm2 = 1.5 * a.wallShearStress.wallAreaMm2;
  const bender::CfdComparison c = bender::CompareCfdResults(a, b, rule);
  EXPECT_FALSE(Find(c, "pressureDrop.outlet_1").highlighted);
  EXPECT_TRUE(Find(c, "pressureDrop.outlet_2").highlighted);
  EXPECT_FALSE(Find(c, "wss.highArea").highlighted);
  EXPECT_FALSE(Find(c, "wss.max").relative.has_value());
  EXPECT_TRUE(Find(c, "wss.max").highlighted);
  EXPECT_FALSE(Find(c, "mesh.cells").highlighted);
  EXPECT_FALSE(Find(c, "wall.area").highlighted);
  EXPECT_NEAR(*Find(c, "mesh.cells").relative, 1.0, 1e-12);
  // A stricter rule highlights the 4.5 % step too.
  bender::CfdHighlightRule strict = rule;
  strict.relative = 0.01;
  EXPECT_TRUE(Find(bender::CompareCfdResults(a, b, strict), "pressureDrop.outlet_1").highlighted);
}

TEST(CfdComparison, AnOutletOfOneCaseOnlyIsListedAndHighlighted)
{
  bender::CfdFlowResults a = Results(), b = Results();
  b.ends[2].name = "outlet_3";
  const bender::CfdComparison c = bender::CompareCfdResults(a, b);
  const bender::CfdComparisonRow& onlyA = Find(c, "pressureDrop.outlet_2");
  EXPECT_TRUE(onlyA.a.has_value());
  EXPECT_FALSE(onlyA.b.has_value());
  EXPECT_FALSE(onlyA.difference.has_value());
  EXPECT_TRUE(onlyA.highlighted);
  EXPECT_NE(onlyA.note.find("only in A"), std::string::npos) << onlyA.note;
  const bender::CfdComparisonRow& onlyB = Find(c, "split.outlet_3");
  EXPECT_FALSE(onlyB.a.has_value());
  EXPECT_TRUE(onlyB.b.has_value());
  EXPECT_TRUE(onlyB.highlighted);
  // The outlets both have are matched by name, not by position.
  EXPECT_FALSE(Find(c, "split.outlet_1").highlighted);
  // A's outlets first, in A's order, then B's own.
  std::vector<std::string> splitKeys;
  for (const bender::CfdComparisonRow& row : c.rows)
  {
    if (row.key.rfind("split.", 0) == 0)
    {
      splitKeys.push_back(row.key);
    }
  }
  EXPECT_EQ(
    splitKeys, (std::vector<std::string>{ "split.outlet_1", "split.outlet_2", "split.outlet_3" }));
}

TEST(CfdComparison, ARunThatDidNotConvergeIsHighlighted)
{
  bender::CfdFlowResults a = Results(), b = Results();
  b.run.converged = false;
  b.run.iterations = 1000;
  const bender::CfdComparison c = bender::CompareCfdResults(a, b);
  const bender::CfdComparisonRow& run = Find(c, "run.iterations");
  EXPECT_TRUE(run.highlighted);
  EXPECT_NE(run.textB.find("stopped at 1000"), std::string::npos) << run.textB;
  EXPECT_NE(run.textA.find("converged"), std::string::npos) << run.textA;
  EXPECT_FALSE(Find(bender::CompareCfdResults(a, a), "run.iterations").highlighted);
}

TEST(CfdComparison, DifferentInletsAreNoted)
{
  bender::CfdFlowResults a = Results(), b = Results();
  b.ends[0].name = "outlet_0";
  EXPECT_FALSE(bender::CompareCfdResults(a, b).notes.empty());
  EXPECT_TRUE(bender::CompareCfdResults(a, a).notes.empty());
}

TEST(CfdComparison, TheJsonHoldsEveryRowWithNullsForMissingValues)
{
  bender::CfdFlowResults a = Results(), b = Results();
  b.ends[2].name = "outlet_3";
  b.ends[1].pressureDropPa = 80.0;
  bender::CfdComparison c = bender::CompareCfdResults(a, b);
  c.labelA = "original";
  c.labelB = "candidate";
  const nlohmann::json j = nlohmann::json::parse(bender::CfdComparisonToJson(c));
  EXPECT_EQ(j.at("format"), "bender-flow-comparison");
  EXPECT_EQ(j.at("version"), 1);
  EXPECT_EQ(j.at("caseA"), "original");
  ASSERT_EQ(j.at("rows").size(), c.rows.size());
  EXPECT_EQ(j.at("highlighted").get<int>(), bender::CountHighlighted(c));
  for (size_t i = 0; i < c.rows.size(); ++i)
  {
    const nlohmann::json& row = j.at("rows")[i];
    EXPECT_EQ(row.at("key"), c.rows[i].key);
    EXPECT_EQ(row.at("a").is_null(), !c.rows[i].a.has_value());
    EXPECT_EQ(row.at("b").is_null(), !c.rows[i].b.has_value());
    EXPECT_EQ(row.at("highlighted").get<bool>(), c.rows[i].highlighted);
    if (c.rows[i].a)
    {
      EXPECT_EQ(row.at("a").get<double>(), *c.rows[i].a);
    }
  }
}

TEST(CfdComparison, TheTextMarksExactlyTheHighlightedRows)
{
  bender::CfdFlowResults a = Results(), b = Results();
  b.ends[1].pressureDropPa = 80.0;
  b.wallShearStress.percentile99Pa = 9.0;
  const bender::CfdComparison c = bender::CompareCfdResults(a, b);
  std::istringstream lines(bender::CfdComparisonToText(c));
  std::string line;
  std::getline(lines, line); // the header
  int marked = 0;
  for (size_t i = 0; i < c.rows.size() && std::getline(lines, line); ++i)
  {
    EXPECT_EQ(line.rfind("* ", 0) == 0, c.rows[i].highlighted) << line;
    EXPECT_NE(line.find(c.rows[i].label), std::string::npos) << line;
    marked += line.rfind("* ", 0) == 0;
  }
  EXPECT_EQ(marked, 2);
}
