#include "WarpPlanIO.h"

#include "IOTestUtilities.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <string>

namespace fs = std::filesystem;
using bender::DecayShape;
using bender::ParseWarpPlan;
using bender::SerializeWarpPlan;
using bender::WarpPlan;
using bender::WarpPlanError;
using json = nlohmann::json;
using bender_test::TempDir;

namespace
{

constexpr const char* Source = "plan.bender.json";

/// A valid warp (the format document's example warp).
json ExampleWarp()
{
  return json::parse(R"({
    "initial": {
      "start": { "position": [0, 0, 0],  "tangent": [1, 0, 0], "normal": [0, 0, 1] },
      "end":   { "position": [40, 0, 0], "tangent": [1, 0, 0], "normal": [0, 0, 1] },
      "extraTurns": 0
    },
    "final": {
      "start": { "position": [0, 0, 0],  "tangent": [1, 0, 0], "normal": [0, 0, 1] },
      "end":   { "position": [30, 20, 0], "tangent": [0, 1, 0], "normal": [0, 0, 1] },
      "extraTurns": 0
    },
    "radius": 12.5,
    "decay": { "shape": "plateau", "plateau": 0.4 },
    "reverseScrews": false,
    "subdivision": { "tolerance": 0.05, "maxPasses": 8 }
  })");
}

/// A valid plan of three example warps (so that messages can name warps[2]).
json ThreeWarps()
{
  json plan = { { "format", "bender-warps" }, { "version", 1 }, { "units", "mm" } };
  plan["warps"] = json::array({ ExampleWarp(), ExampleWarp(), ExampleWarp() });
  return plan;
}

std::string ErrorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const WarpPlanError& e)
  {
    return e.what();
  }
  catch (const std::exception& e)
  {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no exception";
  return {};
}

std::string ParseError(const std::string& text)
{
  return ErrorOf([&] { ParseWarpPlan(text, Source); });
}

std::string ParseDocumentError(const json& document)
{
  return ParseError(document.dump(2));
}

/// The plan of three warps with one change applied.
json Changed(const std::function<void(json&)>& change)
{
  json plan = ThreeWarps();
  change(plan);
  return plan;
}

void ExpectSameEnd(const bender::RibbonEnd& a, const bender::RibbonEnd& b)
{
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(a.position[i], b.position[i]);
    EXPECT_EQ(a.tangent[i], b.tangent[i]);
    EXPECT_EQ(a.normal[i], b.normal[i]);
    EXPECT_EQ(std::signbit(a.position[i]), std::signbit(b.position[i]));
  }
}

/// Same names, and values that are the same JSON (the text may differ in spacing and escapes).
void ExpectSameExtra(const std::map<std::string, std::string>& a,
  const std::map<std::string, std::string>& b)
{
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [key, text] : a)
  {
    ASSERT_TRUE(b.count(key)) << key;
    EXPECT_EQ(json::parse(text), json::parse(b.at(key))) << key;
  }
}

void ExpectSamePlan(const WarpPlan& a, const WarpPlan& b)
{
  EXPECT_EQ(a.units, b.units);
  ExpectSameExtra(a.extraFields, b.extraFields);
  ASSERT_EQ(a.warps.size(), b.warps.size());
  for (std::size_t i = 0; i < a.warps.size(); ++i)
  {
    SCOPED_TRACE("warp " + std::to_string(i));
    const auto& x = a.warps[i];
    const auto& y = b.warps[i];
    ExpectSameEnd(x.initial.start, y.initial.start);
    ExpectSameEnd(x.initial.end, y.initial.end);
    ExpectSameEnd(x.final.start, y.final.start);
    ExpectSameEnd(x.final.end, y.final.end);
    EXPECT_EQ(x.initial.extraTurns, y.initial.extraTurns);
    EXPECT_EQ(x.final.extraTurns, y.final.extraTurns);
    EXPECT_EQ(x.radius, y.radius);
    EXPECT_EQ(x.decay.shape, y.decay.shape);
    EXPECT_EQ(x.decay.plateau, y.decay.plateau);
    EXPECT_EQ(x.reverseScrews, y.reverseScrews);
    ASSERT_EQ(x.subdivision.has_value(), y.subdivision.has_value());
    if (x.subdivision)
    {
      EXPECT_EQ(x.subdivision->tolerance, y.subdivision->tolerance);
      EXPECT_EQ(x.subdivision->maxPasses, y.subdivision->maxPasses);
    }
    ExpectSameExtra(x.extraFields, y.extraFields);
  }
}

