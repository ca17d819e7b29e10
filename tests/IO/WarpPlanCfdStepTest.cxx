// The Prepare for CFD step of a plan (issue 22): a plan with a clip step is version 2 and
// round-trips exactly (text and fields, unknown fields included); a version 1 plan reads as
// before (a "prepareForCfd" member there is an unknown field, kept); every rule of the step
// names its field.
#include "WarpPlanIO.h"

#include "IOTestUtilities.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <iterator>
#include <string>

using bender::CfdStep;
using bender::ParseWarpPlan;
using bender::SerializeWarpPlan;
using bender::WarpPlan;
using json = nlohmann::ordered_json;

namespace
{

constexpr const char* Source = "plan.bender.json";

/// The format document's example (one warp) as JSON.
json Example()
{
  std::ifstream in(bender_test::TestData("io/example.bender.json"));
  return json::parse(std::string(std::istreambuf_iterator<char>(in), {}));
}

/// Two steps: one before the warp with every field set, one after it with the defaults.
WarpPlan PlanWithSteps()
{
  WarpPlan plan = ParseWarpPlan(Example().dump(), Source);
  CfdStep step;
  step.afterWarps = 0;
  step.clip = true;
  step.cap = false;
  step.inletExtension = 7.25;
  step.outletExtension = 1.0 / 3.0;
  step.ends.push_back({ { 1.0 / 3.0, -0.0, 40.000000000000007 }, 2.0 / 3.0 });
  step.ends.push_back({ { 12.5, -3, 40 }, -1.0 });
  step.names.push_back({ { 0.1, 0.2, 0.3 }, "aorta_in", true });
  step.names.push_back({ { -5, 4, 1e-300 }, "outlet_7", false });
  step.extensionFactors.push_back({ { 1, 2, 3 }, 0.0 });
  step.extensionFactors.push_back({ { 4, 5, 6 }, 100.0 });
  step.extraFields["note"] = "{\"by\":\"test\",\"n\":[1,2.5]}";
  plan.cfdSteps.push_back(step);
  CfdStep later;
  later.afterWarps = 1;
  plan.cfdSteps.push_back(later);
  return plan;
}

void ExpectSameSteps(const WarpPlan& a, const WarpPlan& b)
{
  ASSERT_EQ(a.cfdSteps.size(), b.cfdSteps.size());
  for (std::size_t k = 0; k < a.cfdSteps.size(); ++k)
  {
    const CfdStep& x = a.cfdSteps[k];
    const CfdStep& y = b.cfdSteps[k];
    EXPECT_EQ(x.afterWarps, y.afterWarps);
    EXPECT_EQ(x.clip, y.clip);
    EXPECT_EQ(x.cap, y.cap);
    EXPECT_EQ(x.inletExtension, y.inletExtension);
    EXPECT_EQ(x.outletExtension, y.outletExtension);
    ASSERT_EQ(x.ends.size(), y.ends.size());
    for (std::size_t i = 0; i < x.ends.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(x.ends[i].position[c], y.ends[i].position[c]);
        EXPECT_EQ(std::signbit(x.ends[i].position[c]), std::signbit(y.ends[i].position[c]));
      }
      EXPECT_EQ(x.ends[i].distance, y.ends[i].distance);
    }
    ASSERT_EQ(x.names.size(), y.names.size());
    for (std::size_t i = 0; i < x.names.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(x.names[i].position[c], y.names[i].position[c]);
      }
      EXPECT_EQ(x.names[i].name, y.names[i].name);
      EXPECT_EQ(x.names[i].inlet, y.names[i].inlet);
    }
    ASSERT_EQ(x.extensionFactors.size(), y.extensionFactors.size());
    for (std::size_t i = 0; i < x.extensionFactors.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(x.extensionFactors[i].position[c], y.extensionFactors[i].position[c]);
      }
      EXPECT_EQ(x.extensionFactors[i].factor, y.extensionFactors[i].factor);
    }
    EXPECT_EQ(x.extraFields.size(), y.extraFields.size());
    for (const auto& [key, text] : x.extraFields)
    {
      ASSERT_TRUE(y.extraFields.count(key)) << key;
      EXPECT_EQ(json::parse(text), json::parse(y.extraFields.at(key))) << key;
    }
  }
}

std::string ErrorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const bender::WarpPlanError& e)
  {
    return e.what();
  }
  return "(no error)";
}

} // namespace

