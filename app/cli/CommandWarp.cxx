// bender-cli warp IN_MESH PLAN OUT_MESH: replays a saved plan on a mesh.

#include "CliCommands.h"
#include "CliParsing.h"

#include "ApplyPlan.h"
#include "MeshIO.h"
#include "WarpPlanIO.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli warp IN_MESH PLAN OUT_MESH [options]\n"
  "\n"
  "Applies the warps of PLAN (a .bender.json warp plan) in order to IN_MESH and writes the\n"
  "result to OUT_MESH. A warp with a \"subdivision\" object is followed by adaptive\n"
  "subdivision (spec 7) instead of the plain warp: edges the warp bends by more than its\n"
  "tolerance are split. The plan is validated whole before anything is written; on any error\n"
  "nothing is written. OUT_MESH must differ from IN_MESH (an input is never overwritten).\n"
  "\n"
  "Mesh formats (by extension): .stl .obj .ply .vtp .vtk .off (reading and writing).\n"
  "Coordinates stay in the mesh's own frame (LPS mm for Bender's segmentations).\n"
  "\n"
  "options:\n"
  "  --precision exact|table   screw evaluation (default exact: the normative result;\n"
  "                            table interpolates screws, within 1e-5 of the model size)\n"
  "  --ascii                   write ASCII STL (default binary)\n"
  "  --quiet                   print nothing on success\n"
  "  -h, --help                this help\n"
  "\n"
  "exit status: 0 success, 1 bad input (mesh, plan, invalid ribbon), 2 usage error\n";

std::string BaseName(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

int Fail(const std::string& message)
{
  std::fprintf(stderr, "bender-cli warp: %s\n", message.c_str());
  return 1;
}
} // namespace

int RunWarpCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("warp", Usage);
  std::vector<std::string> positional;
  std::string precisionName = "exact";
  bool ascii = false;
  bool quiet = false;
  cli.App.add_option("files", positional);
  cli.App.add_option("--precision", precisionName);
  cli.App.add_flag("--ascii", ascii);
  cli.App.add_flag("--quiet", quiet);
  if (const int status = cli.Parse(args); status >= 0)
  {
    return status;
  }
  bender::ApplyPlanOptions options;
  if (precisionName == "exact")
  {
    options.precision = bender::WarpPrecision::Exact;
  }
  else if (precisionName == "table")
  {
    options.precision = bender::WarpPrecision::Table;
  }
  else
  {
    return cli.UsageError("--precision: unknown value '" + precisionName + "' (exact or table)");
  }
  if (positional.size() != 3)
  {
    return cli.UsageError("expected IN_MESH PLAN OUT_MESH");
  }
  bender::MeshWriteOptions writeOptions;
  if (ascii)
  {
    writeOptions.stlEncoding = bender::StlEncoding::Ascii;
  }
  const std::string& inPath = positional[0];
  const std::string& planPath = positional[1];
  const std::string& outPath = positional[2];
  if (bender::SameFile(inPath, outPath) || bender::SameFile(planPath, outPath))
  {
    return Fail(outPath + ": refusing to overwrite an input file; choose another OUT_MESH");
  }

  // VTK's own messages would duplicate ours; every failure is reported below in one line.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();

  const auto t0 = std::chrono::steady_clock::now();
  vtkSmartPointer<vtkPolyData> mesh;
  bender::WarpPlan plan;
  try
  {
    mesh = bender::ReadMesh(inPath);
    plan = bender::ReadWarpPlan(planPath);
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
  if (mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
  {
    return Fail(BaseName(inPath) + ": the mesh has no polygons (nothing to warp)");
  }

  const std::string planName = BaseName(planPath);
  options.planName = planName;
  bender::ApplyPlanResult result;
  try
  {
    result = bender::ApplyPlan(mesh, plan, options);
  }
  catch (const bender::Error& e)
  {
    return Fail(e.what());
  }
  for (std::size_t i = 0; i < result.info.size(); ++i)
  {
    const bender::WarpStepInfo& info = result.info[i];
    if (!info.warning.empty())
    {
      std::fprintf(stderr,
        "bender-cli warp: warning: %s: warps[%zu]: %s\n",
        planName.c_str(),
        i,
        info.warning.c_str());
    }
    if (quiet)
    {
      continue;
    }
    const char* lift = info.flipOccurred ? " (screw continuity lift used)" : "";
    if (info.subdivided)
    {
      std::printf("warp %zu: subdivision (tolerance %g): %lld -> %lld triangles in %d passes%s%s\n",
        i,
        info.tolerance,
        info.trianglesBefore,
        info.trianglesAfter,
        info.passesRun,
        info.converged ? "" : " (stopped at maxPasses)",
        lift);
    }
    else
    {
      std::printf("warp %zu: %lld of %lld points inside R = %g%s\n",
        i,
        info.boundPoints,
        info.inputPoints,
        plan.warps[i].radius,
        lift);
    }
  }

  vtkPolyData* current = result.output;
  try
  {
    writeOptions.header =
      "bender warp of " + BaseName(inPath) + " by " + planName + " (" + plan.units + ")";
    bender::WriteMesh(current, outPath, writeOptions);
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!quiet)
  {
    std::printf("wrote %s: %lld points, %lld cells, %zu warps in %.3f s\n",
      outPath.c_str(),
      static_cast<long long>(current->GetNumberOfPoints()),
      static_cast<long long>(current->GetNumberOfCells()),
      plan.warps.size(),
      seconds);
  }
  return 0;
}