/// Two warps with awkward numbers: thirds, tenths, tiny and huge values, negative zero.
WarpPlan AwkwardPlan()
{
  WarpPlan plan;
  plan.units = "mm";
  bender::WarpSpec warp;
  warp.initial.start = { { 1.0 / 3.0, -0.0, 0.1 }, { 1, 1e-17, 0 }, { 0, 0.2, 1 } };
  warp.initial.end = { { 40.000000000000007, 1e-300, -2.0 / 3.0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  warp.final = warp.initial;
  warp.final.end.position = { 30.1, 20.7, 1e-5 };
  warp.final.end.tangent = { 0.3, 1, 0 };
  warp.final.extraTurns = 0;
  warp.radius = 12.345678901234567;
  warp.decay.shape = DecayShape::Plateau;
  warp.decay.plateau = 0.95;
  // The non-minimal screw at s = 0 is only valid where the start frames differ (a twin of
  // the identity is a full turn): turn the final start normal by 150 degrees.
  warp.final.start.normal = { 0, 0.5, -0.8660254037844386 };
  warp.reverseScrews = true;
  warp.subdivision = bender::SubdivisionSpec{ 0.05, 0 };
  warp.extraFields["name"] = "\"bend the carotid\"";
  warp.extraFields["createdAt"] = "{\"iso\":\"2024-05-01T10:00:00Z\",\"by\":[1,2.5,null]}";
  plan.warps.push_back(warp);
  warp.reverseScrews = false;
  warp.final.start.normal = warp.initial.start.normal;
  warp.decay = {};
  warp.subdivision.reset();
  warp.extraFields.clear();
  warp.radius = 7;
  plan.warps.push_back(warp);
  plan.extraFields["note"] = "\"made by a test \\u00e9\"";
  plan.extraFields["application"] = "{\"name\":\"bender\",\"version\":[0,1,0]}";
  return plan;
}

} // namespace

// ---------------------------------------------------------------------------------------
// Valid files

TEST(WarpPlanIO, FormatDocumentExampleParses)
{
  const WarpPlan plan = bender::ReadWarpPlan(bender_test::TestData("io/example.bender.json"));
  EXPECT_EQ(plan.units, "mm");
  ASSERT_EQ(plan.warps.size(), 1u);
  const auto& w = plan.warps[0];
  EXPECT_EQ(w.initial.end.position[0], 40.0);
  EXPECT_EQ(w.final.end.position[0], 30.0);
  EXPECT_EQ(w.final.end.position[1], 20.0);
  EXPECT_EQ(w.final.end.tangent[1], 1.0);
  EXPECT_EQ(w.final.start.normal[2], 1.0);
  EXPECT_EQ(w.initial.extraTurns, 0);
  EXPECT_EQ(w.radius, 12.5);
  EXPECT_EQ(w.decay.shape, DecayShape::Plateau);
  EXPECT_EQ(w.decay.plateau, 0.4);
  EXPECT_FALSE(w.reverseScrews);
  ASSERT_TRUE(w.subdivision.has_value());
  EXPECT_EQ(w.subdivision->tolerance, 0.05);
  EXPECT_EQ(w.subdivision->maxPasses, 8);
  EXPECT_TRUE(w.extraFields.empty());
  EXPECT_TRUE(plan.extraFields.empty());
}

TEST(WarpPlanIO, DefaultsApplyToAbsentFields)
{
  json warp = ExampleWarp();
  warp.erase("decay");
  warp.erase("reverseScrews");
  warp.erase("subdivision");
  warp["initial"].erase("extraTurns");
  warp["final"].erase("extraTurns");
  const json document = {
    { "format", "bender-warps" }, { "version", 1 }, { "warps", json::array({ warp }) }
  };
  const WarpPlan plan = ParseWarpPlan(document.dump(), Source);
  EXPECT_EQ(plan.units, "mm");
  ASSERT_EQ(plan.warps.size(), 1u);
  EXPECT_EQ(plan.warps[0].decay.shape, DecayShape::Bell);
  EXPECT_EQ(plan.warps[0].decay.plateau, 0.5);
  EXPECT_FALSE(plan.warps[0].reverseScrews);
  EXPECT_FALSE(plan.warps[0].subdivision.has_value());
  EXPECT_EQ(plan.warps[0].initial.extraTurns, 0);

  json withSubdivision = warp;
  withSubdivision["subdivision"] = { { "tolerance", 0.1 } };
  const json second = {
    { "format", "bender-warps" }, { "version", 1 }, { "warps", json::array({ withSubdivision }) }
  };
  EXPECT_EQ(ParseWarpPlan(second.dump(), Source).warps[0].subdivision->maxPasses, 8);

  const WarpPlan empty =
    ParseWarpPlan(R"({"format": "bender-warps", "version": 1, "warps": []})", Source);
  EXPECT_TRUE(empty.warps.empty());
}

TEST(WarpPlanIO, KeepsVectorsAsWritten)
{
  // Tangents and normals need not be unit or orthogonal; the geometry core normalises them
  // (spec 2), so a replay computes from exactly the numbers the session had.
  json plan = ThreeWarps();
  plan["warps"][0]["initial"]["start"]["tangent"] = { 2, 0, 0 };
  plan["warps"][0]["initial"]["start"]["normal"] = { 0.5, 0, 3 };
  const WarpPlan parsed = ParseWarpPlan(plan.dump(), Source);
  EXPECT_EQ(parsed.warps[0].initial.start.tangent[0], 2.0);
  EXPECT_EQ(parsed.warps[0].initial.start.normal[0], 0.5);
  EXPECT_EQ(parsed.warps[0].initial.start.normal[2], 3.0);
}

TEST(WarpPlanIO, RoundTripIsExactAndKeepsUnknownFields)
{
  const WarpPlan plan = AwkwardPlan();
  const std::string text = SerializeWarpPlan(plan);
  const WarpPlan back = ParseWarpPlan(text, Source);
  ExpectSamePlan(plan, back);
  // Stable: writing what was read gives the same text, and reading it the same fields,
  // members in their original order.
  EXPECT_EQ(SerializeWarpPlan(back), text);
  EXPECT_EQ(
    ParseWarpPlan(SerializeWarpPlan(back), Source).warps[0].extraFields, back.warps[0].extraFields);
  EXPECT_EQ(back.warps[0].extraFields.at("createdAt"),
    "{\"iso\":\"2024-05-01T10:00:00Z\",\"by\":[1,2.5,null]}");
  // The text is JSON with the documented layout.
  const json document = json::parse(text);
  EXPECT_EQ(document["format"], "bender-warps");
  EXPECT_EQ(document["version"], 1);
  EXPECT_EQ(document["warps"][0]["name"], "bend the carotid");
  EXPECT_EQ(document["application"]["version"][2], 0);
  EXPECT_EQ(document["note"], "made by a test \u00e9");
  EXPECT_FALSE(document["warps"][1].contains("subdivision"));
}

// The JSON object form (for documents that embed a plan, such as the session autosave) is
// the file's object, and reads back exactly without going through text.
TEST(WarpPlanIO, JsonObjectFormIsTheFilesObject)
{
  const WarpPlan plan = AwkwardPlan();
  const nlohmann::ordered_json object = bender::WarpPlanToJson(plan);
  EXPECT_EQ(object, nlohmann::ordered_json::parse(SerializeWarpPlan(plan)));
  EXPECT_EQ(object.begin().key(), "format"); // members in the file's order
  ExpectSamePlan(plan, bender::WarpPlanFromJson(object, Source));

  nlohmann::ordered_json bad = object;
  bad["warps"][0]["radius"] = -2.0;
  const std::string message = ErrorOf([&] { bender::WarpPlanFromJson(bad, "session.json: plan"); });
  EXPECT_EQ(message.rfind("session.json: plan: warps[0].radius: ", 0), 0u) << message;

  WarpPlan infinite = plan;
  infinite.warps[0].radius = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ErrorOf([&] { bender::WarpPlanToJson(infinite, "s.json"); })
              .rfind("s.json: warps[0].radius: ", 0),
    0u);
}

