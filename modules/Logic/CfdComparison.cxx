#include "CfdComparison.h"

#include "CfdFlowResults.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace bender
{
namespace
{
CfdComparisonRow Row(std::string key,
  std::string label,
  std::string unit,
  CfdRowKind kind,
  std::optional<double> a,
  std::optional<double> b)
{
  CfdComparisonRow row;
  row.key = std::move(key);
  row.label = std::move(label);
  row.unit = std::move(unit);
  row.kind = kind;
  row.a = a;
  row.b = b;
  return row;
}

double Floor(CfdRowKind kind, const CfdHighlightRule& rule)
{
  switch (kind)
  {
    case CfdRowKind::Pressure:
      return rule.pressureFloor;
    case CfdRowKind::Split:
      return rule.splitFloor;
    case CfdRowKind::FlowRate:
      return rule.flowRateFloor;
    case CfdRowKind::Stress:
      return rule.stressFloor;
    case CfdRowKind::Area:
      return rule.areaFloor;
    case CfdRowKind::Geometry:
    case CfdRowKind::Mesh:
    case CfdRowKind::Run:
      break;
  }
  return 0.0;
}

/// A row of the table read from one part of the results (an end, the WSS statistics).
template<typename Part>
struct Quantity
{
  const char* key;
  std::string label;
  const char* unit;
  CfdRowKind kind;
  double (*get)(const Part&);
};

const CfdEndFlow* FindEnd(const CfdFlowResults& results, const std::string& name)
{
  for (const CfdEndFlow& end : results.ends)
  {
    if (end.name == name)
    {
      return &end;
    }
  }
  return nullptr;
}

// The ends of both cases with the given role: A's in order, then B's that A lacks.
std::vector<std::string> EndNames(const CfdFlowResults& a, const CfdFlowResults& b, bool inlet)
{
  std::vector<std::string> names;
  for (const CfdFlowResults* results : { &a, &b })
  {
    for (const CfdEndFlow& end : results->ends)
    {
      if ((end.role == PatchType::Inlet) == inlet &&
        std::find(names.begin(), names.end(), end.name) == names.end())
      {
        names.push_back(end.name);
      }
    }
  }
  return names;
}

std::string RunState(const CfdFlowResults& results)
{
  return (results.run.converged ? "converged at " : "stopped at ") +
    std::to_string(results.run.iterations);
}

void AddOutletRows(const CfdFlowResults& a,
  const CfdFlowResults& b,
  std::vector<CfdComparisonRow>& rows)
{
  const std::vector<std::string> outlets = EndNames(a, b, false);
  const Quantity<CfdEndFlow> quantities[] = {
    { "pressureDrop",
      "Pressure drop to ",
      "Pa",
      CfdRowKind::Pressure,
      [](const CfdEndFlow& e) { return e.pressureDropPa; } },
    { "split",
      "Flow split to ",
      "%",
      CfdRowKind::Split,
      [](const CfdEndFlow& e) { return e.splitPercent; } },
    { "flowRate",
      "Flow rate through ",
      "ml/min",
      CfdRowKind::FlowRate,
      [](const CfdEndFlow& e) { return e.flowRateMlPerMin; } },
  };
  for (const auto& q : quantities)
  {
    for (const std::string& name : outlets)
    {
      const CfdEndFlow* ea = FindEnd(a, name);
      const CfdEndFlow* eb = FindEnd(b, name);
      rows.push_back(Row(std::string(q.key) + "." + name,
        q.label + name,
        q.unit,
        q.kind,
        ea ? std::optional<double>(q.get(*ea)) : std::nullopt,
        eb ? std::optional<double>(q.get(*eb)) : std::nullopt));
    }
  }
}

std::string Threshold(double pascal)
{
  std::ostringstream text;
  text << pascal << " Pa";
  return text.str();
}

void AddWallRows(const CfdFlowResults& a,
  const CfdFlowResults& b,
  std::vector<CfdComparisonRow>& rows)
{
  const Quantity<CfdWallShearStats> quantities[] = {
    { "wss.mean",
      "WSS mean (area-weighted)",
      "Pa",
      CfdRowKind::Stress,
      [](const CfdWallShearStats& w) { return w.meanPa; } },
    { "wss.max",
      "WSS max",
      "Pa",
      CfdRowKind::Stress,
      [](const CfdWallShearStats& w) { return w.maxPa; } },
    { "wss.p99",
      "WSS 99th percentile",
      "Pa",
      CfdRowKind::Stress,
      [](const CfdWallShearStats& w) { return w.percentile99Pa; } },
    { "wss.lowArea",
      "Wall area with WSS < " + Threshold(kLowWallShearStressPa),
      "mm^2",
      CfdRowKind::Area,
      [](const CfdWallShearStats& w) { return w.lowAreaMm2; } },
    { "wss.highArea",
      "Wall area with WSS > " + Threshold(kHighWallShearStressPa),
      "mm^2",
      CfdRowKind::Area,
      [](const CfdWallShearStats& w) { return w.highAreaMm2; } },
    { "wall.area",
      "Wall area",
      "mm^2",
      CfdRowKind::Geometry,
      [](const CfdWallShearStats& w) { return w.wallAreaMm2; } },
  };
  for (const auto& q : quantities)
  {
    rows.push_back(
      Row(q.key, q.label, q.unit, q.kind, q.get(a.wallShearStress), q.get(b.wallShearStress)));
  }
}

void AddCaseRows(const CfdFlowResults& a,
  const CfdFlowResults& b,
  std::vector<CfdComparisonRow>& rows)
{
  rows.push_back(Row("inlet.flowRate",
    "Inlet flow rate",
    "ml/min",
    CfdRowKind::FlowRate,
    a.inletFlowRateMlPerMin,
    b.inletFlowRateMlPerMin));
  rows.push_back(Row("mesh.cells",
    "Mesh cells",
    "",
    CfdRowKind::Mesh,
    static_cast<double>(a.meshCells),
    static_cast<double>(b.meshCells)));
  CfdComparisonRow run = Row("run.iterations",
    "Solver, iterations",
    "",
    CfdRowKind::Run,
    static_cast<double>(a.run.iterations),
    static_cast<double>(b.run.iterations));
  run.textA = RunState(a);
  run.textB = RunState(b);
  if (!a.run.converged || !b.run.converged)
  {
    run.highlighted = true;
    run.note = std::string(!a.run.converged && !b.run.converged ? "neither" : "a case") +
      " did not meet the residual control: its numbers are not final";
  }
  rows.push_back(run);
}
} // namespace

void CompareCfdRow(CfdComparisonRow& row, const CfdHighlightRule& rule)
{
  row.difference.reset();
  row.relative.reset();
  if (row.a && row.b)
  {
    row.difference = *row.b - *row.a;
    if (*row.a != 0.0)
    {
      row.relative = *row.difference / std::abs(*row.a);
    }
  }
  if (row.kind == CfdRowKind::Run)
  {
    return; // highlighted by its state (AddCaseRows), not by its iteration count
  }
  if (!row.a || !row.b)
  {
    row.highlighted = true;
    row.note = row.a ? "only in A" : "only in B";
    return;
  }
  if (row.kind == CfdRowKind::Mesh || row.kind == CfdRowKind::Geometry)
  {
    row.highlighted = false;
    return;
  }
  const bool aboveFloor = std::abs(*row.difference) > Floor(row.kind, rule);
  const bool aboveRelative = !row.relative || std::abs(*row.relative) > rule.relative;
  row.highlighted = aboveFloor && aboveRelative;
}

CfdComparison CompareCfdResults(const CfdFlowResults& a,
  const CfdFlowResults& b,
  const CfdHighlightRule& rule)
{
  CfdComparison comparison;
  comparison.rule = rule;
  AddOutletRows(a, b, comparison.rows);
  AddWallRows(a, b, comparison.rows);
  AddCaseRows(a, b, comparison.rows);
  for (CfdComparisonRow& row : comparison.rows)
  {
    CompareCfdRow(row, rule);
  }
  const std::vector<std::string> inlets = EndNames(a, b, true);
  if (inlets.size() > 1)
  {
    comparison.notes.push_back("the inlets differ (" + inlets[0] + ", " + inlets[1] +
      "): the cases are not fed at the same end");
  }
  return comparison;
}

int CountHighlighted(const CfdComparison& comparison)
{
  return static_cast<int>(std::count_if(comparison.rows.begin(),
    comparison.rows.end(),
    [](const CfdComparisonRow& row) { return row.highlighted; }));
}

std::string FormatCfdValue(const std::optional<double>& value, int decimals)
{
  if (!value)
  {
    return "-";
  }
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, *value);
  return text;
}

