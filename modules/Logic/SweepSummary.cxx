// A sweep's rows as JSON (each candidate's state.json, summary.json) and CSV (summary.csv).

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "Sweep.h"
#include "SweepRowResults.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <locale>
#include <sstream>

namespace bender
{

namespace
{
using Json = nlohmann::ordered_json;

// NaN (not known) as null.
Json Number(double value)
{
  return std::isfinite(value) ? Json(value) : Json(nullptr);
}

double NumberOf(const Json& j, const char* key)
{
  const auto it = j.find(key);
  return it == j.end() || !it->is_number() ? std::numeric_limits<double>::quiet_NaN()
                                           : it->get<double>();
}

Json RowJson(const SweepRow& row)
{
  Json j;
  j["id"] = row.id;
  j["parameter"] = row.parameter;
  j["value"] = Number(row.value);
  j["plan"] = row.planName;
  j["original"] = row.original;
  j["state"] = row.state;
  j["reason"] = row.reason;
  j["log"] = row.log;
  j["hash"] = row.hash;
  j["bendAngleDeg"] = Number(row.measures.bendAngle);
  j["lengthChangePercent"] = Number(row.measures.lengthChange);
  j["minRadiusMm"] = Number(row.measures.minRadius);
  const bool solved = row.state == "solved";
  j["pressureDropPa"] = solved ? Number(row.pressureDrop) : Json(nullptr);
  Json outlets = Json::array();
  for (const SweepOutlet& o : row.outlets)
  {
    outlets.push_back({ { "name", o.name },
      { "splitPercent", Number(o.splitPercent) },
      { "pressureDropPa", Number(o.pressureDrop) },
      { "flowRateMlPerMin", Number(o.flowRate) } });
  }
  j["outlets"] = outlets;
  const bool wss = solved && row.wallShearStress;
  j["wallShearStress"] = wss ? Json{ { "meanPa", Number(row.wssMean) },
    { "maxPa", Number(row.wssMax) },
    { "p99Pa", Number(row.wssP99) },
    { "lowAreaMm2", Number(row.lowWssArea) },
    { "highAreaMm2", Number(row.highWssArea) } }
                             : Json(nullptr);
  j["meshCells"] = solved ? Json(row.meshCells) : Json(nullptr);
  j["iterations"] = solved ? Json(row.iterations) : Json(nullptr);
  j["converged"] = solved ? Json(row.converged) : Json(nullptr);
  j["solveSeconds"] = solved ? Number(row.solveSeconds) : Json(nullptr);
  return j;
}

// "12.5" in the classic locale, with up to 10 significant digits; empty for NaN.
std::string CsvNumber(double value)
{
  if (!std::isfinite(value))
  {
    return {};
  }
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(10);
  s << value;
  return s.str();
}

std::string CsvText(const std::string& text)
{
  if (text.find_first_of(",\"\n") == std::string::npos)
  {
    return text;
  }
  std::string quoted = "\"";
  for (char c : text)
  {
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  }
  return quoted + "\"";
}

// The outlets' names, in the order they first appear.
std::vector<std::string> OutletNames(const std::vector<SweepRow>& rows)
{
  std::vector<std::string> names;
  for (const SweepRow& row : rows)
  {
    for (const SweepOutlet& o : row.outlets)
    {
      if (std::find(names.begin(), names.end(), o.name) == names.end())
      {
        names.push_back(o.name);
      }
    }
  }
  return names;
}
} // namespace

std::string SweepRowToJson(const SweepRow& row)
{
  return RowJson(row).dump(2) + "\n";
}

SweepRow SweepRowFromJson(const std::string& text, const std::string& source)
{
  const Json j = Json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object())
  {
    throw InputError(source + ": not a sweep candidate's state (malformed JSON)");
  }
  SweepRow row;
  try
  {
    row.id = j.at("id").get<std::string>();
    row.value = NumberOf(j, "value");
    row.planName = j.at("plan").get<std::string>();
    row.original = j.at("original").get<bool>();
    row.state = j.at("state").get<std::string>();
    row.reason = j.at("reason").get<std::string>();
    row.log = j.at("log").get<std::string>();
    row.hash = j.at("hash").get<std::string>();
    row.measures.bendAngle = NumberOf(j, "bendAngleDeg");
    row.measures.lengthChange = NumberOf(j, "lengthChangePercent");
    row.measures.minRadius = NumberOf(j, "minRadiusMm");
    row.pressureDrop = NumberOf(j, "pressureDropPa");
    for (const Json& o : j.at("outlets"))
    {
      row.outlets.push_back({ o.at("name").get<std::string>(),
        NumberOf(o, "splitPercent"),
        NumberOf(o, "pressureDropPa"),
        NumberOf(o, "flowRateMlPerMin") });
    }
    const Json& wss = j.at("wallShearStress");
    row.wallShearStress = wss.is_object();
    if (row.wallShearStress)
    {
      row.wssMean = NumberOf(wss, "meanPa");
      row.wssMax = NumberOf(wss, "maxPa");
      row.wssP99 = NumberOf(wss, "p99Pa");
      row.lowWssArea = NumberOf(wss, "lowAreaMm2");
      row.highWssArea = NumberOf(wss, "highAreaMm2");
    }
    row.meshCells = j.at("meshCells").is_number() ? j["meshCells"].get<long long>() : 0;
    row.iterations = j.at("iterations").is_number() ? j["iterations"].get<int>() : 0;
    row.converged = j.at("converged").is_boolean() && j["converged"].get<bool>();
    row.solveSeconds = NumberOf(j, "solveSeconds");
    row.parameter = j.at("parameter").get<std::string>();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(source + ": " + e.what());
  }
  return row;
}