TEST(WarpPlanIO, UnknownFieldsInAFileAreKeptAndWrittenBack)
{
  json document = ThreeWarps();
  document["createdAt"] = "2024-05-01";
  document["meta"] = { { "scanner", "CT" }, { "slices", json::array({ 1, 2, 3 }) } };
  document["warps"][1]["name"] = "second";
  document["warps"][1]["weights"] = json::array({ 0.1, 0.2 });
  // Unknown fields inside known objects are ignored.
  document["warps"][1]["decay"]["sharpness"] = 3;
  const WarpPlan plan = ParseWarpPlan(document.dump(), Source);
  EXPECT_EQ(plan.extraFields.size(), 2u);
  EXPECT_EQ(json::parse(plan.extraFields.at("meta")), document["meta"]);
  EXPECT_EQ(json::parse(plan.extraFields.at("createdAt")), "2024-05-01");
  EXPECT_EQ(plan.warps[1].extraFields.size(), 2u);
  EXPECT_EQ(json::parse(plan.warps[1].extraFields.at("weights")), document["warps"][1]["weights"]);
  EXPECT_TRUE(plan.warps[0].extraFields.empty());

  const json written = json::parse(SerializeWarpPlan(plan));
  EXPECT_EQ(written["meta"], document["meta"]);
  EXPECT_EQ(written["createdAt"], "2024-05-01");
  EXPECT_EQ(written["warps"][1]["name"], "second");
  EXPECT_EQ(written["warps"][1]["weights"], document["warps"][1]["weights"]);
  EXPECT_FALSE(written["warps"][0].contains("name"));
}