int CfdRowDecimals(const CfdComparisonRow& row)
{
  switch (row.kind)
  {
    case CfdRowKind::Stress:
      return 2;
    case CfdRowKind::Mesh:
    case CfdRowKind::Run:
      return 0;
    default:
      return 1;
  }
}

std::string DescribeHighlightRule(const CfdHighlightRule& rule)
{
  std::ostringstream text;
  text << "highlighted (*): |B - A| above " << rule.relative * 100.0
       << " % of |A| and above the quantity's floor (pressure " << rule.pressureFloor
       << " Pa, split " << rule.splitFloor << " percentage point, flow " << rule.flowRateFloor
       << " ml/min, WSS " << rule.stressFloor << " Pa, area " << rule.areaFloor
       << " mm^2); an outlet of one case only; a run that did not converge";
  return text.str();
}

std::string CfdComparisonToText(const CfdComparison& comparison)
{
  struct Line
  {
    std::string cells[5];
    bool mark = false;
  };
  std::vector<Line> lines;
  lines.push_back({ { "quantity", comparison.labelA, comparison.labelB, "B - A", "rel." } });
  for (const CfdComparisonRow& row : comparison.rows)
  {
    const int decimals = CfdRowDecimals(row);
    const std::string unit = row.unit.empty() ? "" : " (" + row.unit + ")";
    Line line;
    line.cells[0] = row.label + unit;
    line.cells[1] = row.textA.empty() ? FormatCfdValue(row.a, decimals) : row.textA;
    line.cells[2] = row.textB.empty() ? FormatCfdValue(row.b, decimals) : row.textB;
    line.cells[3] = row.kind == CfdRowKind::Run ? "" : FormatCfdValue(row.difference, decimals);
    line.cells[4] = row.relative && row.kind != CfdRowKind::Run
      ? FormatCfdValue(*row.relative * 100.0, 1) + " %"
      : "";
    line.mark = row.highlighted;
    lines.push_back(line);
  }
  size_t width[5] = {};
  for (const Line& line : lines)
  {
    for (int c = 0; c < 5; ++c)
    {
      width[c] = std::max(width[c], line.cells[c].size());
    }
  }
  std::ostringstream text;
  for (const Line& line : lines)
  {
    text << (line.mark ? "* " : "  ") << line.cells[0]
         << std::string(width[0] - line.cells[0].size(), ' ');
    for (int c = 1; c < 5; ++c)
    {
      text << "  " << std::string(width[c] - line.cells[c].size(), ' ') << line.cells[c];
    }
    text << "\n";
  }
  for (const CfdComparisonRow& row : comparison.rows)
  {
    if (row.highlighted && !row.note.empty())
    {
      text << row.label << ": " << row.note << "\n";
    }
  }
  for (const std::string& note : comparison.notes)
  {
    text << "note: " << note << "\n";
  }
  text << DescribeHighlightRule(comparison.rule) << "\n";
  return text.str();
}

