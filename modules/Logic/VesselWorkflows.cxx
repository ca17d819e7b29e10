#include "VesselWorkflows.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "MeshIO.h"
#include "StringUtil.h"
#include "VesselArrayNames.h"
#include "VesselMeasureTable.h"
#include "WarpPlanIO.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace bender
{
namespace
{
using Json = nlohmann::ordered_json;

vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  try
  {
    return ReadMesh(path);
  }
  catch (const MeshIOError& e)
  {
    throw InputError(e.what());
  }
}

// Rounded for the reader: 1e-4 mm is far below any segmentation's resolution.
double R4(double v)
{
  return std::round(v * 1e4) / 1e4;
}

Json P(const Point3& p)
{
  return Json::array({ R4(p[0]), R4(p[1]), R4(p[2]) });
}

const char* KindName(EndpointKind k)
{
  switch (k)
  {
    case EndpointKind::OpenEnd:
      return "open end";
    case EndpointKind::VoronoiTip:
      return "vessel tip";
    case EndpointKind::Seed:
      return "seed";
  }
  return "unknown";
}

Json BranchJson(const BranchMeasures& b)
{
  Json j;
  j["id"] = b.branchId;
  j["parent"] = b.parentBranchId;
  j["outlets"] = Json(std::vector<int>(b.outlets.begin(), b.outlets.end()));
  j["endpoint"] = b.endpointId;
  j["startBifurcation"] = b.startBifurcationId;
  j["endBifurcation"] = b.endBifurcationId;
  for (const VesselMeasure& m : VesselMeasureTable())
  {
    j[m.key] = R4(m.get(b));
  }
  j["minRadiusPosition"] = P(b.minRadiusPosition);
  j["start"] = P(b.start);
  j["end"] = P(b.end);
  j["startTangent"] = P(b.startTangent);
  j["endTangent"] = P(b.endTangent);
  return j;
}

Json ResultJson(const CenterlineWorkflowResult& r)
{
  Json j;
  Json ends = Json::array();
  for (const auto& e : r.centerlines.endpoints)
  {
    ends.push_back({ { "position", P(e.position) },
      { "radius", R4(e.radius) },
      { "kind", KindName(e.kind) },
      { "inlet", e.inlet },
      { "reached", e.reached } });
  }
  j["endpoints"] = ends;
  Json bifs = Json::array();
  for (const auto& b : r.measures.bifurcations)
  {
    Json angles = Json::array();
    for (double a : b.parentChildAngles)
    {
      angles.push_back(R4(a));
    }
    bifs.push_back({ { "id", b.id },
      { "position", P(b.position) },
      { "parent", b.parentBranchId },
      { "children", b.childBranchIds },
      { "parentChildAngles", angles },
      { "childrenAngle", R4(b.childrenAngle) } });
  }
  j["bifurcations"] = bifs;
  Json branches = Json::array();
  for (const auto& b : r.measures.branches)
  {
    branches.push_back(BranchJson(b));
  }
  j["branches"] = branches;
  j["step"] = R4(r.centerlines.step);
  j["warnings"] = r.centerlines.warnings;
  return j;
}

CenterlineWorkflowResult Compute(vtkPolyData* surface,
  const std::string& name,
  const std::vector<Point3>& seeds)
{
  CenterlineWorkflowResult result;
  result.surface = surface;
  CenterlineOptions options;
  options.seeds = seeds;
  try
  {
    result.centerlines = ComputeCenterlines(surface, options);
  }
  catch (const std::invalid_argument& e)
  {
    throw InputError(name + ": " + e.what());
  }
  if (!result.centerlines.ok)
  {
    throw InputError(name + ": " + result.centerlines.message);
  }
  result.measures = MeasureBranches(result.centerlines.branches);
  return result;
}
} // namespace

Point3 ParsePoint(const std::string& text, const std::string& what)
{
  Point3 p{ { 0, 0, 0 } };
  std::string rest = text;
  for (int c = 0; c < 3; ++c)
  {
    const auto comma = rest.find(',');
    const std::string field = c < 2 ? rest.substr(0, comma) : rest;
    if ((c < 2 && comma == std::string::npos) || field.empty())
    {
      throw InputError(what + ": '" + text + "' is not x,y,z");
    }
    std::size_t used = 0;
    try
    {
      p[c] = std::stod(field, &used);
    }
    catch (const std::exception&) // std::stod's invalid_argument and out_of_range
    {
      used = 0;
    }
    if (used != field.size() || !std::isfinite(p[c]))
    {
      throw InputError(what + ": '" + text + "' is not x,y,z (three finite numbers)");
    }
    if (c < 2)
    {
      rest = rest.substr(comma + 1);
    }
  }
  return p;
}

CenterlineWorkflowResult ComputeCenterlinesOfFile(const CenterlineWorkflowOptions& options)
{
  if (!options.output.empty())
  {
    if (!EndsWith(options.output, ".vtp") && !EndsWith(options.output, ".vtk"))
    {
      throw InputError(DisplayName(options.output) +
        ": centerlines are written as .vtp or .vtk (polylines with point and cell data)");
    }
    if (SameFile(options.input, options.output))
    {
      throw InputError(DisplayName(options.output) + ": is the input surface; not overwritten");
    }
  }
  vtkSmartPointer<vtkPolyData> surface = Read(options.input);
  CenterlineWorkflowResult result = Compute(surface, DisplayName(options.input), options.seeds);
  if (!options.output.empty())
  {
    try
    {
      WriteMesh(result.centerlines.branches, options.output);
    }
    catch (const MeshIOError& e)
    {
      throw InputError(e.what());
    }
  }
  return result;
}

