// A sweep row's numbers read back from its solved case.

#include "SweepRowResults.h"

#include "BenderErrors.h"
#include "CfdFlowResults.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
std::string ReadLog(const fs::path& path)
{
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The number after the last `key` in `text` (0 when there is none).
double LastNumberAfter(const std::string& text, const std::string& key)
{
  const std::size_t at = text.rfind(key);
  if (at == std::string::npos)
  {
    return 0.0;
  }
  std::istringstream in(text.substr(at + key.size(), 64));
  in.imbue(std::locale::classic());
  double value = 0.0;
  in >> value;
  return in ? value : 0.0;
}
} // namespace

void ReadSweepRowResults(const std::string& caseDirectory, SweepRow& row)
{
  // The local engine's RunOpenFoamCase mapped the results already; a Slurm task ran the Allrun
  // alone: map them here, on the submitting machine.
  std::error_code ec;
  const bool mapped = fs::exists(fs::path(caseDirectory) / kCfdResultsFolder / kCfdFlowJson, ec);
  const CfdFlowResults flow =
    mapped ? ReadCfdFlowResults(caseDirectory) : MapCfdResults(caseDirectory);
  row.iterations = flow.run.iterations;
  row.converged = flow.run.converged;
  row.meshCells = flow.meshCells;
  row.outlets.clear();
  double total = 0.0, weighted = 0.0;
  for (const CfdEndFlow& end : flow.ends)
  {
    if (end.role != PatchType::Outlet)
    {
      continue;
    }
    row.outlets.push_back({ end.name, end.splitPercent, end.pressureDropPa, end.flowRateMlPerMin });
    total += end.flowRateMlPerMin;
    weighted += end.flowRateMlPerMin * end.pressureDropPa;
  }
  row.pressureDrop = total > 0.0 ? weighted / total : 0.0;
  const CfdWallShearStats& wss = flow.wallShearStress;
  row.wallShearStress = wss.wallAreaMm2 > 0.0;
  row.wssMean = wss.meanPa;
  row.wssMax = wss.maxPa;
  row.wssP99 = wss.percentile99Pa;
  row.lowWssArea = wss.lowAreaMm2;
  row.highWssArea = wss.highAreaMm2;
}

double SweepCaseSeconds(const std::string& caseDirectory)
{
  double seconds = 0.0;
  for (const char* step : { "blockMesh",
         "surfaceFeatureExtract",
         "snappyHexMesh",
         "checkMesh",
         "decomposePar",
         "simpleFoam",
         "reconstructPar" })
  {
    seconds += LastNumberAfter(
      ReadLog(fs::path(caseDirectory) / (std::string("log.") + step)), "ClockTime = ");
  }
  return seconds;
}

} // namespace bender