TEST(WarpPlanIO, FileRoundTripIsAtomic)
{
  TempDir dir;
  const WarpPlan plan = AwkwardPlan();
  const std::string path = dir / "plan.bender.json";
  bender_test::WriteText(path, "old content");
  bender::WriteWarpPlan(plan, path);
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "plan.bender.json" });
  ExpectSamePlan(plan, bender::ReadWarpPlan(path));

  // A plan that cannot be written leaves the previous file untouched and no temporary file.
  WarpPlan bad = plan;
  bad.warps[1].radius = std::numeric_limits<double>::quiet_NaN();
  const std::string before = bender_test::ReadText(path);
  EXPECT_EQ(ErrorOf([&] { bender::WriteWarpPlan(bad, path); }),
    "plan.bender.json: warps[1].radius: not a finite number (JSON cannot hold it)");
  EXPECT_EQ(bender_test::ReadText(path), before);
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "plan.bender.json" });

  const std::string message =
    ErrorOf([&] { bender::WriteWarpPlan(plan, dir / "no/folder/p.json"); });
  EXPECT_EQ(message.rfind("p.json: folder ", 0), 0u) << message;
}

TEST(WarpPlanIO, SerialiseRefusesWhatJsonCannotHold)
{
  WarpPlan plan = AwkwardPlan();
  plan.warps[0].final.end.tangent = { 0, std::numeric_limits<double>::infinity(), 0 };
  EXPECT_EQ(ErrorOf([&] { SerializeWarpPlan(plan); }),
    "plan: warps[0].final.end.tangent[1]: not a finite number (JSON cannot hold it)");

  plan = AwkwardPlan();
  plan.warps[1].extraFields["broken"] = "{not json";
  EXPECT_EQ(ErrorOf([&] { SerializeWarpPlan(plan); })
              .rfind("plan: warps[1].broken: extra field is not valid JSON", 0),
    0u);

  plan = AwkwardPlan();
  plan.extraFields["warps"] = "[]";
  EXPECT_EQ(ErrorOf([&] { SerializeWarpPlan(plan); }),
    "plan: warps: an extra field may not have the name of a known field");
}

