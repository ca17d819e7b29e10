// bender-cli warp IN_MESH PLAN OUT_MESH: replays a saved plan on a mesh.

#include "CliCommand.h"
#include "CliParsing.h"

#include "ApplyPlan.h"
#include "MeshIO.h"
#include "StringUtil.h"
#include "WarpPlanIO.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Applies the warps of PLAN (a .bender.json warp plan) in order to IN_MESH and writes the "
  "result to OUT_MESH. A warp with a \"subdivision\" object is followed by adaptive subdivision "
  "(spec 7) instead of the plain warp: edges the warp bends by more than its tolerance are "
  "split. A plan saved after Prepare for CFD (version 2, \"prepareForCfd\") also clips, names, "
  "extends and caps the vessel ends where the window did (as `bender-cli clip`); write .vtp or "
  ".vtk to keep the labels. The plan is validated whole before anything is written; on any "
  "error nothing is written. OUT_MESH must differ from IN_MESH (an input is never "
  "overwritten).\n"
  "\n"
  "Mesh formats (by extension): .stl .obj .ply .vtp .vtk .off (reading and writing). "
  "Coordinates stay in the mesh's own frame (LPS mm for Bender's segmentations).\n"
  "\n"
  "exit status: 0 success, 1 bad input (mesh, plan, invalid ribbon), 2 usage error";

struct WarpArguments
{
  std::string input, plan, output;
  std::string precision = "exact";
  bool ascii = false;
  bool quiet = false;
};

int Fail(const std::string& message)
{
  return bender::CommandError("warp", message);
}

void PrintStep(const bender::WarpStepInfo& info, std::size_t i, double radius)
{
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
      radius,
      lift);
  }
}

int RunWarp(const WarpArguments& a)
{
  if (bender::SameFile(a.input, a.output) || bender::SameFile(a.plan, a.output))
  {
    return Fail(a.output + ": refusing to overwrite an input file; choose another OUT_MESH");
  }
  const auto t0 = std::chrono::steady_clock::now();
  const vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(a.input);
  const bender::WarpPlan plan = bender::ReadWarpPlan(a.plan);
  if (mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
  {
    return Fail(bender::DisplayName(a.input) + ": the mesh has no polygons (nothing to warp)");
  }

  const std::string planName = bender::DisplayName(a.plan);
  bender::ApplyPlanOptions options;
  options.precision =
    a.precision == "table" ? bender::WarpPrecision::Table : bender::WarpPrecision::Exact;
  options.planName = planName;
  const bender::ApplyPlanResult result = bender::ApplyPlan(mesh, plan, options);
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
    if (!a.quiet)
    {
      PrintStep(info, i, plan.warps[i].radius);
    }
  }
  for (std::size_t j = 0; j < result.prepared.size(); ++j)
  {
    for (const std::string& warning : result.prepared[j].warnings)
    {
      std::fprintf(stderr,
        "bender-cli warp: warning: %s: prepareForCfd[%zu]: %s\n",
        planName.c_str(),
        j,
        warning.c_str());
    }
    if (!a.quiet)
    {
      std::printf("prepare for CFD %zu (after %zu warps): %zu ends%s%s\n",
        j,
        plan.cfdSteps[j].afterWarps,
        result.prepared[j].ends.size(),
        plan.cfdSteps[j].clip ? " clipped" : "",
        plan.cfdSteps[j].cap ? ", capped and labelled" : ", labelled");
    }
  }

  vtkPolyData* current = result.output;
  bender::MeshWriteOptions writeOptions;
  if (a.ascii)
  {
    writeOptions.stlEncoding = bender::StlEncoding::Ascii;
  }
  writeOptions.header =
    "bender warp of " + bender::DisplayName(a.input) + " by " + planName + " (" + plan.units + ")";
  bender::WriteMesh(current, a.output, writeOptions);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet)
  {
    std::printf("wrote %s: %lld points, %lld cells, %zu warps%s in %.3f s\n",
      a.output.c_str(),
      static_cast<long long>(current->GetNumberOfPoints()),
      static_cast<long long>(current->GetNumberOfCells()),
      plan.warps.size(),
      plan.cfdSteps.empty() ? "" : " and Prepare for CFD",
      seconds);
  }
  return 0;
}
} // namespace

void bender::AddWarpCommand(CLI::App& cli)
{
  auto a = std::make_shared<WarpArguments>();
  CLI::App* warp = AddCommand(cli,
    "warp",
    "apply a warp plan (.bender.json) to a mesh",
    Details,
    [a] { return RunWarp(*a); });
  warp->add_option("IN_MESH", a->input, "the mesh to warp")->required();
  warp->add_option("PLAN", a->plan, "the warp plan (.bender.json)")->required();
  warp->add_option("OUT_MESH", a->output, "the warped mesh (never IN_MESH)")->required();
  OneOf(warp->add_option("--precision",
          a->precision,
          "screw evaluation: exact is the normative result; table interpolates screws, within "
          "1e-5 of the model size"),
    { "exact", "table" })
    ->capture_default_str();
  warp->add_flag("--ascii", a->ascii, "write ASCII STL (default binary)");
  warp->add_flag("--quiet", a->quiet, "print nothing on success");
}
