#include "CfdFlowResults.h"

#include "BenderErrors.h"
#include "CfdDictionaries.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTriangle.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <locale>
#include <sstream>

// flow.json (written and read back), the WSS statistics and the text of the figures.

namespace fs = std::filesystem;

namespace bender
{

namespace
{
constexpr const char* kFormat = "bender-flow-results";
constexpr int kVersion = 1;

/// The numbers of flow.json's objects, each with its key (its unit in its name): one table
/// for writing and reading.
template<typename T>
struct NumberKey
{
  const char* key;
  double T::*member;
};
constexpr NumberKey<CfdEndFlow> kEndKeys[] = {
  { "flowRate_ml_per_min", &CfdEndFlow::flowRateMlPerMin },
  { "split_percent", &CfdEndFlow::splitPercent },
  { "meanPressure_Pa", &CfdEndFlow::meanPressurePa },
  { "pressureDrop_Pa", &CfdEndFlow::pressureDropPa },
};
constexpr NumberKey<CfdWallShearStats> kWallShearStressKeys[] = {
  { "mean_Pa", &CfdWallShearStats::meanPa },
  { "max_Pa", &CfdWallShearStats::maxPa },
  { "percentile99_Pa", &CfdWallShearStats::percentile99Pa },
  { "lowArea_mm2", &CfdWallShearStats::lowAreaMm2 },
  { "highArea_mm2", &CfdWallShearStats::highAreaMm2 },
  { "wallArea_mm2", &CfdWallShearStats::wallAreaMm2 },
};
constexpr NumberKey<CfdFlowSettings> kSettingsKeys[] = {
  { "density_kg_per_m3", &CfdFlowSettings::densityKgPerM3 },
  { "viscosity_m2_per_s", &CfdFlowSettings::viscosityM2PerS },
  { "inletFlowRate_ml_per_min", &CfdFlowSettings::inletFlowRateMlPerMin },
  { "inletVelocity_m_per_s", &CfdFlowSettings::inletVelocityMPerS },
  { "reynolds", &CfdFlowSettings::reynolds },
  { "cellSize_mm", &CfdFlowSettings::cellSizeMm },
};

template<typename T, std::size_t N>
void PutNumbers(nlohmann::ordered_json& j, const T& from, const NumberKey<T> (&keys)[N])
{
  for (const auto& k : keys)
  {
    j[k.key] = from.*k.member;
  }
}

template<typename T, std::size_t N>
void GetNumbers(const nlohmann::json& j, T& to, const NumberKey<T> (&keys)[N])
{
  for (const auto& k : keys)
  {
    to.*k.member = j.at(k.key).template get<double>();
  }
}
} // namespace

double WeightedPercentile(std::vector<std::pair<double, double>> valueWeights, double percent)
{
  if (valueWeights.empty())
  {
    return 0.0;
  }
  std::sort(valueWeights.begin(), valueWeights.end());
  double total = 0.0;
  for (const auto& vw : valueWeights)
  {
    total += vw.second;
  }
  const double wanted = std::clamp(percent, 0.0, 100.0) / 100.0 * total;
  double sum = 0.0;
  for (const auto& [value, weight] : valueWeights)
  {
    sum += weight;
    if (sum >= wanted)
    {
      return value;
    }
  }
  return valueWeights.back().first;
}

CfdWallShearStats ComputeWallShearStats(vtkPolyData* surface)
{
  vtkDataArray* wss =
    surface ? surface->GetPointData()->GetArray(kWallShearStressMagnitudeArrayName) : nullptr;
  if (!wss)
  {
    throw InputError(
      std::string("the surface has no point data ") + kWallShearStressMagnitudeArrayName);
  }
  const std::vector<int> ids = HasPatchLabels(surface)
    ? CellPatchIds(surface)
    : std::vector<int>(static_cast<std::size_t>(surface->GetNumberOfCells()), kWallEntityId);
  CfdWallShearStats stats;
  std::vector<std::pair<double, double>> valueAreas;
  std::vector<char> onWall(static_cast<std::size_t>(surface->GetNumberOfPoints()), 0);
  double weighted = 0.0;
  vtkIdType n = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = surface->GetPolys();
  polys->InitTraversal();
  // Polygons come first in cell order (polydata orders verts, lines, polys, strips).
  const vtkIdType first = surface->GetNumberOfVerts() + surface->GetNumberOfLines();
  for (vtkIdType cell = first; polys->GetNextCell(n, pts); ++cell)
  {
    if (ids[static_cast<std::size_t>(cell)] != kWallEntityId || n < 3)
    {
      continue;
    }
    // Fan triangulation: each triangle's value is the mean of its corners.
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      double a[3], b[3], c[3];
      surface->GetPoint(pts[0], a);
      surface->GetPoint(pts[k], b);
      surface->GetPoint(pts[k + 1], c);
      const double area = vtkTriangle::TriangleArea(a, b, c);
      const double value =
        (wss->GetTuple1(pts[0]) + wss->GetTuple1(pts[k]) + wss->GetTuple1(pts[k + 1])) / 3.0;
      valueAreas.emplace_back(value, area);
      weighted += value * area;
      stats.wallAreaMm2 += area;
      if (value < kLowWallShearStressPa)
      {
        stats.lowAreaMm2 += area;
      }
      if (value > kHighWallShearStressPa)
      {
        stats.highAreaMm2 += area;
      }
    }
    for (vtkIdType k = 0; k < n; ++k)
    {
      onWall[static_cast<std::size_t>(pts[k])] = 1;
    }
  }
  for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
  {
    if (onWall[static_cast<std::size_t>(p)])
    {
      stats.maxPa = std::max(stats.maxPa, wss->GetTuple1(p));
    }
  }
  stats.meanPa = stats.wallAreaMm2 > 0.0 ? weighted / stats.wallAreaMm2 : 0.0;
  stats.percentile99Pa = WeightedPercentile(std::move(valueAreas), 99.0);
  return stats;
}