// ---------------------------------------------------------------------------------------
// Rejections: one line naming the file, the warp and the field

TEST(WarpPlanIORejects, FileProblems)
{
  TempDir dir;
  EXPECT_EQ(ErrorOf([&] { bender::ReadWarpPlan(dir / "nothere.bender.json"); }),
    "nothere.bender.json: no such file");
  fs::create_directory(dir / "folder.bender.json");
  EXPECT_EQ(ErrorOf([&] { bender::ReadWarpPlan(dir / "folder.bender.json"); }),
    "folder.bender.json: is a folder, not a file");
  bender_test::WriteText(dir / "empty.bender.json", "");
  EXPECT_EQ(ErrorOf([&] { bender::ReadWarpPlan(dir / "empty.bender.json"); }),
    "empty.bender.json: empty file (0 bytes)");
  json bad = ThreeWarps();
  bad["warps"][2]["final"]["end"]["tangent"] = { 0, 0, 0 };
  bender_test::WriteText(dir / "plan.bender.json", bad.dump(2));
  EXPECT_EQ(ErrorOf([&] { bender::ReadWarpPlan(dir / "plan.bender.json"); }),
    "plan.bender.json: warps[2].final.end.tangent: zero vector");
}

TEST(WarpPlanIORejects, MalformedJsonWithItsPosition)
{
  const std::string text =
    "{\n  \"format\": \"bender-warps\",\n  \"version\": 1\n  \"warps\": []\n}";
  const std::string message = ParseError(text);
  EXPECT_EQ(
    message.rfind("plan.bender.json: malformed JSON: parse error at line 4, column ", 0), 0u)
    << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_EQ(ParseError("").rfind("plan.bender.json: malformed JSON: ", 0), 0u);
  EXPECT_EQ(
    ParseError("{\"format\": \"bender-warps\", ").rfind("plan.bender.json: malformed JSON: ", 0),
    0u);
  EXPECT_EQ(ParseError(std::string(10000, '[') + std::string(10000, ']')),
    "plan.bender.json: JSON nested more than 64 levels deep");
  // The source name is given by the caller; an empty one still gives a prefix.
  EXPECT_EQ(ErrorOf([] { ParseWarpPlan("[]", ""); }),
    "plan: expected a JSON object at the top level, found an array");
}

