#include "CfdCase.h"

#include "BenderErrors.h"
#include "CfdBoundaryConditions.h"
#include "CfdCaseFile.h"
#include "CfdDictionaries.h"
#include "CfdMeshGrading.h"
#include "CfdMeshing.h"
#include "CfdPatches.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <locale>
#include <sstream>

// Reading a case's results back (postProcessing, the mesh's patches) and reporting them.

namespace fs = std::filesystem;

namespace bender
{

namespace
{

/// The data lines of a postProcessing .dat file of the latest start time, as words.
std::vector<std::vector<std::string>> ReadDat(const fs::path& caseDir,
  const std::string& object,
  const std::string& file,
  std::vector<std::string>* header = nullptr)
{
  const fs::path folder = caseDir / "postProcessing" / object;
  std::error_code ec;
  fs::path latest;
  double latestTime = -1.0;
  if (fs::is_directory(folder, ec))
  {
    for (const auto& entry : fs::directory_iterator(folder, ec))
    {
      char* end = nullptr;
      const std::string t = entry.path().filename().string();
      const double time = std::strtod(t.c_str(), &end);
      if (end && *end == '\0' && time > latestTime && fs::exists(entry.path() / file, ec))
      {
        latestTime = time;
        latest = entry.path() / file;
      }
    }
  }
  if (latest.empty())
  {
    throw InputError((folder / "0" / file).string() + ": missing (has the case run?)");
  }
  std::ifstream in(latest);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::vector<std::string> row;
    std::string w;
    while (words >> w)
    {
      row.push_back(w);
    }
    if (row.empty())
    {
      continue;
    }
    if (row[0] == "#")
    {
      if (header && row.size() > 1 && row[1] == "Time")
      {
        header->assign(row.begin() + 1, row.end());
      }
      continue;
    }
    rows.push_back(row);
  }
  if (rows.empty())
  {
    throw InputError(latest.string() + ": no data");
  }
  return rows;
}

double ParseNumber(const std::string& word, const std::string& where)
{
  char* end = nullptr;
  const double v = std::strtod(word.c_str(), &end);
  if (!end || *end != '\0' || !std::isfinite(v))
  {
    throw InputError(where + ": '" + word + "' is not a number");
  }
  return v;
}

/// The last value of a surfaceFieldValue file, and its iteration.
double LastValue(const fs::path& caseDir, const std::string& object, int& iteration)
{
  const auto rows = ReadDat(caseDir, object, "surfaceFieldValue.dat");
  const auto& last = rows.back();
  const std::string where = (caseDir / "postProcessing" / object).string();
  if (last.size() < 2)
  {
    throw InputError(where + ": a line without a value");
  }
  iteration = static_cast<int>(ParseNumber(last[0], where));
  return ParseNumber(last[1], where);
}

} // namespace