std::string CfdFlowResultsToJson(const CfdFlowResults& r)
{
  nlohmann::ordered_json residuals = nlohmann::ordered_json::object();
  for (const auto& [field, value] : r.run.residuals)
  {
    residuals[field] = value;
  }
  nlohmann::ordered_json ends = nlohmann::ordered_json::array();
  for (const auto& e : r.ends)
  {
    nlohmann::ordered_json end = { { "name", e.name }, { "role", PatchTypeName(e.role) } };
    PutNumbers(end, e, kEndKeys);
    ends.push_back(end);
  }
  nlohmann::ordered_json wss = { { "lowThreshold_Pa", kLowWallShearStressPa },
    { "highThreshold_Pa", kHighWallShearStressPa } };
  PutNumbers(wss, r.wallShearStress, kWallShearStressKeys);
  nlohmann::ordered_json settings = nlohmann::ordered_json::object();
  PutNumbers(settings, r.settings, kSettingsKeys);
  settings["processors"] = r.settings.processors;
  const nlohmann::ordered_json j = { { "format", kFormat },
    { "version", kVersion },
    { "units",
      { { "flowRate", "ml/min" },
        { "pressure", "Pa (relative to the outlets' area-weighted mean)" },
        { "wallShearStress", "Pa" },
        { "area", "mm^2" },
        { "length", "mm" },
        { "velocity", "m/s" } } },
    { "time", r.time },
    { "run",
      { { "iterations", r.run.iterations },
        { "iterationLimit", r.run.iterationLimit },
        { "converged", r.run.converged },
        { "status", r.run.status },
        { "residuals", residuals } } },
    { "inletFlowRate_ml_per_min", r.inletFlowRateMlPerMin },
    { "massImbalance_percent", r.massImbalancePercent },
    { "ends", ends },
    { "wallShearStress", wss },
    { "meshCells", r.meshCells },
    { "settings", settings } };
  return j.dump(2) + "\n";
}