TEST(WarpPlanIORejects, EveryRuleNamesItsField)
{
  struct Case
  {
    std::function<void(json&)> change;
    std::string expected; // the message after "plan.bender.json: "
  };
  const auto at = [](json& plan, int warp) -> json& { return plan["warps"][warp]; };
  const std::vector<Case> cases = {
    // Top level.
    { [](json& p) { p.erase("format"); }, "format: missing" },
    { [](json& p) { p["format"] = "bender-warp"; },
      "format: expected \"bender-warps\", found \"bender-warp\"" },
    { [](json& p) { p["format"] = 1; }, "format: expected the string \"bender-warps\", found 1" },
    { [](json& p) { p.erase("version"); }, "version: missing" },
    { [](json& p) { p["version"] = 3; },
      "version: unsupported version 3 (this reader knows versions 1 and 2)" },
    { [](json& p) { p["version"] = 0; },
      "version: unsupported version 0 (this reader knows versions 1 and 2)" },
    { [](json& p) { p["version"] = 1.5; },
      "version: unsupported version 1.5 (this reader knows versions 1 and 2)" },
    { [](json& p) { p["version"] = "1"; }, "version: expected an integer, found a string \"1\"" },
    { [](json& p) { p["units"] = 5; }, "units: expected a string, found 5" },
    { [](json& p) { p.erase("warps"); }, "warps: missing" },
    { [](json& p) { p["warps"] = json::object(); }, "warps: expected an array, found an object" },
    { [](json& p) { p["warps"] = nullptr; }, "warps: expected an array, found null" },
    { [&](json& p) { at(p, 1) = 5; }, "warps[1]: expected an object, found 5" },
    // Ribbons and ends.
    { [&](json& p) { at(p, 0).erase("initial"); }, "warps[0].initial: missing" },
    { [&](json& p) { at(p, 0)["final"] = json::array(); },
      "warps[0].final: expected an object, found an array" },
    { [&](json& p) { at(p, 1)["final"].erase("end"); }, "warps[1].final.end: missing" },
    { [&](json& p) { at(p, 1)["final"]["start"] = "here"; },
      "warps[1].final.start: expected an object, found a string \"here\"" },
    { [&](json& p) { at(p, 2)["initial"]["start"].erase("position"); },
      "warps[2].initial.start.position: missing" },
    { [&](json& p) {
       at(p, 2)["initial"]["start"]["position"] = { 0, 0 };
     },
      "warps[2].initial.start.position: expected an array of 3 numbers, found an array of 2" },
    { [&](json& p) {
       at(p, 2)["initial"]["start"]["position"] = { 0, 0, 0, 0 };
     },
      "warps[2].initial.start.position: expected an array of 3 numbers, found an array of 4" },
    { [&](json& p) { at(p, 2)["initial"]["start"]["position"] = 0; },
      "warps[2].initial.start.position: expected an array of 3 numbers, found 0" },
    { [&](json& p) {
       at(p, 2)["initial"]["end"]["position"] = { 0, "a", 0 };
     },
      "warps[2].initial.end.position[1]: expected a number, found a string \"a\"" },
    { [&](json& p) {
       at(p, 2)["initial"]["end"]["position"] = { 0, nullptr, 0 };
     },
      "warps[2].initial.end.position[1]: expected a number, found null" },
    { [&](json& p) {
       at(p, 2)["final"]["end"]["tangent"] = { 0, 0, 0 };
     },
      "warps[2].final.end.tangent: zero vector" },
    { [&](json& p) {
       at(p, 0)["initial"]["start"]["tangent"] = { true, 0, 0 };
     },
      "warps[0].initial.start.tangent[0]: expected a number, found true" },
    { [&](json& p) { at(p, 0)["initial"]["start"].erase("normal"); },
      "warps[0].initial.start.normal: missing" },
    { [&](json& p) {
       at(p, 0)["initial"]["start"]["normal"] = { 0, 0, 0 };
     },
      "warps[0].initial.start.normal: zero vector" },
    { [&](json& p) {
       at(p, 0)["final"]["end"]["normal"] = { 0, -3, 0 };
     },
      "warps[0].final.end.normal: parallel to the tangent" },
    { [&](json& p) {
       at(p, 0)["final"]["end"]["normal"] = { 1e-10, 1, 0 };
     },
      "warps[0].final.end.normal: parallel to the tangent" },
    { [&](json& p) { at(p, 0)["final"]["extraTurns"] = 1.5; },
      "warps[0].final.extraTurns: expected an integer, found 1.5" },
    { [&](json& p) { at(p, 0)["final"]["extraTurns"] = 1.0; },
      "warps[0].final.extraTurns: expected an integer, found 1.0" },
    { [&](json& p) { at(p, 0)["final"]["extraTurns"] = "1"; },
      "warps[0].final.extraTurns: expected an integer, found a string \"1\"" },
    { [&](json& p) { at(p, 0)["final"]["extraTurns"] = 10000000000LL; },
      "warps[0].final.extraTurns: out of range (found 10000000000)" },
    // Warp parameters.
    { [&](json& p) { at(p, 1).erase("radius"); }, "warps[1].radius: missing" },
    { [&](json& p) { at(p, 1)["radius"] = 0; }, "warps[1].radius: must be > 0 (found 0.0)" },
    { [&](json& p) { at(p, 1)["radius"] = -2.5; }, "warps[1].radius: must be > 0 (found -2.5)" },
    { [&](json& p) { at(p, 1)["radius"] = "12"; },
      "warps[1].radius: expected a number, found a string \"12\"" },
    { [&](json& p) { at(p, 1)["decay"] = "bell"; },
      "warps[1].decay: expected an object, found a string \"bell\"" },
    { [&](json& p) { at(p, 1)["decay"]["shape"] = "cubic"; },
      "warps[1].decay.shape: expected \"bell\" or \"plateau\", found \"cubic\"" },
    { [&](json& p) { at(p, 1)["decay"]["shape"] = 2; },
      "warps[1].decay.shape: expected \"bell\" or \"plateau\", found 2" },
    { [&](json& p) { at(p, 1)["decay"]["plateau"] = 0.96; },
      "warps[1].decay.plateau: must be in [0, 0.95] (found 0.96)" },
    { [&](json& p) { at(p, 1)["decay"]["plateau"] = -0.1; },
      "warps[1].decay.plateau: must be in [0, 0.95] (found -0.1)" },
    { [&](json& p) { at(p, 1)["decay"]["plateau"] = false; },
      "warps[1].decay.plateau: expected a number, found false" },
    { [&](json& p) { at(p, 1)["reverseScrews"] = "yes"; },
      "warps[1].reverseScrews: expected true or false, found a string \"yes\"" },
    { [&](json& p) { at(p, 1)["reverseScrews"] = 1; },
      "warps[1].reverseScrews: expected true or false, found 1" },
    { [&](json& p) { at(p, 2)["subdivision"] = 5; },
      "warps[2].subdivision: expected an object, found 5" },
    { [&](json& p) { at(p, 2)["subdivision"].erase("tolerance"); },
      "warps[2].subdivision.tolerance: missing" },
    { [&](json& p) { at(p, 2)["subdivision"]["tolerance"] = 0; },
      "warps[2].subdivision.tolerance: must be > 0 (found 0.0)" },
    { [&](json& p) { at(p, 2)["subdivision"]["tolerance"] = -1e-3; },
      "warps[2].subdivision.tolerance: must be > 0 (found -0.001)" },
    { [&](json& p) { at(p, 2)["subdivision"]["maxPasses"] = -1; },
      "warps[2].subdivision.maxPasses: must be >= 0 (found -1)" },
    { [&](json& p) { at(p, 2)["subdivision"]["maxPasses"] = 2.5; },
      "warps[2].subdivision.maxPasses: expected an integer, found 2.5" },
    { [&](json& p) { at(p, 2)["subdivision"]["maxPasses"] = "8"; },
      "warps[2].subdivision.maxPasses: expected an integer, found a string \"8\"" },
  };
  for (const Case& c : cases)
  {
    EXPECT_EQ(ParseDocumentError(Changed(c.change)), std::string(Source) + ": " + c.expected);
  }
}

