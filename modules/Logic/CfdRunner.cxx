#include "CfdCase.h"

#include "BenderErrors.h"
#include "CfdCaseFile.h"
#include "CfdMeshing.h"
#include "CfdStageTimes.h"
#include "StringUtil.h"

#include "ProcessRunner.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

// Running a case: where OpenFOAM is, the Allrun, the mesh's patches checked between the steps.

namespace fs = std::filesystem;

namespace bender
{

std::string FindOpenFoamProblem(int processors)
{
  for (const char* program :
    { "blockMesh", "surfaceFeatureExtract", "snappyHexMesh", "checkMesh", "simpleFoam" })
  {
    if (FindExecutable(program).empty())
    {
      return std::string("OpenFOAM is not installed: ") + program +
        " is not on PATH (Debian: apt-get install openfoam; elsewhere source OpenFOAM's "
        "etc/bashrc)";
    }
  }
  if (processors > 1)
  {
    for (const char* program : { "decomposePar", "reconstructPar", "mpirun" })
    {
      if (FindExecutable(program).empty())
      {
        return std::string("a parallel run needs ") + program + ", which is not on PATH";
      }
    }
  }
  const char* project = std::getenv("WM_PROJECT_DIR");
  std::error_code ec;
  if ((!project || !fs::exists(fs::path(project) / "etc" / "controlDict", ec)) &&
    !fs::exists("/usr/share/openfoam/etc/controlDict", ec))
  {
    return "OpenFOAM's etc/controlDict is not found (set WM_PROJECT_DIR or source OpenFOAM's "
           "etc/bashrc)";
  }
  return "";
}

namespace
{
/// Runs `sh ./Allrun what` in dir, its output to log.Allrun (appended when append) and to
/// options.onLine, its steps timed by clock. Throws Error naming the failed step.
void RunAllrun(const fs::path& dir,
  const std::string& caseDirectory,
  const std::string& what,
  const CfdRunOptions& options,
  bool append,
  CfdStepClock& clock)
{
  ProcessOptions run;
  run.argv = { "/bin/sh", "./Allrun", what };
  run.workingDirectory = dir.string();
  run.logPath = (dir / "log.Allrun").string();
  run.appendLog = append;
  run.onLine = [&](const std::string& line)
  {
    clock.Line(line);
    if (options.onLine)
    {
      options.onLine(line);
    }
  };
  run.cancel = options.progress.cancel;
  const ProcessResult result = RunProcess(run);
  clock.Finish();
  if (result.cancelled)
  {
    throw Cancelled(caseDirectory + ": cancelled during Allrun " + what);
  }
  if (!result.Succeeded())
  {
    // Allrun's own message names the failed step and its log.
    const std::string text = ReadTextFile(dir / "log.Allrun");
    std::string failed;
    const std::size_t at = text.find("bender Allrun: ");
    std::size_t pos = text.rfind(" failed, see ");
    if (pos == std::string::npos)
    {
      pos = text.rfind("checkMesh found problems");
    }
    if (pos != std::string::npos && at != std::string::npos)
    {
      const std::size_t start = text.rfind("bender Allrun: ", pos);
      const std::size_t end = text.find('\n', pos);
      failed =
        text.substr(start + 15, end == std::string::npos ? std::string::npos : end - start - 15);
    }
    throw Error(caseDirectory + ": " + (failed.empty() ? "Allrun failed" : failed) +
      " (all output in log.Allrun)");
  }
}

/// Every end of the case (bender-case.json) must be a non-empty patch of the mesh.
void CheckMeshPatches(const std::string& caseDirectory)
{
  const auto meshPatches = ReadMeshPatches(caseDirectory);
  std::ifstream in(fs::path(caseDirectory) / kCfdCaseJson);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("patches") || !j["patches"].is_array())
  {
    throw InputError(caseDirectory + ": " + kCfdCaseJson + " is unreadable");
  }
  for (const auto& p : j["patches"])
  {
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string())
    {
      throw InputError(caseDirectory + ": " + kCfdCaseJson + ": a patch without a name");
    }
    const std::string name = p["name"].get<std::string>();
    const auto it = std::find_if(
      meshPatches.begin(), meshPatches.end(), [&](const auto& m) { return m.first == name; });
    if (it == meshPatches.end() || it->second <= 0)
    {
      // Where the missing end is and how wide (bender-case.json: metres), when written.
      std::string where;
      const nlohmann::json& centre = p.contains("centre") ? p["centre"] : nlohmann::json();
      if (centre.is_array() && centre.size() == 3 && centre[0].is_number() &&
        centre[1].is_number() && centre[2].is_number() && p.contains("diameter") &&
        p["diameter"].is_number())
      {
        where = " at " +
          FormatPoint({ { 1e3 * centre[0].get<double>(),
            1e3 * centre[1].get<double>(),
            1e3 * centre[2].get<double>() } }) +
          " mm (" + FormatNumber(1e3 * p["diameter"].get<double>()) + " mm wide)";
      }
      throw Error(caseDirectory + ": snappyHexMesh left patch " + name + where +
        " without faces: the case would miss that end (give a smaller --cell-size)");
    }
  }
}
} // namespace

CfdRunResult RunOpenFoamCase(const std::string& caseDirectory, const CfdRunOptions& options)
{
  const fs::path dir(caseDirectory);
  std::error_code ec;
  if (!fs::exists(dir / "Allrun", ec) || !fs::exists(dir / kCfdCaseJson, ec))
  {
    throw InputError(caseDirectory + ": not a case written by bender-cli cfd-case (no Allrun)");
  }
  int processors = 1;
  try
  {
    std::ifstream in(dir / kCfdCaseJson);
    processors = nlohmann::json::parse(in).at("processors").get<int>();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError((dir / kCfdCaseJson).string() + ": " + e.what());
  }
  if (const std::string problem = FindOpenFoamProblem(processors); !problem.empty())
  {
    throw EnvironmentError(problem);
  }
  using Steps = CfdRunOptions::Steps;
  CfdStepClock clock;
  if (options.steps != Steps::Solve)
  {
    RunAllrun(dir, caseDirectory, "mesh", options, false, clock);
    CheckMeshPatches(caseDirectory);
  }
  if (options.steps != Steps::Mesh)
  {
    RunAllrun(dir, caseDirectory, "solve", options, options.steps == Steps::All, clock);
  }
  const CfdStageTimes stages = GroupCfdStages(clock.Steps(),
    options.steps == Steps::Solve ? std::string() : ReadTextFile(dir / "log.snappyHexMesh"));
  if (options.steps == CfdRunOptions::Steps::Mesh)
  {
    CfdRunResult meshed;
    meshed.mesh = ReadCfdMeshReport(caseDirectory);
    meshed.stages = stages;
    return meshed;
  }
  CfdRunResult run = ReadCfdResults(caseDirectory);
  if (options.steps == Steps::All)
  {
    run.mesh = ReadCfdMeshReport(caseDirectory);
  }
  run.stages = stages;
  const auto mapStart = std::chrono::steady_clock::now();
  run.flow = MapCfdResults(caseDirectory);
  run.stages.map =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - mapStart).count();
  return run;
}

} // namespace bender