CfdFlowResults ReadCfdFlowResults(const std::string& caseDirectory)
{
  const fs::path path = fs::path(caseDirectory) / kCfdResultsFolder / kCfdFlowJson;
  std::ifstream in(path);
  if (!in)
  {
    throw InputError(path.string() + ": missing (has the case run and been mapped?)");
  }
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object())
  {
    throw InputError(path.string() + ": not valid JSON");
  }
  if (j.value("format", std::string()) != kFormat || !j.contains("version") ||
    !j["version"].is_number_integer() || j["version"].get<int>() != kVersion)
  {
    throw InputError(
      path.string() + ": not a " + kFormat + " file of version " + std::to_string(kVersion));
  }
  CfdFlowResults r;
  r.caseDirectory = caseDirectory;
  try
  {
    r.time = j.at("time").get<double>();
    const auto& run = j.at("run");
    r.run.iterations = run.at("iterations").get<int>();
    r.run.iterationLimit = run.at("iterationLimit").get<int>();
    r.run.converged = run.at("converged").get<bool>();
    r.run.status = run.at("status").get<std::string>();
    for (const auto& [field, value] : run.at("residuals").items())
    {
      r.run.residuals.emplace_back(field, value.get<double>());
    }
    r.inletFlowRateMlPerMin = j.at("inletFlowRate_ml_per_min").get<double>();
    r.massImbalancePercent = j.at("massImbalance_percent").get<double>();
    for (const auto& e : j.at("ends"))
    {
      CfdEndFlow end;
      end.name = e.at("name").get<std::string>();
      end.role = PatchTypeFromName(e.at("role").get<std::string>());
      GetNumbers(e, end, kEndKeys);
      r.ends.push_back(end);
    }
    GetNumbers(j.at("wallShearStress"), r.wallShearStress, kWallShearStressKeys);
    r.meshCells = j.at("meshCells").get<long long>();
    GetNumbers(j.at("settings"), r.settings, kSettingsKeys);
    r.settings.processors = j.at("settings").at("processors").get<int>();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(path.string() + ": " + e.what());
  }
  catch (const InputError& e)
  {
    throw InputError(path.string() + ": " + e.what());
  }
  return r;
}

std::string FormatCfdFlowResults(const CfdFlowResults& r)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "simpleFoam: " << r.run.status << "\n";
  for (const auto& e : r.ends)
  {
    if (e.role == PatchType::Inlet)
    {
      s << "  " << e.name << " (inlet): " << CfdShort(e.flowRateMlPerMin) << " ml/min, pressure "
        << CfdShort(e.meanPressurePa) << " Pa above the outlets' mean\n";
    }
    else
    {
      s << "  " << e.name << ": " << CfdShort(e.splitPercent) << " % of the inlet flow ("
        << CfdShort(e.flowRateMlPerMin) << " ml/min), pressure drop from the inlet "
        << CfdShort(e.pressureDropPa) << " Pa\n";
    }
  }
  s << "  mass imbalance " << CfdShort(r.massImbalancePercent, 2) << " % of the inlet flow\n";
  s << "  mesh: " << r.meshCells << " cells\n";
  return s.str() + FormatCfdWallShearStress(r);
}

std::string FormatCfdWallShearStress(const CfdFlowResults& r)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  const CfdWallShearStats& w = r.wallShearStress;
  s << "  wall shear stress: mean " << CfdShort(w.meanPa) << " Pa, 99th percentile "
    << CfdShort(w.percentile99Pa) << " Pa, max " << CfdShort(w.maxPa) << " Pa\n";
  s << "  wall area " << CfdShort(w.wallAreaMm2) << " mm^2: " << CfdShort(w.lowAreaMm2)
    << " mm^2 below " << CfdShort(kLowWallShearStressPa) << " Pa, " << CfdShort(w.highAreaMm2)
    << " mm^2 above " << CfdShort(kHighWallShearStressPa) << " Pa\n";
  s << "  results on the surface in " << r.caseDirectory << "/" << kCfdResultsFolder << " ("
    << kCfdSurfaceResults << ", " << kCfdVolumeResults << ", " << kCfdFlowJson << ")\n";
  return s.str();
}

} // namespace bender
