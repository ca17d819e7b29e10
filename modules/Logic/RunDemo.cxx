#include "RunDemo.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "CfdCase.h"
#include "ExportSurface.h"
#include "MeshIO.h"
#include "PrepareForCfd.h"
#include "RenderToPng.h"
#include "WarpPlanIO.h"

#include "AtomicFile.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <exception>
#include <filesystem>

namespace bender
{

namespace fs = std::filesystem;

RunDemoResult RunDemo(const RunDemoOptions& options)
{
  RunDemoResult result;
  auto say = [&options](const std::string& line)
  {
    if (options.onMessage)
    {
      options.onMessage(line, false);
    }
  };
  auto warn = [&options, &result](const std::string& line)
  {
    result.warnings.push_back(line);
    if (options.onMessage)
    {
      options.onMessage("warning: " + line, true);
    }
  };
  const std::string& dir = options.outputDirectory;
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir, error))
  {
    throw InputError(dir + ": cannot create the output folder");
  }
  const std::string vesselPath = options.vesselPath.empty() ? DemoVesselPath() : options.vesselPath;
  const std::string planPath = options.planPath.empty() ? DemoPlanPath() : options.planPath;
  auto out = [&dir](const char* name) { return (fs::path(dir) / name).string(); };

  vtkSmartPointer<vtkPolyData> surface;
  WarpPlan plan;
  if (options.segment)
  {
    say("Segmenting the demo vessel (MRA-like phantom of " + vesselPath + ")...");
    const DemoVessel demo = SegmentDemoVesselOrFallBack(vesselPath, options.demo, options.progress);
    surface = demo.surface;
    if (demo.fallback.empty())
    {
      say(demo.summary);
      WriteMesh(surface, out("demo-segmented.vtp"));
      result.written.push_back(out("demo-segmented.vtp"));
      result.segmented = true;
    }
    else
    {
      warn("segmentation failed (" + demo.fallback + "); using the vessel surface");
    }
  }
  else
  {
    surface = ReadMesh(vesselPath);
  }
  plan = ReadWarpPlan(planPath);
  options.progress.ThrowIfCancelled("demo plan");

  ApplyPlanOptions applyOptions;
  applyOptions.planName = fs::path(planPath).filename().string();
  applyOptions.progress = options.progress;
  const vtkSmartPointer<vtkPolyData> bent = ApplyPlan(surface, plan, applyOptions).output;
  say("Applied " + std::to_string(plan.warps.size()) + " warps of " + applyOptions.planName);

  const MeshCheckReport report = CheckForExport(bent, surface);
  const std::string reportText = FormatReportText(report, "demo-bent.stl");
  std::string problem;
  if (!AtomicWriteText(out("demo-check.txt"), reportText, problem))
  {
    throw InputError(out("demo-check.txt") + ": " + problem);
  }
  result.written.push_back(out("demo-check.txt"));
  say(reportText);
  result.checkClean = report.Clean();
  if (!result.checkClean)
  {
    warn("the check found problems (see demo-check.txt); exporting anyway");
  }

  for (const char* name : { "demo-bent.stl", "demo-bent.vtp" })
  {
    ExportSurfaceOptions exportOptions;
    exportOptions.output = out(name);
    exportOptions.protectedPath = vesselPath;
    for (const std::string& file : ExportSurface(bent, exportOptions).written)
    {
      result.written.push_back(file);
    }
  }
  if (options.cfd)
  {
    // Issue 11: the bent vessel made CFD-ready (ends clipped, flow extensions, labelled caps),
    // in metres, as a case. The bend comes first: flow extensions are modelling artefacts that
    // must continue the final ends, and a plan placed on the whole vessel, applied to the
    // clipped and extended one, moves the near part of an extension but not its far part (the
    // demo plan then folds 519 triangles).
    try
    {
      say("Preparing the bent vessel for CFD (ends clipped, flow extensions, labelled caps)...");
      PrepareForCfdOptions prepare;
      prepare.inputName = "the bent demo vessel";
      const PrepareForCfdResult prepared = PrepareForCfd(bent, prepare);
      for (const std::string& w : prepared.warnings)
      {
        warn(w);
      }
      options.progress.ThrowIfCancelled("demo CFD");
      ExportSurfaceOptions stl;
      stl.output = out("demo-cfd.stl");
      stl.protectedPath = vesselPath;
      stl.unit = "m";
      stl.stlEncoding = StlEncoding::Ascii;
      stl.patches = StlPatchMode::Solids;
      stl.patchesJson = true;
      ExportSurfaceOptions vtp;
      vtp.output = out("demo-cfd.vtp");
      vtp.protectedPath = vesselPath;
      for (const auto* exportOptions : { &stl, &vtp })
      {
        for (const std::string& file : ExportSurface(prepared, *exportOptions).written)
        {
          result.written.push_back(file);
        }
      }
      CfdCaseOptions caseOptions;
      caseOptions.caseDirectory = out("demo-openfoam");
      caseOptions.force = true; // the job's own folder, rewritten at every run
      caseOptions.sourceName = "demo-cfd.vtp";
      const CfdCaseResult written = WriteOpenFoamCase(prepared, caseOptions);
      result.cfdCase = written.caseDirectory;
      result.written.push_back(written.caseDirectory);
      say(FormatCfdCase(written));
      if (options.runCfd)
      {
        CfdRunOptions runOptions;
        runOptions.onLine = say;
        say(FormatCfdRun(RunOpenFoamCase(written.caseDirectory, runOptions)));
      }
    }
    catch (const Cancelled&)
    {
      throw;
    }
    catch (const std::exception& e) // bender's errors and std::filesystem_error of the case
    {
      warn(std::string("the CFD step failed: ") + e.what());
    }
  }
  WriteWarpPlan(plan, out("demo-plan.bender.json")); // WarpPlanError: an InputError
  result.written.push_back(out("demo-plan.bender.json"));

  if (options.screenshot)
  {
    RenderToPngOptions render;
    render.output = out("demo.png");
    render.width = 1200;
    render.height = 900;
    render.darkBackground = true;
    render.color = { { 0.86, 0.36, 0.32 } };
    render.opacity = 0.75;
    render.ghost = surface;
    if (!plan.warps.empty())
    {
      // The final ribbon of the last warp, where the surgeon's hands let go.
      render.ribbons.push_back({ plan.warps.back().final, 1.2, { { 1.0, 0.78, 0.2 } } });
    }
    try
    {
      RenderToPng(bent, render);
      result.written.push_back(render.output);
    }
    catch (const EnvironmentError& e)
    {
      warn(std::string(e.what()) + ": screenshot skipped");
    }
    catch (const InputError& e)
    {
      warn(std::string("the screenshot could not be written: ") + e.what());
    }
  }
  return result;
}

} // namespace bender
