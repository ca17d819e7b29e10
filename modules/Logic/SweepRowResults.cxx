// A sweep row's numbers read back from its solved case.

#include "SweepRowResults.h"

#include "BenderErrors.h"
#include "CfdCase.h"

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
  const CfdRunResult run = ReadCfdResults(caseDirectory);
  row.iterations = run.iterations;
  row.converged = run.converged;
  row.outlets.clear();
  double flow = 0.0, weighted = 0.0;
  for (const CfdPatchFlow& patch : run.patches)
  {
    if (patch.type != PatchType::Outlet)
    {
      continue;
    }
    row.outlets.push_back(
      { patch.name, patch.percentOfInlet, patch.pressureDrop, patch.flowRate * 6.0e7 });
    flow += patch.flowRate;
    weighted += patch.flowRate * patch.pressureDrop;
  }
  row.pressureDrop = flow > 0.0 ? weighted / flow : 0.0;
  row.meshCells = static_cast<long long>(
    LastNumberAfter(ReadLog(fs::path(caseDirectory) / "log.checkMesh"), "    cells:"));
  row.wallShearStress = false;
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
