#include "CfdCase.h"

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "CfdBoundaryConditions.h"
#include "CfdCaseFile.h"
#include "CfdDictionaries.h"
#include "CfdMeshing.h"
#include "CfdStageTimes.h"
#include "StringUtil.h"

#include "ProcessRunner.h"
#include "VtkMessageGuard.h"

#include <nlohmann/json.hpp>

#include <vtkCellArray.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOpenFOAMReader.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
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
/// The meshed patch `name`'s area (m^2) and vector area (outward, m^2), read by VTK's reader.
std::pair<double, std::array<double, 3>> MeshPatchArea(const fs::path& dir, const std::string& name)
{
  // The reader is asked only for a meshed patch with faces (its pipeline's own errors would
  // otherwise reach the terminal).
  const auto patches = ReadMeshPatches(dir.string());
  if (std::none_of(patches.begin(),
        patches.end(),
        [&](const auto& p) { return p.first == name && p.second > 0; }))
  {
    throw Error(dir.string() + ": the mesh has no faces of patch " + name);
  }
  vtkNew<vtkOpenFOAMReader> reader;
  io_detail::VtkMessageGuard guard;
  guard.Watch(reader);
  reader->SetFileName(CfdFoamFile(dir).c_str());
  reader->SetSkipZeroTime(false);
  reader->SetReadZones(0);
  reader->UpdateInformation();
  reader->DisableAllCellArrays();
  reader->DisableAllPointArrays();
  reader->DisableAllLagrangianArrays();
  reader->EnableAllPatchArrays();
  reader->SetPatchArrayStatus("internalMesh", 0);
  reader->Update();
  double area = 0.0;
  std::array<double, 3> vector{ { 0, 0, 0 } };
  bool found = false;
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(reader->GetOutput()->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* patch = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
    vtkInformation* info = it->GetCurrentMetaData();
    const char* block = info ? info->Get(vtkCompositeDataSet::NAME()) : nullptr;
    if (!patch || !block || name != block)
    {
      continue;
    }
    found = true;
    vtkNew<vtkIdList> ids;
    vtkCellArray* polys = patch->GetPolys();
    for (polys->InitTraversal(); polys->GetNextCell(ids);)
    {
      // A face's vector area: half the sum of its edges' cross products about its first corner.
      std::array<double, 3> a{}, b{}, c{}, face{ { 0, 0, 0 } };
      patch->GetPoint(ids->GetId(0), a.data());
      for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
      {
        patch->GetPoint(ids->GetId(k), b.data());
        patch->GetPoint(ids->GetId(k + 1), c.data());
        const std::array<double, 3> u{ { b[0] - a[0], b[1] - a[1], b[2] - a[2] } };
        const std::array<double, 3> v{ { c[0] - a[0], c[1] - a[1], c[2] - a[2] } };
        face[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
        face[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
        face[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
      }
      area += std::sqrt(face[0] * face[0] + face[1] * face[1] + face[2] * face[2]);
      for (std::size_t k = 0; k < 3; ++k)
      {
        vector[k] += face[k];
      }
    }
  }
  if (!found || !(area > 0.0))
  {
    const std::string message = guard.Message();
    throw Error(dir.string() + ": vtkOpenFOAMReader found no faces of patch " + name +
      " in the mesh" + (message.empty() ? std::string() : " (" + message + ")"));
  }
  return { area, vector };
}

} // namespace

void SetInletFlowOnMesh(const std::string& caseDirectory)
{
  const fs::path dir(caseDirectory);
  std::ifstream in(dir / kCfdCaseJson);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  const auto text = [&](const char* key)
  {
    return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>()
                                                                  : std::string();
  };
  if (text("inletProfile") != CfdInletProfileName(CfdInletProfile::Poiseuille))
  {
    return; // a plug or flow-rate inlet: OpenFOAM sets the flow on the faces itself
  }
  const std::string inlet = text("inlet");
  if (inlet.empty() || !j.contains("inletFlowRate") || !j["inletFlowRate"].is_number() ||
    !(j["inletFlowRate"].get<double>() > 0.0))
  {
    throw InputError((dir / kCfdCaseJson).string() + ": no inlet or inletFlowRate");
  }
  const double flowRate = j["inletFlowRate"].get<double>();
  const fs::path valuesPath = dir / "constant" / "boundaryData" / inlet / "0" / "U";
  const fs::path fieldPath = dir / "0" / "U";
  std::string values = ReadTextFile(valuesPath), field = ReadTextFile(fieldPath);
  const std::size_t marker = values.find(kCfdInletAverageMarker);
  const std::string setFalse = "setAverage      false;", setTrue = "setAverage      true;";
  const std::size_t set =
    field.find(setFalse) != std::string::npos ? field.find(setFalse) : field.find(setTrue);
  if (marker == std::string::npos || set == std::string::npos)
  {
    throw InputError((marker == std::string::npos ? valuesPath : fieldPath).string() +
      ": not as bender-cli cfd-case wrote it (no inlet average to set); write the case again");
  }

  // OpenFOAM scales the mapped profile so that its area-weighted mean has the given magnitude;
  // the faces' velocities are along the cap's normal, the faces' normal may differ slightly.
  const auto [area, vector] = MeshPatchArea(dir, inlet);
  const double length =
    std::sqrt(vector[0] * vector[0] + vector[1] * vector[1] + vector[2] * vector[2]);
  std::array<double, 3> inward{ { -vector[0] / length, -vector[1] / length, -vector[2] / length } };
  double alignment = 1.0;
  for (const auto& p : j.value("patches", nlohmann::json::array()))
  {
    if (p.is_object() && p.contains("name") && p["name"].is_string() &&
      p["name"].get<std::string>() == inlet && p.contains("normal") && p["normal"].is_array() &&
      p["normal"].size() == 3)
    {
      std::array<double, 3> n{};
      for (std::size_t k = 0; k < 3; ++k)
      {
        n[k] = p["normal"][k].is_number() ? -p["normal"][k].get<double>() : 0.0;
      }
      const double dot = n[0] * inward[0] + n[1] * inward[1] + n[2] * inward[2];
      if (dot > 0.5)
      {
        alignment = dot;
        inward = n;
      }
    }
  }
  const double speed = flowRate / (area * alignment);
  const std::size_t lineEnd = values.find('\n', marker);
  values = values.substr(0, lineEnd == std::string::npos ? values.size() : lineEnd) + "\n" +
    "// On the meshed inlet's " + CfdNumber(area) + " m^2: " + CfdNumber(flowRate) + " m^3/s.\n" +
    CfdVector({ { speed * inward[0], speed * inward[1], speed * inward[2] } }) + "\n";
  field.replace(set,
    field.compare(set, setFalse.size(), setFalse) == 0 ? setFalse.size() : setTrue.size(),
    setTrue);
  for (const auto& [path, content] :
    { std::pair{ valuesPath, values }, std::pair{ fieldPath, field } })
  {
    std::string problem;
    if (!AtomicWriteText(path.string(), content, problem))
    {
      throw Error(path.string() + ": " + problem);
    }
  }
}

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
    SetInletFlowOnMesh(caseDirectory);
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
