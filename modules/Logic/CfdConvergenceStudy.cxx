#include "CfdConvergenceStudy.h"

#include "BenderErrors.h"
#include "CfdLabelledRun.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace bender
{
namespace
{

std::string Short(double v, int digits = 4)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  return text;
}

std::string MeshName(std::size_t i)
{
  return "mesh-" + std::to_string(i + 1);
}

// A quantity from its value on each mesh (mesh-1 first).
CfdConvergenceQuantity Study(const std::string& name,
  const std::string& unit,
  const CfdConvergenceResult& r,
  const std::function<double(const CfdFlowResults&)>& value)
{
  std::array<MeshSample, 3> samples{};
  for (std::size_t i = 0; i < 3; ++i)
  {
    samples[i] = { r.cases[i].cellSize, value(r.flows[i]) };
  }
  CfdConvergenceQuantity q;
  q.name = name;
  q.unit = unit;
  q.study = EstimateMeshConvergence(samples);
  if (const std::optional<double> deviation = CoarsestDeviation(q.study))
  {
    q.coarseDeviation = *deviation;
    q.deviationReference = q.study.kind == ConvergenceKind::Monotone ? "extrapolated" : MeshName(2);
  }
  return q;
}

const CfdEndFlow& EndNamed(const CfdFlowResults& flow, const std::string& name)
{
  for (const CfdEndFlow& e : flow.ends)
  {
    if (e.name == name)
    {
      return e;
    }
  }
  throw Error(flow.caseDirectory + ": no end named " + name + " in the results");
}

nlohmann::ordered_json OrNull(bool known, double v)
{
  return known ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

} // namespace

CfdConvergenceResult RunCfdConvergence(vtkPolyData* surface, const CfdConvergenceOptions& options)
{
  if (!(options.ratio >= MinimumRefinementRatio * (1.0 - 1e-9)) || !(options.ratio <= 4.0))
  {
    throw InputError("--refinement-ratio " + Short(options.ratio) + ": give " +
      Short(MinimumRefinementRatio) + " to 4");
  }
  const std::string& folder = options.caseOptions.caseDirectory;
  std::error_code ec;
  if (fs::exists(folder, ec) && !options.caseOptions.force &&
    (!fs::is_directory(folder, ec) || !fs::is_empty(folder, ec)))
  {
    throw InputError(folder + ": the folder is not empty (use --force to replace its meshes)");
  }
  fs::create_directories(folder, ec);
  if (ec)
  {
    throw InputError(folder + ": cannot create the folder (" + ec.message() + ")");
  }

  CfdConvergenceResult r;
  r.folder = folder;
  r.ratio = options.ratio;
  double cellSize = options.caseOptions.cellSize;
  for (std::size_t i = 0; i < 3; ++i)
  {
    const std::string mesh = MeshName(i);
    CfdCaseOptions caseOptions = options.caseOptions;
    caseOptions.caseDirectory = (fs::path(folder) / mesh).string();
    caseOptions.cellSize = cellSize;
    if (i > 0)
    {
      // The finer meshes keep mesh-1's grading: the same levels in the same places (they
      // follow from the cell size x the cells across), every cell divided by the ratio.
      caseOptions.cellsAcross = r.cases[0].grading.cellsAcross * (r.cases[0].cellSize / cellSize);
    }
    r.cases[i] = WriteOpenFoamCase(surface, caseOptions);
    // H is mesh-1's (the default when none was given); the finer ones divide it exactly.
    cellSize = r.cases[0].cellSize / std::pow(options.ratio, static_cast<double>(i + 1));
  }

  // The three runs, `jobs` at once (each serial), the finest first: on two cores mesh-3 and
  // mesh-2 start, and mesh-1 follows whichever ends first.
  std::mutex lines;
  const auto onLine = [&](const std::string& line)
  {
    if (options.onLine)
    {
      const std::lock_guard<std::mutex> lock(lines);
      options.onLine(line);
    }
  };
  std::exception_ptr failed[3];
  std::atomic<int> next{ 0 };
  const auto work = [&]()
  {
    for (int k; (k = next++) < 3;)
    {
      const std::size_t i = static_cast<std::size_t>(2 - k);
      try
      {
        r.flows[i] =
          RunLabelledCase(r.cases[i].caseDirectory, MeshName(i), onLine, options.progress);
      }
      catch (...)
      {
        failed[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::clamp(options.jobs, 1, 3); ++t)
  {
    pool.emplace_back(work);
  }
  work();
  for (std::thread& t : pool)
  {
    t.join();
  }
  for (const std::exception_ptr& e : failed)
  {
    if (e)
    {
      std::rethrow_exception(e);
    }
  }

  std::vector<std::string> outlets;
  for (const CfdEndFlow& e : r.flows[0].ends)
  {
    if (e.role == PatchType::Outlet)
    {
      outlets.push_back(e.name);
    }
  }
  for (const std::string& outlet : outlets)
  {
    r.quantities.push_back(Study("pressure drop to " + outlet,
      "Pa",
      r,
      [&outlet](const CfdFlowResults& f) { return EndNamed(f, outlet).pressureDropPa; }));
  }
  if (outlets.size() > 1)
  {
    for (const std::string& outlet : outlets)
    {
      r.quantities.push_back(Study("flow split of " + outlet,
        "%",
        r,
        [&outlet](const CfdFlowResults& f) { return EndNamed(f, outlet).splitPercent; }));
    }
  }
  r.quantities.push_back(Study("mean wall shear stress",
    "Pa",
    r,
    [](const CfdFlowResults& f) { return f.wallShearStress.meanPa; }));
  return r;
}

std::string FormatCfdConvergence(const CfdConvergenceResult& r)
{
  std::string text = "mesh convergence in " + r.folder + " (refinement ratio " + Short(r.ratio) +
    ", GCI with safety factor " + Short(GciSafetyFactor) + "):\n";
  for (std::size_t i = 0; i < 3; ++i)
  {
    text += "  " + MeshName(i) + ": cells of " + Short(1e3 * r.cases[i].cellSize) +
      " mm at the wall, " + std::to_string(r.flows[i].meshCells) + " cells, " +
      r.flows[i].run.status + "\n";
  }
  char line[512];
  std::snprintf(line,
    sizeof line,
    "  %-32s %10s %10s %10s %12s %6s %8s %12s\n",
    "quantity",
    "mesh-1",
    "mesh-2",
    "mesh-3",
    "extrapolated",
    "order",
    "GCI",
    "mesh-1 off");
  text += line;
  std::string notes;
  for (const CfdConvergenceQuantity& q : r.quantities)
  {
    const MeshConvergence& s = q.study;
    const bool monotone = s.kind == ConvergenceKind::Monotone;
    const std::string label = q.name + " (" + q.unit + ")";
    // The study holds the values finest first; the table reads mesh-1 (coarsest) first.
    std::snprintf(line,
      sizeof line,
      "  %-32s %10s %10s %10s %12s %6s %8s %12s\n",
      label.c_str(),
      Short(s.values[2]).c_str(),
      Short(s.values[1]).c_str(),
      Short(s.values[0]).c_str(),
      monotone ? Short(s.extrapolated).c_str() : "-",
      monotone ? Short(s.order, 3).c_str() : "-",
      monotone ? (Short(100.0 * s.gci, 2) + " %").c_str() : "-",
      q.deviationReference.empty() ? "-" : (Short(100.0 * q.coarseDeviation, 2) + " %").c_str());
    text += line;
    if (!monotone)
    {
      notes += "  " + q.name + ": " + s.note +
        (q.deviationReference.empty() ? "" : "; mesh-1 off from " + q.deviationReference) + "\n";
    }
  }
  return text + notes;
}

std::string CfdConvergenceToJson(const CfdConvergenceResult& r)
{
  nlohmann::ordered_json j;
  j["format"] = "bender-mesh-convergence";
  j["version"] = 1;
  j["folder"] = r.folder;
  j["refinementRatio"] = r.ratio;
  j["gciSafetyFactor"] = GciSafetyFactor;
  j["meshes"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < 3; ++i)
  {
    nlohmann::ordered_json m;
    m["name"] = MeshName(i);
    m["caseDirectory"] = r.cases[i].caseDirectory;
    m["cellSize_m"] = r.cases[i].cellSize;
    m["meshCells"] = r.flows[i].meshCells;
    m["iterations"] = r.flows[i].run.iterations;
    m["converged"] = r.flows[i].run.converged;
    j["meshes"].push_back(m);
  }
  j["quantities"] = nlohmann::ordered_json::array();
  for (const CfdConvergenceQuantity& q : r.quantities)
  {
    const MeshConvergence& s = q.study;
    const bool monotone = s.kind == ConvergenceKind::Monotone;
    nlohmann::ordered_json qj;
    qj["name"] = q.name;
    qj["unit"] = q.unit;
    qj["values"] = { s.values[2], s.values[1], s.values[0] };
    qj["convergence"] = ConvergenceKindName(s.kind);
    qj["order"] = OrNull(monotone, s.order);
    qj["extrapolated"] = OrNull(monotone, s.extrapolated);
    qj["gciPercent"] = OrNull(monotone && s.values[0] != 0.0, 100.0 * s.gci);
    qj["uncertainty"] = s.uncertainty;
    qj["mesh1DeviationPercent"] = OrNull(!q.deviationReference.empty(), 100.0 * q.coarseDeviation);
    qj["mesh1DeviationFrom"] = q.deviationReference.empty()
      ? nlohmann::ordered_json(nullptr)
      : nlohmann::ordered_json(q.deviationReference);
    qj["note"] = s.note;
    j["quantities"].push_back(qj);
  }
  return j.dump(2);
}

} // namespace bender