TEST(WarpPlanCfdStep, RoundTripIsExact)
{
  const WarpPlan plan = PlanWithSteps();
  const std::string text = SerializeWarpPlan(plan);
  const json document = json::parse(text);
  EXPECT_EQ(document["version"], 2);
  ASSERT_TRUE(document.contains("prepareForCfd"));
  EXPECT_EQ(document["prepareForCfd"].size(), 2u);
  // The end without a distance is written without one (it means "cut nearest this point").
  EXPECT_FALSE(document["prepareForCfd"][0]["ends"][1].contains("distance"));

  const WarpPlan back = ParseWarpPlan(text, Source);
  EXPECT_EQ(back.warps.size(), plan.warps.size());
  ExpectSameSteps(plan, back);
  EXPECT_TRUE(back.extraFields.empty()); // the steps are not an unknown field
  // Stable: what was read writes the same text, through the JSON object form too.
  EXPECT_EQ(SerializeWarpPlan(back), text);
  ExpectSameSteps(plan, bender::WarpPlanFromJson(bender::WarpPlanToJson(plan), Source));

  // The plan without its steps is version 1, as written before steps existed.
  WarpPlan plain = plan;
  plain.cfdSteps.clear();
  EXPECT_EQ(json::parse(SerializeWarpPlan(plain))["version"], 1);
  EXPECT_FALSE(json::parse(SerializeWarpPlan(plain)).contains("prepareForCfd"));
}

TEST(WarpPlanCfdStep, AVersionOnePlanReadsAsBefore)
{
  // The example as written (version 1), and with a member of the step's name: version 1 knows
  // no step, so it is an unknown field there, kept and written back as it was.
  const json example = Example();
  const WarpPlan plan = ParseWarpPlan(example.dump(), Source);
  EXPECT_TRUE(plan.cfdSteps.empty());
  EXPECT_EQ(plan.warps.size(), 1u);

  json withMember = example;
  withMember["prepareForCfd"] = json::parse(R"([{"afterWarps": 0}])");
  const WarpPlan kept = ParseWarpPlan(withMember.dump(), Source);
  EXPECT_TRUE(kept.cfdSteps.empty());
  ASSERT_EQ(kept.extraFields.count("prepareForCfd"), 1u);
  const json again = json::parse(SerializeWarpPlan(kept));
  EXPECT_EQ(again["version"], 1);
  EXPECT_EQ(again["prepareForCfd"], withMember["prepareForCfd"]);

  // Version 2 without steps is read; the defaults apply to a step's absent fields.
  json two = example;
  two["version"] = 2;
  EXPECT_TRUE(ParseWarpPlan(two.dump(), Source).cfdSteps.empty());
  two["prepareForCfd"] = json::parse(R"([{"afterWarps": 1}])");
  const WarpPlan defaults = ParseWarpPlan(two.dump(), Source);
  ASSERT_EQ(defaults.cfdSteps.size(), 1u);
  const CfdStep none;
  EXPECT_EQ(defaults.cfdSteps[0].afterWarps, 1u);
  EXPECT_EQ(defaults.cfdSteps[0].clip, none.clip);
  EXPECT_EQ(defaults.cfdSteps[0].cap, none.cap);
  EXPECT_EQ(defaults.cfdSteps[0].inletExtension, none.inletExtension);
  EXPECT_EQ(defaults.cfdSteps[0].outletExtension, none.outletExtension);
  EXPECT_TRUE(defaults.cfdSteps[0].ends.empty());
}

TEST(WarpPlanCfdStep, PlanOrderPutsEachStepBeforeItsWarp)
{
  WarpPlan plan = ParseWarpPlan(Example().dump(), Source);
  plan.warps.push_back(plan.warps.front());
  plan.cfdSteps.resize(3);
  plan.cfdSteps[0].afterWarps = 0;
  plan.cfdSteps[1].afterWarps = 1;
  plan.cfdSteps[2].afterWarps = 2;
  const std::vector<bender::PlanStepRef> order = bender::PlanOrder(plan);
  ASSERT_EQ(order.size(), 5u);
  const bool cfd[] = { true, false, true, false, true };
  const std::size_t index[] = { 0, 0, 1, 1, 2 };
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    EXPECT_EQ(order[k].cfd, cfd[k]) << k;
    EXPECT_EQ(order[k].index, index[k]) << k;
  }
}