CfdRunResult ReadCfdResults(const std::string& caseDirectory)
{
  const fs::path dir(caseDirectory);
  const fs::path jsonPath = dir / kCfdCaseJson;
  nlohmann::json j;
  try
  {
    std::ifstream in(jsonPath);
    if (!in)
    {
      throw InputError(jsonPath.string() + ": missing (not a case written by bender-cli cfd-case)");
    }
    in >> j;
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(jsonPath.string() + ": not valid JSON (" + e.what() + ")");
  }
  CfdRunResult run;
  double density = 1060.0;
  std::vector<CfdPatchFlow> flows;
  try
  {
    density = j.at("density").get<double>();
    for (const auto& p : j.at("patches"))
    {
      CfdPatchFlow f;
      f.name = p.at("name").get<std::string>();
      f.type = PatchTypeFromName(p.at("type").get<std::string>());
      if (IsEndPatch(f.type) && IsValidPatchName(f.name))
      {
        flows.push_back(f);
      }
    }
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(jsonPath.string() + ": " + e.what());
  }
  double inletPressure = 0.0, total = 0.0;
  for (auto& f : flows)
  {
    int iteration = 0;
    f.flowRate = LastValue(dir, "flow_" + f.name, iteration);
    f.pressure = density * LastValue(dir, "pressure_" + f.name, iteration);
    run.iterations = std::max(run.iterations, iteration);
    total += f.flowRate;
    if (f.type == PatchType::Inlet)
    {
      run.inletFlowRate += -f.flowRate;
      inletPressure = f.pressure;
    }
  }
  if (!(run.inletFlowRate > 0.0))
  {
    throw InputError(caseDirectory + ": no flow into the inlet in the results");
  }
  run.massImbalance = std::abs(total) / run.inletFlowRate;
  for (auto& f : flows)
  {
    f.percentOfInlet = 100.0 * f.flowRate / run.inletFlowRate;
    f.pressureDrop = inletPressure - f.pressure;
  }
  run.patches = flows;
  std::vector<std::string> header;
  const auto rows = ReadDat(dir, "solverInfo", "solverInfo.dat", &header);
  const auto& last = rows.back();
  for (std::size_t c = 0; c < header.size() && c < last.size(); ++c)
  {
    const std::string& h = header[c];
    const std::string suffix = "_initial";
    if (h.size() > suffix.size() && h.compare(h.size() - suffix.size(), suffix.size(), suffix) == 0)
    {
      run.residuals.emplace_back(h.substr(0, h.size() - suffix.size()),
        ParseNumber(last[c], (dir / "postProcessing/solverInfo").string()));
    }
  }
  // Converged only when simpleFoam met the residual control; an iteration count below the
  // limit alone (a run killed or cut short) is not convergence.
  run.converged =
    ReadTextFile(dir / "log.simpleFoam").find("SIMPLE solution converged in") != std::string::npos;
  return run;
}

std::vector<std::pair<std::string, long long>> ReadMeshPatches(const std::string& caseDirectory)
{
  const fs::path path = fs::path(caseDirectory) / "constant" / "polyMesh" / "boundary";
  std::ifstream in(path);
  if (!in)
  {
    throw InputError(path.string() + ": missing (has the case been meshed?)");
  }
  // After the FoamFile header: N ( name { type ...; nFaces N; startFace N; } ... ).
  std::vector<std::string> words;
  std::string w;
  while (in >> w)
  {
    words.push_back(w);
  }
  std::vector<std::pair<std::string, long long>> patches;
  std::size_t i = 0;
  for (; i < words.size() && words[i] != "FoamFile"; ++i)
  {
  }
  int depth = 0;
  std::string current;
  bool inList = false;
  for (; i < words.size(); ++i)
  {
    const std::string& t = words[i];
    if (t == "{")
    {
      ++depth;
      if (inList && depth == 1 && i > 0)
      {
        current = words[i - 1];
        patches.emplace_back(current, -1);
      }
    }
    else if (t == "}")
    {
      --depth;
    }
    else if (t == "(" && depth == 0)
    {
      inList = true;
    }
    else if (t == "nFaces" && depth == 1 && !patches.empty() && i + 1 < words.size())
    {
      std::string n = words[i + 1];
      if (!n.empty() && n.back() == ';')
      {
        n.pop_back();
      }
      patches.back().second = static_cast<long long>(ParseNumber(n, path.string()));
    }
  }
  if (patches.empty())
  {
    throw InputError(path.string() + ": no patches");
  }
  return patches;
}