TEST(WarpPlanIORejects, NonFiniteNumbersInTheText)
{
  // JSON has no NaN or infinity, but 1e999 parses to infinity.
  json plan = ThreeWarps();
  std::string text = plan.dump();
  const std::string needle = "\"radius\":12.5";
  text.replace(text.find(needle), needle.size(), "\"radius\":1e999");
  EXPECT_EQ(ParseError(text), "plan.bender.json: malformed JSON: number overflow parsing '1e999'");
}

TEST(WarpPlanIORejects, LimitsThatAreAccepted)
{
  // The edges of each range are valid.
  for (const auto& change : std::vector<std::function<void(json&)>>{ [](json& p)
         { p["warps"][0]["decay"]["plateau"] = 0.95; },
         [](json& p) { p["warps"][0]["decay"]["plateau"] = 0; },
         [](json& p) { p["warps"][0]["subdivision"]["maxPasses"] = 0; },
         [](json& p) {
           p["warps"][0]["final"]["end"]["normal"] = { 1e-8, 1, 1e-3 };
         },
         [](json& p) { p["units"] = "m"; },
         [](json& p) { p["warps"] = json::array(); } })
  {
    const json plan = Changed(change);
    EXPECT_NO_THROW(ParseWarpPlan(plan.dump(), Source)) << plan.dump();
  }
}