MeasureWorkflowResult MeasureVessels(const MeasureWorkflowOptions& options)
{
  if (!options.after.empty() && !options.plan.empty())
  {
    throw InputError("measure: give either an after surface or a plan, not both");
  }
  MeasureWorkflowResult result;
  result.before = Compute(Read(options.input), DisplayName(options.input), options.seeds);
  vtkSmartPointer<vtkPolyData> after;
  std::string afterName;
  if (!options.after.empty())
  {
    after = Read(options.after);
    afterName = DisplayName(options.after);
  }
  else if (!options.plan.empty())
  {
    const WarpPlan plan = ReadWarpPlan(options.plan); // WarpPlanError: an InputError
    ApplyPlanOptions applyOptions;
    applyOptions.planName = DisplayName(options.plan);
    after = ApplyPlan(result.before.surface, plan, applyOptions).output;
    afterName = DisplayName(options.input) + " after " + DisplayName(options.plan);
  }
  if (!after)
  {
    return result;
  }
  const std::vector<Point3> seeds =
    MatchedSeeds(result.before.surface, after, result.before.centerlines.endpoints);
  result.after = Compute(after, afterName, seeds);
  const VesselComparison comparison =
    CompareVessels(result.before.centerlines.branches, result.after->centerlines.branches);
  for (const auto& pair : comparison.pairs)
  {
    BranchComparison c;
    if (pair.beforeIndex >= 0)
    {
      c.before = comparison.before.branches[pair.beforeIndex];
    }
    if (pair.afterIndex >= 0)
    {
      c.after = comparison.after.branches[pair.afterIndex];
    }
    if (c.before && c.after)
    {
      c.startTurn = AngleDegrees(c.before->startTangent, c.after->startTangent);
      c.endTurn = AngleDegrees(c.before->endTangent, c.after->endTangent);
    }
    else
    {
      result.warnings.push_back(std::string("a branch ") +
        (c.before ? "before has no match after" : "after has no match before") +
        " (the branch graphs differ)");
    }
    result.branches.push_back(c);
  }
  return result;
}

std::string CenterlinesToJson(const CenterlineWorkflowResult& result)
{
  return ResultJson(result).dump(2);
}

std::string MeasurementsToJson(const MeasureWorkflowResult& result)
{
  Json j;
  j["before"] = ResultJson(result.before);
  if (result.after)
  {
    j["after"] = ResultJson(*result.after);
    Json comparison = Json::array();
    for (const auto& c : result.branches)
    {
      Json e;
      e["before"] = c.before ? BranchJson(*c.before) : Json();
      e["after"] = c.after ? BranchJson(*c.after) : Json();
      if (c.before && c.after)
      {
        Json change;
        for (const VesselMeasure& m : VesselMeasureTable())
        {
          change[m.key] = R4(m.get(*c.after) - m.get(*c.before));
        }
        change["startTurn"] = R4(c.startTurn);
        change["endTurn"] = R4(c.endTurn);
        e["change"] = change;
      }
      comparison.push_back(e);
    }
    j["comparison"] = comparison;
    j["warnings"] = result.warnings;
  }
  return j.dump(2);
}

std::string MeasurementsToText(const MeasureWorkflowResult& result)
{
  std::vector<const VesselMeasure*> columns;
  for (const VesselMeasure& m : VesselMeasureTable())
  {
    if (m.text)
    {
      columns.push_back(&m);
    }
  }
  auto width = [](const VesselMeasure& m)
  { return std::max<int>(10, static_cast<int>(MeasureTitle(m).size())); };
  std::ostringstream out;
  char cell[64];
  auto header = [&](const char* first)
  {
    out << first;
    for (const VesselMeasure* m : columns)
    {
      std::snprintf(cell, sizeof(cell), "  %*s", width(*m), MeasureTitle(*m).c_str());
      out << cell;
    }
  };
  auto table = [&](const CenterlineWorkflowResult& r, const char* title)
  {
    out << title << ": " << r.centerlines.endpoints.size() << " endpoints, "
        << r.measures.branches.size() << " branches, " << r.measures.bifurcations.size()
        << " bifurcations\n";
    header("  branch parent");
    out << "\n";
    for (const auto& b : r.measures.branches)
    {
      std::snprintf(cell, sizeof(cell), "  %6d %6d", b.branchId, b.parentBranchId);
      out << cell;
      for (const VesselMeasure* m : columns)
      {
        std::snprintf(cell, sizeof(cell), "  %*.*f", width(*m), m->decimals, m->get(b));
        out << cell;
      }
      out << "\n";
    }
    for (const auto& b : r.measures.bifurcations)
    {
      std::snprintf(cell,
        sizeof(cell),
        "  bifurcation %d: angle between children %.1f deg\n",
        b.id,
        b.childrenAngle);
      out << cell;
    }
    for (const auto& w : r.centerlines.warnings)
    {
      out << "  warning: " << w << "\n";
    }
  };
  table(result.before, "before");
  if (result.after)
  {
    table(*result.after, "after");
    out << "change (after - before)\n";
    header("  branch");
    out << "  start turn    end turn\n";
    for (const auto& c : result.branches)
    {
      if (!c.before || !c.after)
      {
        continue;
      }
      std::snprintf(cell, sizeof(cell), "  %6d", c.before->branchId);
      out << cell;
      for (const VesselMeasure* m : columns)
      {
        std::snprintf(cell,
          sizeof(cell),
          "  %+*.*f",
          width(*m),
          m->decimals,
          m->get(*c.after) - m->get(*c.before));
        out << cell;
      }
      std::snprintf(cell, sizeof(cell), "  %10.1f  %10.1f\n", c.startTurn, c.endTurn);
      out << cell;
    }
    for (const auto& w : result.warnings)
    {
      out << "  warning: " << w << "\n";
    }
  }
  return out.str();
}

} // namespace bender