std::string CfdToJson(const CfdCaseResult& written, const CfdRunResult* run)
{
  nlohmann::ordered_json j = { { "case", written.caseDirectory },
    { "inlet", written.inlet },
    { "inletFlowRate", written.inletFlowRate },
    { "inletVelocity", written.inletVelocity },
    { "reynolds", written.reynolds },
    { "cellSize", written.cellSize },
    { "grading", CfdMeshGradingJson(written.grading) },
    { "backgroundCells", written.backgroundCells },
    { "insidePoint", written.insidePoint },
    { "patches", CfdPatchesJson(written.patches) },
    { "files", written.written } };
  if (run)
  {
    nlohmann::ordered_json flows = nlohmann::ordered_json::array();
    for (const auto& f : run->patches)
    {
      flows.push_back({ { "name", f.name },
        { "type", PatchTypeName(f.type) },
        { "flowRate", f.flowRate },
        { "percentOfInlet", f.percentOfInlet },
        { "pressure", f.pressure },
        { "pressureDrop", f.pressureDrop } });
    }
    nlohmann::ordered_json residuals = nlohmann::ordered_json::object();
    for (const auto& [field, value] : run->residuals)
    {
      residuals[field] = value;
    }
    j["run"] = { { "iterations", run->iterations },
      { "converged", run->converged },
      { "inletFlowRate", run->inletFlowRate },
      { "massImbalance", run->massImbalance },
      { "patches", flows },
      { "residuals", residuals },
      { "mesh", CfdMeshReportJson(run->mesh) } };
    if (run->flow)
    {
      j["flow"] = nlohmann::ordered_json::parse(CfdFlowResultsToJson(*run->flow));
    }
  }
  return j.dump(2);
}

std::string FormatCfdCase(const CfdCaseResult& r)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "OpenFOAM case " << r.caseDirectory << " (" << r.written.size() << " files, metres):\n";
  for (const auto& p : r.patches)
  {
    s << "  " << p.name << " (" << PatchTypeName(p.type) << "): " << p.triangles
      << " triangles, area " << CfdShort(p.area * 1e6) << " mm^2";
    if (IsEndPatch(p.type))
    {
      s << ", diameter " << CfdShort(p.diameter * 1e3) << " mm";
    }
    s << "\n";
  }
  s << "  inlet " << r.inlet << ": " << CfdShort(r.inletFlowRate * 6e7) << " ml/min ("
    << CfdShort(r.inletFlowRate) << " m^3/s), mean velocity " << CfdShort(r.inletVelocity)
    << " m/s, Reynolds " << CfdShort(r.reynolds) << "\n";
  s << "  mesh: cells of " << CfdShort(r.cellSize * 1e3) << " mm at the wall, background "
    << r.backgroundCells[0] << " x " << r.backgroundCells[1] << " x " << r.backgroundCells[2]
    << " cells of " << CfdShort(r.backgroundCellSize * 1e3) << " mm\n";
  s << FormatCfdBoundaryConditions(r);
  s << "  run it: " << r.caseDirectory << "/Allrun\n";
  return s.str();
}

std::string CfdRunStatus(const CfdRunResult& run)
{
  std::string status = (run.converged ? "converged in " : "stopped at ") +
    std::to_string(run.iterations) + " iterations" +
    (run.converged ? "; initial residuals" : ", residuals");
  for (const auto& [field, value] : run.residuals)
  {
    status += " " + field + " " + CfdShort(value, 2);
  }
  return status + (run.converged ? "" : " (not converged: the residual control was not met)");
}

std::string FormatCfdRun(const CfdRunResult& run)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "simpleFoam: " << CfdRunStatus(run) << "\n";
  for (const auto& f : run.patches)
  {
    if (f.type == PatchType::Inlet)
    {
      s << "  " << f.name << " (inlet): " << CfdShort(-f.flowRate * 6e7) << " ml/min, pressure "
        << CfdShort(f.pressure) << " Pa\n";
    }
  }
  for (const auto& f : run.patches)
  {
    if (f.type == PatchType::Outlet)
    {
      s << "  " << f.name << ": " << CfdShort(f.percentOfInlet) << " % of the inlet flow ("
        << CfdShort(f.flowRate * 6e7) << " ml/min), pressure drop from the inlet "
        << CfdShort(f.pressureDrop) << " Pa\n";
    }
  }
  s << "  mass imbalance " << CfdShort(100.0 * run.massImbalance, 2) << " % of the inlet flow\n";
  if (run.mesh.cells > 0)
  {
    s << FormatCfdMeshReport(run.mesh);
  }
  return s.str() + (run.flow ? FormatCfdWallShearStress(*run.flow) : std::string());
}

} // namespace bender