std::string CfdComparisonToJson(const CfdComparison& comparison, int indent)
{
  auto value = [](const std::optional<double>& v)
  { return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr); };
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const CfdComparisonRow& row : comparison.rows)
  {
    nlohmann::ordered_json j = { { "key", row.key },
      { "label", row.label },
      { "unit", row.unit },
      { "a", value(row.a) },
      { "b", value(row.b) },
      { "difference", value(row.difference) },
      { "relativeDifference", value(row.relative) },
      { "highlighted", row.highlighted },
      { "note", row.note } };
    if (!row.textA.empty() || !row.textB.empty())
    {
      j["stateA"] = row.textA;
      j["stateB"] = row.textB;
    }
    rows.push_back(j);
  }
  const CfdHighlightRule& r = comparison.rule;
  nlohmann::ordered_json j = { { "format", "bender-flow-comparison" },
    { "version", 1 },
    { "caseA", comparison.labelA },
    { "caseB", comparison.labelB },
    { "rule",
      { { "relative", r.relative },
        { "pressureFloor_Pa", r.pressureFloor },
        { "splitFloor_percentPoints", r.splitFloor },
        { "flowRateFloor_mlPerMin", r.flowRateFloor },
        { "stressFloor_Pa", r.stressFloor },
        { "areaFloor_mm2", r.areaFloor },
        { "text", DescribeHighlightRule(r) } } },
    { "rows", rows },
    { "highlighted", CountHighlighted(comparison) },
    { "notes", comparison.notes } };
  return j.dump(indent);
}

} // namespace bender
