#include "CfdStageTimes.h"

#include "StringUtil.h"

#include <cstdlib>
#include <sstream>

namespace bender
{

namespace
{
constexpr const char* kAllrunTag = "bender Allrun: ";

/// The number after the last line starting with `prefix` ("Mesh refined in = "), 0 when none.
double LastSeconds(const std::string& log, const std::string& prefix)
{
  std::size_t at = log.rfind("\n" + prefix);
  if (at != std::string::npos)
  {
    ++at;
  }
  else if (StartsWith(log, prefix))
  {
    at = 0;
  }
  else
  {
    return 0.0;
  }
  const double value = std::strtod(log.c_str() + at + prefix.size(), nullptr);
  return value > 0.0 ? value : 0.0;
}

bool IsMeshStep(const std::string& program)
{
  // postProcess: the mesh step's measure of the inlet's flow (the Poiseuille inlet).
  return program == "blockMesh" || program == "surfaceFeatureExtract" ||
    program == "snappyHexMesh" || program == "checkMesh" || program == "postProcess";
}
} // namespace

SnappyPhaseTimes ParseSnappyPhaseTimes(const std::string& log)
{
  SnappyPhaseTimes t;
  t.refine = LastSeconds(log, "Mesh refined in = ");
  t.snap = LastSeconds(log, "Mesh snapped in = ");
  t.layers = LastSeconds(log, "Layers added in = ");
  return t;
}

void CfdStepClock::Line(const std::string& line)
{
  if (!StartsWith(line, kAllrunTag) || line.find(" failed, see ") != std::string::npos ||
    line.find("found problems") != std::string::npos)
  {
    return;
  }
  this->Finish();
  const std::string command = line.substr(std::string(kAllrunTag).size());
  this->Current = command.substr(0, command.find(' '));
  this->Started = Clock::now();
}

void CfdStepClock::Finish()
{
  if (!this->Current.empty())
  {
    this->Timed.emplace_back(
      this->Current, std::chrono::duration<double>(Clock::now() - this->Started).count());
    this->Current.clear();
  }
}

CfdStageTimes GroupCfdStages(const std::vector<std::pair<std::string, double>>& steps,
  const std::string& snappyLog)
{
  CfdStageTimes times;
  times.steps = steps;
  const SnappyPhaseTimes phases = ParseSnappyPhaseTimes(snappyLog);
  const double ownClock = phases.refine + phases.snap + phases.layers;
  for (const auto& [program, seconds] : steps)
  {
    if (program == "snappyHexMesh" && ownClock > 0.0)
    {
      const double layers = seconds * phases.layers / ownClock;
      times.layers += layers;
      times.mesh += seconds - layers;
    }
    else if (IsMeshStep(program))
    {
      times.mesh += seconds;
    }
    else
    {
      times.solve += seconds;
    }
  }
  return times;
}

std::string FormatCfdStageTimes(const CfdStageTimes& times)
{
  std::ostringstream s;
  s << "mesh " << FormatNumber(times.mesh) << " s, layers " << FormatNumber(times.layers)
    << " s, solve " << FormatNumber(times.solve) << " s, map " << FormatNumber(times.map) << " s";
  return s.str();
}

} // namespace bender
