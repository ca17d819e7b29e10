// bender-cli warp IN_MESH PLAN OUT_MESH: replays a saved plan on a mesh.

#include "CliCommands.h"

#include "MeshIO.h"
#include "WarpPlanIO.h"
#include "vtkBenderAdaptiveSubdivisionFilter.h"
#include "vtkBenderWarpFilter.h"

#include <vtkNew.h>
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
  "subdivision (spec 7): edges the warp bends by more than its tolerance are split. The plan is validated whole before anything is warped; on any error\n"
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
  std::vector<std::string> positional;
  bender::WarpPrecision precision = bender::WarpPrecision::Exact;
  bool quiet = false;
  bender::MeshWriteOptions writeOptions;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help")
    {
      std::fputs(Usage, stdout);
      return 0;
    }
    else if (a == "--precision")
    {
      if (i + 1 >= args.size())
      {
        std::fprintf(stderr, "bender-cli warp: --precision needs a value (exact or table)\n");
        return 2;
      }
      const std::string v = args[++i];
      if (v == "exact")
      {
        precision = bender::WarpPrecision::Exact;
      }
      else if (v == "table")
      {
        precision = bender::WarpPrecision::Table;
      }
      else
      {
        std::fprintf(stderr, "bender-cli warp: --precision: unknown value '%s'\n", v.c_str());
        return 2;
      }
    }
    else if (a == "--ascii")
    {
      writeOptions.stlEncoding = bender::StlEncoding::Ascii;
    }
    else if (a == "--quiet")
    {
      quiet = true;
    }
    else if (a.size() > 1 && a[0] == '-')
    {
      std::fprintf(stderr, "bender-cli warp: unknown option '%s'\n%s", a.c_str(), Usage);
      return 2;
    }
    else
    {
      positional.push_back(a);
    }
  }
  if (positional.size() != 3)
  {
    std::fprintf(stderr, "bender-cli warp: expected IN_MESH PLAN OUT_MESH\n%s", Usage);
    return 2;
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
  vtkSmartPointer<vtkPolyData> current = mesh;
  for (std::size_t i = 0; i < plan.warps.size(); ++i)
  {
    vtkNew<vtkBenderWarpFilter> filter;
    filter->SetInputData(current);
    filter->SetWarp(plan.warps[i]);
    filter->SetPrecision(precision);
    filter->Update();
    const std::string where = planName + ": warps[" + std::to_string(i) + "]";
    if (!filter->GetLastError().empty())
    {
      return Fail(where + ": " + filter->GetLastError());
    }
    if (!filter->GetLastWarning().empty())
    {
      std::fprintf(stderr, "bender-cli warp: warning: %s: %s\n", where.c_str(),
        filter->GetLastWarning().c_str());
    }
    if (!quiet)
    {
      std::printf("warp %zu: %lld of %lld points inside R = %g%s\n", i,
        static_cast<long long>(filter->GetNumberOfBoundPoints()),
        static_cast<long long>(current->GetNumberOfPoints()), plan.warps[i].radius,
        filter->GetFlipOccurred() ? " (screw continuity lift used)" : "");
    }
    vtkSmartPointer<vtkPolyData> next = vtkSmartPointer<vtkPolyData>::New();
    if (plan.warps[i].subdivision)
    {
      // Subdivision needs the pre-warp positions: it warps `current` itself, refining where
      // the warp bends edges by more than the tolerance.
      vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivide;
      subdivide->SetInputData(current);
      subdivide->SetWarp(plan.warps[i]);
      subdivide->SetPrecision(precision);
      subdivide->Update();
      if (!subdivide->GetLastError().empty())
      {
        return Fail(where + ": subdivision: " + subdivide->GetLastError());
      }
      const vtkIdType before = current->GetNumberOfPolys() + current->GetNumberOfStrips();
      next->ShallowCopy(subdivide->GetOutput());
      if (!quiet)
      {
        std::printf("warp %zu: subdivision (tolerance %g): %lld -> %lld triangles in %d "
                    "passes%s\n",
          i, subdivide->GetTolerance(), static_cast<long long>(before),
          static_cast<long long>(next->GetNumberOfPolys()), subdivide->GetNumberOfPassesRun(),
          subdivide->GetConverged() ? "" : " (stopped at maxPasses)");
      }
    }
    else
    {
      next->ShallowCopy(filter->GetOutput());
    }
    current = next;
  }

  try
  {
    writeOptions.header = "bender warp of " + BaseName(inPath) + " by " + planName + " (" +
      plan.units + ")";
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
    std::printf("wrote %s: %lld points, %lld cells, %zu warps in %.3f s\n", outPath.c_str(),
      static_cast<long long>(current->GetNumberOfPoints()),
      static_cast<long long>(current->GetNumberOfCells()), plan.warps.size(), seconds);
  }
  return 0;
}