std::string SweepSummaryJson(const std::vector<SweepRow>& rows, const std::string& parameter)
{
  Json j;
  j["format"] = "bender-sweep-summary";
  j["version"] = 1;
  j["parameter"] = parameter;
  j["units"] = { { "fraction", "of each warp's motion" },
    { "radius", "mm" },
    { "pressureDropPa", "Pa, inlet minus the outlets' flow-weighted mean" },
    { "splitPercent", "% of the inlet's flow" },
    { "flowRateMlPerMin", "ml/min" },
    { "wallShearStress", "Pa; areas in mm^2 (low: below 0.4 Pa, high: above 15 Pa)" } };
  j["rows"] = Json::array();
  j["missing"] = Json::array();
  for (const SweepRow& row : rows)
  {
    j["rows"].push_back(RowJson(row));
    if (row.state != "solved")
    {
      j["missing"].push_back(
        { { "id", row.id }, { "state", row.state }, { "reason", row.reason }, { "log", row.log } });
    }
  }
  return j.dump(2) + "\n";
}

std::string SweepSummaryCsv(const std::vector<SweepRow>& rows)
{
  const std::vector<std::string> outlets = OutletNames(rows);
  std::ostringstream s;
  s << "id,parameter,value,plan,original,state,reason,bend_angle_deg,length_change_percent,"
       "min_radius_mm,pressure_drop_pa";
  for (const std::string& name : outlets)
  {
    s << ",split_" << name << "_percent,pressure_drop_" << name << "_pa";
  }
  s << ",wss_mean_pa,wss_max_pa,wss_p99_pa,low_wss_area_mm2,high_wss_area_mm2,mesh_cells,"
       "iterations,converged,hash\n";
  for (const SweepRow& row : rows)
  {
    const bool solved = row.state == "solved";
    const bool wss = solved && row.wallShearStress;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s << row.id << ',' << row.parameter << ',' << CsvNumber(row.value) << ','
      << CsvText(row.planName) << ',' << (row.original ? "yes" : "no") << ',' << row.state << ','
      << CsvText(row.reason) << ',' << CsvNumber(row.measures.bendAngle) << ','
      << CsvNumber(row.measures.lengthChange) << ',' << CsvNumber(row.measures.minRadius) << ','
      << CsvNumber(solved ? row.pressureDrop : nan);
    for (const std::string& name : outlets)
    {
      const auto it = std::find_if(row.outlets.begin(),
        row.outlets.end(),
        [&name](const SweepOutlet& o) { return o.name == name; });
      const bool known = solved && it != row.outlets.end();
      s << ',' << CsvNumber(known ? it->splitPercent : nan) << ','
        << CsvNumber(known ? it->pressureDrop : nan);
    }
    s << ',' << CsvNumber(wss ? row.wssMean : nan) << ',' << CsvNumber(wss ? row.wssMax : nan)
      << ',' << CsvNumber(wss ? row.wssP99 : nan) << ',' << CsvNumber(wss ? row.lowWssArea : nan)
      << ',' << CsvNumber(wss ? row.highWssArea : nan) << ','
      << (solved ? std::to_string(row.meshCells) : "") << ','
      << (solved ? std::to_string(row.iterations) : "") << ','
      << (solved ? (row.converged ? "yes" : "no") : "") << ',' << row.hash << '\n';
  }
  return s.str();
}

void WriteSweepSummary(const std::vector<SweepRow>& rows,
  const std::string& parameter,
  const std::string& folder,
  SweepResult& result,
  bool plot)
{
  const std::filesystem::path dir(folder);
  result.summaryCsv = (dir / "summary.csv").string();
  result.summaryJson = (dir / "summary.json").string();
  std::string problem;
  if (!AtomicWriteText(result.summaryCsv, SweepSummaryCsv(rows), problem) ||
    !AtomicWriteText(result.summaryJson, SweepSummaryJson(rows, parameter), problem))
  {
    throw InputError(folder + ": cannot write the summary: " + problem);
  }
  if (!plot)
  {
    result.plotProblem = "summary.png is left to the caller";
    return;
  }
  result.summaryPng = (dir / "summary.png").string();
  try
  {
    WriteSweepPlot(rows, parameter, result.summaryPng);
  }
  catch (const EnvironmentError& e)
  {
    result.plotProblem = e.what();
    result.summaryPng.clear();
  }
}

} // namespace bender
