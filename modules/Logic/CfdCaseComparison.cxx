#include "CfdCaseComparison.h"

#include "BenderErrors.h"
#include "CfdCaseFile.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "RibbonLengthChange.h"
#include "StringUtil.h"
#include "VesselCenterlines.h"
#include "VesselMeasures.h"
#include "WarpPlanIO.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace bender
{
namespace fs = std::filesystem;

namespace
{
/// The arrays the report colours by; a surface without them does not match the results.
const char* const SurfaceFields[] = { kPressureArrayName, kWallShearStressMagnitudeArrayName };

/// The ends of a case (bender-case.json): name -> centre (mm, LPS), the inlet first.
struct CaseEnds
{
  std::string inlet;
  std::map<std::string, Point3> centres;
};

CaseEnds ReadCaseEnds(const fs::path& dir)
{
  const fs::path record = dir / kCfdCaseJson;
  std::ifstream in(record);
  if (!in)
  {
    throw InputError(dir.string() + ": not a Bender CFD case (no " + kCfdCaseJson +
      "; write one with bender-cli cfd-case)");
  }
  CaseEnds ends;
  try
  {
    const nlohmann::json j = nlohmann::json::parse(in);
    ends.inlet = j.at("inlet").get<std::string>();
    for (const auto& p : j.at("patches"))
    {
      const std::string type = p.at("type").get<std::string>();
      if (type == "wall")
      {
        continue;
      }
      const auto c = p.at("centre").get<std::array<double, 3>>();
      // The case is in metres; the surfaces and the report in millimetres.
      ends.centres[p.at("name").get<std::string>()] = { c[0] * 1e3, c[1] * 1e3, c[2] * 1e3 };
    }
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(record.string() + ": " + e.what());
  }
  return ends;
}

ComparedCfdCase ReadCase(const std::string& directory, const std::string& label)
{
  const fs::path dir(directory);
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
  {
    throw InputError(directory + ": no such case folder");
  }
  const CaseEnds ends = ReadCaseEnds(dir);
  const fs::path flow = dir / kCfdResultsFolder / kCfdFlowJson;
  if (!fs::exists(flow, ec))
  {
    const bool run = fs::exists(dir / "postProcessing", ec);
    throw InputError(directory +
      (run ? ": results missing (no results/flow.json): run the case again to map them"
           : ": the case has not been run (no results): run bender-cli cfd-case --run"));
  }
  ComparedCfdCase c;
  c.directory = directory;
  c.label = label;
  c.results = ReadCfdFlowResults(directory);
  for (const CfdEndFlow& end : c.results.ends)
  {
    if (!ends.centres.count(end.name))
    {
      throw InputError(flow.string() + ": end '" + end.name +
        "' is not a patch of the case: the results do not match it (run it again)");
    }
  }
  const fs::path surface = dir / kCfdResultsFolder / kCfdSurfaceResults;
  if (!fs::exists(surface, ec))
  {
    throw InputError(directory + ": results missing (no results/surface.vtp)");
  }
  c.surface = ReadMesh(surface.string());
  for (const char* field : SurfaceFields)
  {
    if (!c.surface->GetPointData()->GetArray(field))
    {
      throw InputError(surface.string() + ": no point data " + field +
        ": the results do not match this version (run the case again)");
    }
  }
  return c;
}

// Seeds in the same name order for both cases: the inlet, then the outlets both have.
std::vector<std::string> SeedNames(const CaseEnds& a, const CaseEnds& b)
{
  std::vector<std::string> names{ a.inlet };
  for (const auto& [name, centre] : a.centres)
  {
    if (name != a.inlet && b.centres.count(name))
    {
      names.push_back(name);
    }
  }
  return names;
}

vtkSmartPointer<vtkPolyData> Branches(const ComparedCfdCase& c,
  const CaseEnds& ends,
  const std::vector<std::string>& names,
  std::vector<std::string>& unavailable)
{
  CenterlineOptions options;
  for (const std::string& name : names)
  {
    options.seeds.push_back(ends.centres.at(name));
  }
  const CenterlineResult result = ComputeCenterlines(c.surface, options);
  if (!result.ok)
  {
    unavailable.push_back("bend measures: no centerline of " + c.label + ": " + result.message);
    return nullptr;
  }
  return result.branches;
}

std::string BranchName(const BranchMeasures& branch, const std::vector<std::string>& names)
{
  std::string text;
  for (const int id : branch.outlets)
  {
    if (id >= 0 && id < static_cast<int>(names.size()))
    {
      text += (text.empty() ? "" : " + ") + names[id];
    }
  }
  if (branch.outlets.size() > 1)
  {
    return "trunk to " + text;
  }
  return text.empty() ? "branch " + std::to_string(branch.branchId) : text;
}

std::vector<BendBranchMeasures> MeasureBends(const ComparedCfdCase& a,
  const ComparedCfdCase& b,
  const ProgressReporter& progress,
  std::vector<std::string>& unavailable)
{
  const CaseEnds endsA = ReadCaseEnds(a.directory);
  const CaseEnds endsB = ReadCaseEnds(b.directory);
  if (endsA.inlet != endsB.inlet || !endsB.centres.count(endsA.inlet))
  {
    unavailable.push_back(
      "bend measures: the cases have different inlets (" + endsA.inlet + ", " + endsB.inlet + ")");
    return {};
  }
  const std::vector<std::string> names = SeedNames(endsA, endsB);
  progress.Report("centerlines", 0.0);
  const vtkSmartPointer<vtkPolyData> branchesA = Branches(a, endsA, names, unavailable);
  progress.ThrowIfCancelled("centerlines");
  progress.Report("centerlines", 0.5);
  const vtkSmartPointer<vtkPolyData> branchesB = Branches(b, endsB, names, unavailable);
  progress.ThrowIfCancelled("centerlines");
  progress.Report("centerlines", 1.0);
  if (!branchesA || !branchesB)
  {
    return {};
  }
  const VesselComparison comparison = CompareVessels(branchesA, branchesB);
  std::vector<BendBranchMeasures> bends;
  for (const BranchChange& pair : comparison.pairs)
  {
    BendBranchMeasures m;
    if (pair.beforeIndex >= 0)
    {
      const BranchMeasures& x = comparison.before.branches[pair.beforeIndex];
      m.name = BranchName(x, names);
      m.angleA = x.bendAngle, m.lengthA = x.length, m.minRadiusA = x.minRadius;
    }
    if (pair.afterIndex >= 0)
    {
      const BranchMeasures& y = comparison.after.branches[pair.afterIndex];
      m.name = m.name.empty() ? BranchName(y, names) : m.name;
      m.angleB = y.bendAngle, m.lengthB = y.length, m.minRadiusB = y.minRadius;
    }
    bends.push_back(m);
  }
  return bends;
}

PlanDescription DescribePlan(const std::string& file)
{
  const WarpPlan plan = ReadWarpPlan(file); // WarpPlanError: an InputError naming the file
  PlanDescription d;
  d.file = file;
  for (const char* key : { "name", "description", "note" })
  {
    const auto it = plan.extraFields.find(key);
    if (d.name.empty() && it != plan.extraFields.end())
    {
      const nlohmann::json value = nlohmann::json::parse(it->second, nullptr, false);
      d.name = value.is_string() ? value.get<std::string>() : std::string();
    }
  }
  for (const WarpSpec& warp : plan.warps)
  {
    PlanWarpMeasures m;
    const Point3 before{
      warp.initial.end.tangent.x, warp.initial.end.tangent.y, warp.initial.end.tangent.z
    };
    const Point3 after{
      warp.final.end.tangent.x, warp.final.end.tangent.y, warp.final.end.tangent.z
    };
    m.endTurn = AngleDegrees(before, after);
    m.lengthChange = RibbonLengthChange(warp);
    m.radius = warp.radius;
    d.warps.push_back(m);
  }
  d.preparedForCfd = !plan.cfdSteps.empty();
  return d;
}

nlohmann::ordered_json Optional(const std::optional<double>& v)
{
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}
} // namespace

CfdCaseComparison CompareCfdCases(const CompareCfdCasesOptions& options)
{
  if (options.caseA.empty() || options.caseB.empty())
  {
    throw InputError("compare: two case folders are needed");
  }
  std::error_code ec;
  if (fs::equivalent(options.caseA, options.caseB, ec))
  {
    throw InputError(options.caseB + ": the same case as " + options.caseA);
  }
  CfdCaseComparison c;
  options.progress.Report("read", 0.0);
  c.a = ReadCase(options.caseA, options.labelA);
  c.b = ReadCase(options.caseB, options.labelB);
  options.progress.Report("read", 1.0);
  c.table = CompareCfdResults(c.a.results, c.b.results, options.rule);
  c.table.labelA = options.labelA;
  c.table.labelB = options.labelB;
  if (!options.plan.empty())
  {
    c.plan = DescribePlan(options.plan);
  }
  else
  {
    c.unavailable.push_back("plan: none given (bender-cli compare --plan PLAN): the plan's "
                            "description and warps are not reported");
  }
  if (options.measureBends)
  {
    c.bends = MeasureBends(c.a, c.b, options.progress, c.unavailable);
  }
  return c;
}

std::string CfdCaseComparisonToJson(const CfdCaseComparison& c)
{
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(CfdComparisonToJson(c.table));
  j["cases"] = { { { "label", c.a.label }, { "folder", c.a.directory } },
    { { "label", c.b.label }, { "folder", c.b.directory } } };
  nlohmann::ordered_json bends = nlohmann::ordered_json::array();
  for (const BendBranchMeasures& m : c.bends)
  {
    bends.push_back({ { "branch", m.name },
      { "bendAngleA_deg", Optional(m.angleA) },
      { "bendAngleB_deg", Optional(m.angleB) },
      { "lengthA_mm", Optional(m.lengthA) },
      { "lengthB_mm", Optional(m.lengthB) },
      { "minRadiusA_mm", Optional(m.minRadiusA) },
      { "minRadiusB_mm", Optional(m.minRadiusB) } });
  }
  j["bends"] = bends;
  if (c.plan)
  {
    nlohmann::ordered_json warps = nlohmann::ordered_json::array();
    for (const PlanWarpMeasures& w : c.plan->warps)
    {
      warps.push_back({ { "endTurn_deg", w.endTurn },
        { "ribbonLengthChange_percent", w.lengthChange * 100.0 },
        { "radius_mm", w.radius } });
    }
    j["plan"] = { { "file", c.plan->file },
      { "name", c.plan->name },
      { "warps", warps },
      { "preparedForCfd", c.plan->preparedForCfd } };
  }
  else
  {
    j["plan"] = nullptr;
  }
  j["unavailable"] = c.unavailable;
  return j.dump(2);
}

std::vector<std::string> CfdMeshAndConvergenceLines(const CfdFlowResults& r)
{
  char line[256];
  std::vector<std::string> lines;
  std::snprintf(line,
    sizeof(line),
    "mesh: %lld cells, %.3g mm at the wall",
    r.meshCells,
    r.settings.cellSizeMm);
  lines.push_back(line);
  std::string run = "run: " +
    (r.run.status.empty() ? (r.run.converged ? "converged in " : "stopped at ") +
          std::to_string(r.run.iterations) + " iterations"
                          : r.run.status);
  if (run.find("residuals") == std::string::npos && !r.run.residuals.empty())
  {
    run += ", final residuals";
    for (const auto& [field, value] : r.run.residuals)
    {
      std::snprintf(line, sizeof(line), " %s %.2g", field.c_str(), value);
      run += line;
    }
  }
  lines.push_back(run);
  std::snprintf(line,
    sizeof(line),
    "inlet: %.1f ml/min, Reynolds number %.0f; mass imbalance %.2f %%",
    r.inletFlowRateMlPerMin,
    r.settings.reynolds,
    r.massImbalancePercent);
  lines.push_back(line);
  return lines;
}

std::string BendMeasuresToText(const CfdCaseComparison& c)
{
  std::ostringstream text;
  char line[256];
  if (c.plan)
  {
    text << "plan: " << DisplayName(c.plan->file)
         << (c.plan->name.empty() ? "" : " (" + c.plan->name + ")") << "\n";
    for (size_t i = 0; i < c.plan->warps.size(); ++i)
    {
      const PlanWarpMeasures& w = c.plan->warps[i];
      std::snprintf(line,
        sizeof(line),
        "  warp %zu: ribbon end turned %.1f deg, ribbon length %+.1f %%, R %.2f mm\n",
        i + 1,
        w.endTurn,
        w.lengthChange * 100.0,
        w.radius);
      text << line;
    }
  }
  if (!c.bends.empty())
  {
    text << "branches (" << c.a.label << " -> " << c.b.label << "):\n";
  }
  for (const BendBranchMeasures& m : c.bends)
  {
    text << "  " << m.name << ": bend angle " << FormatCfdValue(m.angleA, 1) << " -> "
         << FormatCfdValue(m.angleB, 1) << " deg, length " << FormatCfdValue(m.lengthA, 1) << " -> "
         << FormatCfdValue(m.lengthB, 1) << " mm, minimal radius "
         << FormatCfdValue(m.minRadiusA, 2) << " -> " << FormatCfdValue(m.minRadiusB, 2) << " mm\n";
  }
  for (const ComparedCfdCase* one : { &c.a, &c.b })
  {
    for (const std::string& line : CfdMeshAndConvergenceLines(one->results))
    {
      text << one->label << " " << line << "\n";
    }
  }
  for (const std::string& u : c.unavailable)
  {
    text << "not available: " << u << "\n";
  }
  return text.str();
}

} // namespace bender
