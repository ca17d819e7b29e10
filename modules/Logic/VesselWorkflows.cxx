#include "VesselWorkflows.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "MeshIO.h"
#include "VesselArrayNames.h"
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

std::string BaseName(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool EndsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

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

double Angle(const Point3& a, const Point3& b)
{
  const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (na <= 0 || nb <= 0)
  {
    return 0.0;
  }
  const double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (na * nb);
  return std::acos(std::max(-1.0, std::min(1.0, c))) * 180.0 / 3.14159265358979323846;
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
  j["id"] = b.BranchId;
  j["parent"] = b.ParentBranchId;
  j["outlets"] = Json(std::vector<int>(b.Outlets.begin(), b.Outlets.end()));
  j["endpoint"] = b.EndpointId;
  j["startBifurcation"] = b.StartBifurcationId;
  j["endBifurcation"] = b.EndBifurcationId;
  j["length"] = R4(b.Length);
  j["tortuosity"] = R4(b.Tortuosity);
  j["maxCurvature"] = R4(b.MaxCurvature);
  j["meanCurvature"] = R4(b.MeanCurvature);
  j["bendAngle"] = R4(b.BendAngle);
  j["minRadius"] = R4(b.MinRadius);
  j["meanRadius"] = R4(b.MeanRadius);
  j["maxRadius"] = R4(b.MaxRadius);
  j["minRadiusPosition"] = P(b.MinRadiusPosition);
  j["minRadiusAbscissa"] = R4(b.MinRadiusAbscissa);
  j["start"] = P(b.Start);
  j["end"] = P(b.End);
  j["startTangent"] = P(b.StartTangent);
  j["endTangent"] = P(b.EndTangent);
  return j;
}

Json ResultJson(const CenterlineWorkflowResult& r)
{
  Json j;
  Json ends = Json::array();
  for (const auto& e : r.centerlines.Endpoints)
  {
    ends.push_back({ { "position", P(e.Position) },
      { "radius", R4(e.Radius) },
      { "kind", KindName(e.Kind) },
      { "inlet", e.Inlet },
      { "reached", e.Reached } });
  }
  j["endpoints"] = ends;
  Json bifs = Json::array();
  for (const auto& b : r.measures.Bifurcations)
  {
    Json angles = Json::array();
    for (double a : b.ParentChildAngles)
    {
      angles.push_back(R4(a));
    }
    bifs.push_back({ { "id", b.Id },
      { "position", P(b.Position) },
      { "parent", b.ParentBranchId },
      { "children", b.ChildBranchIds },
      { "parentChildAngles", angles },
      { "childrenAngle", R4(b.ChildrenAngle) } });
  }
  j["bifurcations"] = bifs;
  Json branches = Json::array();
  for (const auto& b : r.measures.Branches)
  {
    branches.push_back(BranchJson(b));
  }
  j["branches"] = branches;
  j["step"] = R4(r.centerlines.Step);
  j["warnings"] = r.centerlines.Warnings;
  return j;
}

CenterlineWorkflowResult Compute(vtkPolyData* surface,
  const std::string& name,
  const std::vector<Point3>& seeds)
{
  CenterlineWorkflowResult result;
  result.surface = surface;
  CenterlineOptions options;
  options.Seeds = seeds;
  try
  {
    result.centerlines = ComputeCenterlines(surface, options);
  }
  catch (const std::invalid_argument& e)
  {
    throw InputError(name + ": " + e.what());
  }
  if (!result.centerlines.Ok)
  {
    throw InputError(name + ": " + result.centerlines.Message);
  }
  result.measures = MeasureBranches(result.centerlines.Branches);
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
    catch (const std::exception&)
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
      throw InputError(BaseName(options.output) +
        ": centerlines are written as .vtp or .vtk (polylines with point and cell data)");
    }
    if (SameFile(options.input, options.output))
    {
      throw InputError(BaseName(options.output) + ": is the input surface; not overwritten");
    }
  }
  vtkSmartPointer<vtkPolyData> surface = Read(options.input);
  CenterlineWorkflowResult result = Compute(surface, BaseName(options.input), options.seeds);
  if (!options.output.empty())
  {
    try
    {
      WriteMesh(result.centerlines.Branches, options.output);
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
  result.before = Compute(Read(options.input), BaseName(options.input), options.seeds);
  vtkSmartPointer<vtkPolyData> after;
  std::string afterName;
  if (!options.after.empty())
  {
    after = Read(options.after);
    afterName = BaseName(options.after);
  }
  else if (!options.plan.empty())
  {
    WarpPlan plan;
    try
    {
      plan = ReadWarpPlan(options.plan);
    }
    catch (const std::exception& e)
    {
      throw InputError(e.what());
    }
    ApplyPlanOptions applyOptions;
    applyOptions.planName = BaseName(options.plan);
    after = ApplyPlan(result.before.surface, plan, applyOptions).output;
    afterName = BaseName(options.input) + " after " + BaseName(options.plan);
  }
  if (!after)
  {
    return result;
  }
  const std::vector<Point3> seeds =
    MatchedSeeds(result.before.surface, after, result.before.centerlines.Endpoints);
  result.after = Compute(after, afterName, seeds);
  const VesselComparison comparison =
    CompareVessels(result.before.centerlines.Branches, result.after->centerlines.Branches);
  for (const auto& pair : comparison.Pairs)
  {
    BranchComparison c;
    if (pair.BeforeIndex >= 0)
    {
      c.before = comparison.Before.Branches[pair.BeforeIndex];
    }
    if (pair.AfterIndex >= 0)
    {
      c.after = comparison.After.Branches[pair.AfterIndex];
    }
    if (c.before && c.after)
    {
      c.startTurn = Angle(c.before->StartTangent, c.after->StartTangent);
      c.endTurn = Angle(c.before->EndTangent, c.after->EndTangent);
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
        e["change"] = { { "length", R4(c.after->Length - c.before->Length) },
          { "tortuosity", R4(c.after->Tortuosity - c.before->Tortuosity) },
          { "bendAngle", R4(c.after->BendAngle - c.before->BendAngle) },
          { "minRadius", R4(c.after->MinRadius - c.before->MinRadius) },
          { "meanRadius", R4(c.after->MeanRadius - c.before->MeanRadius) },
          { "maxCurvature", R4(c.after->MaxCurvature - c.before->MaxCurvature) },
          { "startTurn", R4(c.startTurn) },
          { "endTurn", R4(c.endTurn) } };
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
  std::ostringstream out;
  char line[256];
  auto table = [&](const CenterlineWorkflowResult& r, const char* title)
  {
    out << title << ": " << r.centerlines.Endpoints.size() << " endpoints, "
        << r.measures.Branches.size() << " branches, " << r.measures.Bifurcations.size()
        << " bifurcations\n";
    out << "  branch parent  length  tortuosity  bend(deg)  max curv  min/mean/max radius\n";
    for (const auto& b : r.measures.Branches)
    {
      std::snprintf(line,
        sizeof(line),
        "  %6d %6d %7.2f %11.4f %10.2f %9.4f  %.2f / %.2f / %.2f\n",
        b.BranchId,
        b.ParentBranchId,
        b.Length,
        b.Tortuosity,
        b.BendAngle,
        b.MaxCurvature,
        b.MinRadius,
        b.MeanRadius,
        b.MaxRadius);
      out << line;
    }
    for (const auto& b : r.measures.Bifurcations)
    {
      std::snprintf(line,
        sizeof(line),
        "  bifurcation %d: angle between children %.1f deg\n",
        b.Id,
        b.ChildrenAngle);
      out << line;
    }
    for (const auto& w : r.centerlines.Warnings)
    {
      out << "  warning: " << w << "\n";
    }
  };
  table(result.before, "before");
  if (result.after)
  {
    table(*result.after, "after");
    out << "change (after - before)\n";
    out << "  branch  length  tortuosity  bend(deg)  min radius  start turn  end turn\n";
    for (const auto& c : result.branches)
    {
      if (!c.before || !c.after)
      {
        continue;
      }
      std::snprintf(line,
        sizeof(line),
        "  %6d %+7.2f %+11.4f %+10.2f %+11.3f %10.1f %9.1f\n",
        c.before->BranchId,
        c.after->Length - c.before->Length,
        c.after->Tortuosity - c.before->Tortuosity,
        c.after->BendAngle - c.before->BendAngle,
        c.after->MinRadius - c.before->MinRadius,
        c.startTurn,
        c.endTurn);
      out << line;
    }
    for (const auto& w : result.warnings)
    {
      out << "  warning: " << w << "\n";
    }
  }
  return out.str();
}

} // namespace bender