TEST(WarpPlanCfdStep, EveryRuleNamesItsField)
{
  struct Case
  {
    std::function<void(json&)> change;
    std::string expected; // after "plan.bender.json: "
  };
  const auto step = [](json& p) -> json& { return p["prepareForCfd"][0]; };
  const std::vector<Case> cases = {
    { [](json& p) { p["prepareForCfd"] = 3; }, "prepareForCfd: expected an array, found 3" },
    { [](json& p) { p["prepareForCfd"][0] = "clip"; },
      "prepareForCfd[0]: expected an object, found a string \"clip\"" },
    { [&](json& p) { step(p).erase("afterWarps"); }, "prepareForCfd[0].afterWarps: missing" },
    { [&](json& p) { step(p)["afterWarps"] = 2; },
      "prepareForCfd[0].afterWarps: the plan has 1 warps (found 2)" },
    { [&](json& p) { step(p)["afterWarps"] = -1; },
      "prepareForCfd[0].afterWarps: must be >= 0 (found -1)" },
    { [](json& p)
      {
        p["prepareForCfd"][0]["afterWarps"] = 1;
        p["prepareForCfd"][1] = { { "afterWarps", 0 } };
      },
      "prepareForCfd[1].afterWarps: the steps must be in the order applied (found 0 after 1)" },
    { [&](json& p) { step(p)["clip"] = "yes"; },
      "prepareForCfd[0].clip: expected true or false, found a string \"yes\"" },
    { [&](json& p) { step(p)["cap"] = 1; },
      "prepareForCfd[0].cap: expected true or false, found 1" },
    { [&](json& p) { step(p)["inletExtension"] = 101; },
      "prepareForCfd[0].inletExtension: must be in [0, 100] (found 101)" },
    { [&](json& p) { step(p)["outletExtension"] = -0.5; },
      "prepareForCfd[0].outletExtension: must be in [0, 100] (found -0.5)" },
    { [&](json& p) { step(p)["ends"] = json::object(); },
      "prepareForCfd[0].ends: expected an array, found an object" },
    { [&](json& p) { step(p)["ends"] = json::parse(R"([{"distance": 2}])"); },
      "prepareForCfd[0].ends[0].position: missing" },
    { [&](json& p)
      { step(p)["ends"] = json::parse(R"([{"position": [0, 0, 0], "distance": -2}])"); },
      "prepareForCfd[0].ends[0].distance: must be >= 0 (found -2)" },
    { [&](json& p) { step(p)["names"] = json::parse(R"([{"position": [0, 0], "name": "a"}])"); },
      "prepareForCfd[0].names[0].position: expected an array of 3 numbers, found an array of 2" },
    { [&](json& p) { step(p)["names"] = json::parse(R"([{"position": [0, 0, 0]}])"); },
      "prepareForCfd[0].names[0].name: missing" },
    { [&](json& p)
      { step(p)["names"] = json::parse(R"([{"position": [0, 0, 0], "name": "wall"}])"); },
      "prepareForCfd[0].names[0].name: expected a patch name (letters, digits and '_', not "
      "starting with a digit, not \"wall\"), found a string \"wall\"" },
    { [&](json& p)
      { step(p)["names"] = json::parse(R"([{"position": [0, 0, 0], "name": "no spaces"}])"); },
      "prepareForCfd[0].names[0].name: expected a patch name (letters, digits and '_', not "
      "starting with a digit, not \"wall\"), found a string \"no spaces\"" },
    { [&](json& p)
      { step(p)["names"] = json::parse(R"([{"position": [0, 0, 0], "name": "a", "inlet": 0}])"); },
      "prepareForCfd[0].names[0].inlet: expected true or false, found 0" },
    { [&](json& p)
      { step(p)["extensionFactors"] = json::parse(R"([{"position": [0, 0, 0], "factor": 200}])"); },
      "prepareForCfd[0].extensionFactors[0].factor: must be in [0, 100] (found 200)" },
    { [&](json& p) { step(p)["extensionFactors"] = json::parse(R"([{"position": [0, 0, 0]}])"); },
      "prepareForCfd[0].extensionFactors[0].factor: missing" },
  };
  for (const Case& c : cases)
  {
    json document = Example();
    document["version"] = 2;
    document["prepareForCfd"] = json::parse(R"([{"afterWarps": 0}])");
    c.change(document);
    EXPECT_EQ(ErrorOf([&] { ParseWarpPlan(document.dump(), Source); }),
      std::string(Source) + ": " + c.expected);
  }
}
