#include "FlowStudy.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "CfdPatches.h"
#include "FlowCacheTrim.h"
#include "FlowCaseCache.h"
#include "FlowStreamlines.h"
#include "MeshIO.h"
#include "WarpedPoints.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <filesystem>
#include <thread>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
/// The names of the ends (inlet and outlets) of a patch table, sorted.
std::vector<std::string> EndNames(const std::vector<PatchLabel>& patches)
{
  std::vector<std::string> names;
  for (const PatchLabel& p : patches)
  {
    if (IsEndPatch(p.type))
    {
      names.push_back(p.name);
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string Joined(const std::vector<std::string>& names)
{
  std::string text;
  for (const std::string& n : names)
  {
    text += (text.empty() ? "" : ", ") + n;
  }
  return text.empty() ? "none" : text;
}

/// The surface's patch table, refused when it has fewer than two ends.
LabelledSurface Labelled(vtkPolyData* surface, const std::string& what)
{
  LabelledSurface labelled;
  if (surface && HasPatchLabels(surface))
  {
    labelled = ReadLabelledSurface(surface);
  }
  if (EndNames(labelled.patches).size() < 2)
  {
    throw InputError(what + " is not prepared for CFD (no labelled inlet and outlets): press " +
      "Prepare for CFD (Export panel) first");
  }
  return labelled;
}

/// The plan's Prepare for CFD steps without its warps, all before the first (none) warp. A
/// step made after warps chose its ends on the bent shape: its positions are carried back
/// through those warps, so that the original is cut at the same ends (WarpedPoints.h).
WarpPlan PrepareStepsOnly(const WarpPlan& plan)
{
  WarpPlan steps;
  steps.units = plan.units;
  steps.cfdSteps = plan.cfdSteps;
  for (CfdStep& step : steps.cfdSteps)
  {
    CarryBack(CfdStepPoints(step), plan.warps, step.afterWarps);
    step.afterWarps = 0;
  }
  return steps;
}

/// Reports every iteration of a case's solverInfo (a case found solved: its plot at once).
void ReplayIterations(const std::string& caseDirectory,
  const std::function<void(const CfdIteration&)>& onIteration)
{
  if (!onIteration)
  {
    return;
  }
  std::vector<CfdIteration> rows;
  CfdResidualMonitor monitor(
    caseDirectory, [&rows](const CfdIteration& it) { rows.push_back(it); });
  monitor.Stop();
  for (const CfdIteration& row : rows)
  {
    onIteration(row);
  }
}
/// The streamlines of a read result; a case they cannot be traced in keeps its results.
void AddStreamlines(FlowShapeResult& result, int seeds)
{
  if (seeds <= 0)
  {
    return;
  }
  try
  {
    result.streamlines = FlowStreamlines(result.caseDirectory, result.surface, seeds);
  }
  catch (const InputError& e)
  {
    result.streamlineProblem = e.what();
  }
}
} // namespace

const char* FlowShapeName(FlowShape shape)
{
  return shape == FlowShape::Original ? "original" : "current shape";
}

LabelledSurface FlowReadySurface(const FlowStudyInput& input,
  FlowShape shape,
  const ProgressReporter& progress)
{
  const LabelledSurface current = Labelled(input.current, input.name + ": the current shape");
  if (shape == FlowShape::Current)
  {
    return current;
  }
  LabelledSurface original;
  if (input.plan.cfdSteps.empty())
  {
    original = Labelled(input.first, input.name + ": the original");
  }
  else
  {
    ApplyPlanOptions apply;
    apply.planName = input.name;
    apply.progress = progress;
    WarpPlan steps;
    try
    {
      steps = PrepareStepsOnly(input.plan);
    }
    catch (const InputError& e)
    {
      throw InputError(input.name + ": the original: " + e.what());
    }
    const ApplyPlanResult made = ApplyPlan(input.first, steps, apply);
    original = made.prepared.back();
  }
  const std::vector<std::string> want = EndNames(current.patches);
  const std::vector<std::string> got = EndNames(original.patches);
  if (want != got)
  {
    throw InputError(input.name + ": the original's ends (" + Joined(got) +
      ") are not the current shape's (" + Joined(want) +
      "): the bend changed which ends the Prepare for CFD step finds");
  }
  return original;
}

FlowShapeResult ReadFlowShape(const std::string& caseDirectory, FlowShape shape)
{
  FlowShapeResult result;
  result.shape = shape;
  result.caseDirectory = caseDirectory;
  result.key = fs::path(caseDirectory).filename().string();
  result.results = ReadCfdFlowResults(caseDirectory);
  result.surface =
    ReadMesh((fs::path(caseDirectory) / kCfdResultsFolder / kCfdSurfaceResults).string());
  return result;
}

namespace
{
/// The shape made CFD-ready and written into the cache (marked used: the last to go when the
/// cache is trimmed).
CachedFlowCase StoreFlowShape(const FlowStudyInput& input,
  FlowShape shape,
  const FlowStudyOptions& options)
{
  const ProgressReporter& progress = options.progress;
  progress.Report("prepare", 0.0);
  const LabelledSurface ready = FlowReadySurface(input, shape, progress);
  progress.ThrowIfCancelled("case");
  progress.Report("case", 0.0);
  CfdCaseOptions caseOptions = options.caseOptions;
  if (caseOptions.sourceName.empty())
  {
    caseOptions.sourceName = input.name + " (" + FlowShapeName(shape) + ")";
  }
  const CachedFlowCase stored = StoreFlowCase(ready, caseOptions, options.cacheDirectory);
  MarkFlowCaseUsed(stored.caseDirectory);
  return stored;
}

/// The stored case run unless solved, then read back.
FlowShapeResult SolveFlowShape(const CachedFlowCase& stored,
  FlowShape shape,
  const FlowStudyOptions& options)
{
  const ProgressReporter& progress = options.progress;
  if (HasFlowResults(stored.caseDirectory))
  {
    ReplayIterations(stored.caseDirectory, options.onIteration);
    FlowShapeResult result = ReadFlowShape(stored.caseDirectory, shape);
    result.cached = true; // nothing run: solved before, or by the other shape of a study
    AddStreamlines(result, options.streamlineSeeds);
    return result;
  }
  CfdRunOptions run;
  run.progress = progress;
  run.onLine = [&options, &progress](const std::string& line)
  {
    const std::string tag = "bender Allrun: ";
    if (line.compare(0, tag.size(), tag) == 0)
    {
      // "bender Allrun: snappyHexMesh -overwrite": the program names the stage.
      const std::string step = line.substr(tag.size(), line.find(' ', tag.size()) - tag.size());
      const bool solve = step == "simpleFoam" || step == "mpirun";
      const bool parallel = step == "decomposePar" || step == "reconstructPar";
      progress.Report(solve ? "solve" : (parallel ? step : "mesh: " + step), 0.0);
    }
    if (options.onLine)
    {
      options.onLine(line);
    }
  };
  const double limit = std::max(1, options.caseOptions.iterations);
  {
    CfdResidualMonitor monitor(stored.caseDirectory,
      [&options, &progress, limit](const CfdIteration& it)
      {
        progress.Report("solve", std::min(1.0, it.iteration / limit));
        if (options.onIteration)
        {
          options.onIteration(it);
        }
      });
    RunOpenFoamCase(stored.caseDirectory, run);
    monitor.Stop();
  }
  // RunOpenFoamCase mapped the results (CASE/results) once the solver was done.
  progress.ThrowIfCancelled("results");
  progress.Report("results", 0.0);
  FlowShapeResult result = ReadFlowShape(stored.caseDirectory, shape);
  AddStreamlines(result, options.streamlineSeeds);
  progress.Report("results", 1.0);
  return result;
}
} // namespace

FlowShapeResult RunFlowShape(const FlowStudyInput& input,
  FlowShape shape,
  const FlowStudyOptions& options)
{
  return SolveFlowShape(StoreFlowShape(input, shape, options), shape, options);
}

FlowStudyResult RunFlowStudy(const FlowStudyInput& input,
  const FlowStudyOptions& options,
  const std::function<void(FlowShape, const CfdIteration&)>& onIteration,
  bool concurrent)
{
  constexpr FlowShape shapes[2] = { FlowShape::Original, FlowShape::Current };
  // Each shape's own options: its iterations, its stages named after it.
  FlowStudyOptions each[2] = { options, options };
  for (int k = 0; k < 2; ++k)
  {
    const FlowShape shape = shapes[k];
    each[k].onIteration = onIteration
      ? std::function<void(const CfdIteration&)>(
          [onIteration, shape](const CfdIteration& it) { onIteration(shape, it); })
      : nullptr;
    each[k].progress.onProgress = options.progress.onProgress
      ? std::function<void(const std::string&, double)>(
          [report = options.progress.onProgress, shape](const std::string& stage, double f)
          { report(std::string(FlowShapeName(shape)) + ": " + stage, f); })
      : nullptr;
  }
  // Both cases written first (cheap), so that a shape whose case is the other's (the same
  // content, the same cache folder) is run once, never twice at once in one folder.
  const CachedFlowCase stored[2] = { StoreFlowShape(input, shapes[0], each[0]),
    StoreFlowShape(input, shapes[1], each[1]) };
  const bool same = stored[0].caseDirectory == stored[1].caseDirectory;
  FlowStudyResult study;
  std::exception_ptr failed[2];
  std::atomic<bool> cancelled{ false };
  const auto solve = [&](int k)
  {
    // A failure names its shape (the case folder alone does not say which), of the same type.
    const std::string shape = std::string(FlowShapeName(shapes[k])) + ": ";
    try
    {
      study.shapes[k] = SolveFlowShape(stored[k], shapes[k], each[k]);
    }
    catch (const Cancelled&)
    {
      cancelled = true;
      failed[k] = std::current_exception();
    }
    catch (const EnvironmentError& e)
    {
      failed[k] = std::make_exception_ptr(EnvironmentError(shape + e.what()));
    }
    catch (const InputError& e)
    {
      failed[k] = std::make_exception_ptr(InputError(shape + e.what()));
    }
    catch (const Error& e)
    {
      failed[k] = std::make_exception_ptr(Error(shape + e.what()));
    }
    catch (...)
    {
      failed[k] = std::current_exception();
    }
  };
  if (concurrent && !same)
  {
    std::thread current(solve, 1);
    solve(0);
    current.join();
  }
  else
  {
    solve(0);
    // A failed original does not keep the current shape from its run, unless it is the same
    // case (it would fail again).
    if (!cancelled && !(same && failed[0]))
    {
      solve(1);
    }
  }
  for (const std::exception_ptr& e : failed)
  {
    if (e)
    {
      std::rethrow_exception(e);
    }
  }
  return study;
}

} // namespace bender