TEST(WarpPlanIORejects, InvalidRibbonsThroughTheGeometryCore)
{
  // Coincident ends (convention 11): the geometry core names the ribbon; the reader adds the
  // file and the warp.
  json plan = ThreeWarps();
  plan["warps"][1]["initial"]["end"]["position"] = { 0, 0, 0 };
  std::string message = ParseDocumentError(plan);
  EXPECT_EQ(message.rfind("plan.bender.json: warps[1].initial", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);

  // A warp that twists a full turn relative to its grab (more than 340 degrees).
  plan = ThreeWarps();
  plan["warps"][2]["final"]["extraTurns"] = 1;
  message = ParseDocumentError(plan);
  EXPECT_EQ(message.rfind("plan.bender.json: warps[2].final: ", 0), 0u) << message;

  // Non-finite after normalisation is impossible to write in JSON; huge but finite is fine
  // structurally and left to the core.
  plan = ThreeWarps();
  plan["warps"][0]["final"]["end"]["tangent"] = { 0, 1e308, 1e308 };
  message = ErrorOf([&] { ParseWarpPlan(plan.dump(), Source); });
  EXPECT_EQ(message.rfind("plan.bender.json: warps[0].final.end.tangent: ", 0), 0u) << message;
}

TEST(WarpPlanIO, MalformedJsonErrorsQuoteNoRawBytes)
{
  // nlohmann's parse errors quote the bytes last read; from a file they may be control bytes or
  // invalid UTF-8, which must not reach a terminal (issue 13, found by fuzz/fuzz_plan).
  const std::string text =
    std::string("{\"format\": \"bender-warps\", \"version\": 1, \x1b[31m\xdb") + "\x07 }";
  const std::string message = ErrorOf([&] { ParseWarpPlan(text, Source); });
  ASSERT_NE(message.find("malformed JSON"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  for (const char c : message)
  {
    const unsigned char u = static_cast<unsigned char>(c);
    EXPECT_TRUE(u >= 0x20 && u < 0x7f) << "byte " << int(u) << " in: " << message;
  }
}

TEST(WarpPlanIO, QuotedStringsInErrorsArePrintableAscii)
{
  // A DEL byte or a non-ASCII character in a string the message quotes (found by fuzz_plan:
  // a top-level string holding 0x7f) is escaped, and the quote stays short.
  const auto expectPrintable = [](const std::string& message)
  {
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_LT(message.size(), 300u) << message;
    for (const char c : message)
    {
      const unsigned char u = static_cast<unsigned char>(c);
      EXPECT_TRUE(u >= 0x20 && u < 0x7f) << "byte " << int(u) << " in: " << message;
    }
  };
  const std::string del = std::string("\"www\x7fwww") + std::string(60, 'w') + "\"";
  std::string message = ErrorOf([&] { ParseWarpPlan(del, Source); });
  EXPECT_NE(message.find("found a string \"www\\u007fwww"), std::string::npos) << message;
  expectPrintable(message);
  message = ErrorOf([&] { ParseWarpPlan("{\"format\": \"b\xc3\xa9nder\x7f\"}", Source); });
  EXPECT_NE(
    message.find("format: expected \"bender-warps\", found \"b\\u00e9nder"), std::string::npos)
    << message;
  expectPrintable(message);
  message = ErrorOf(
    [&]
    {
      ParseWarpPlan(
        "{\"format\": \"bender-warps\", \"version\": 1, \"warps\": [{\"decay\": {\"shape\": "
        "\"b\x7f" +
          std::string(100, 'x') + "\"}}]}",
        Source);
    });
  expectPrintable(message);
}
