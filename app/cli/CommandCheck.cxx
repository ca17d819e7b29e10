// bender-cli check MESH [--json] [--before MESH] [--closed]: what a CFD engineer checks
// before meshing a surface.

#include "CliCommands.h"

#include "BenderMeshCheck.h"
#include "MeshIO.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdio>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli check MESH [options]\n"
  "\n"
  "Reports what a CFD engineer checks before meshing a surface: triangle and point counts,\n"
  "connected components, boundary loops (open vessel ends) with their sizes, non-manifold\n"
  "edges and vertices, inconsistently oriented edges, degenerate triangles, self-\n"
  "intersections (pairs of triangles sharing no vertex), area, enclosed volume when closed,\n"
  "edge-length and minimum-angle statistics.\n"
  "\n"
  "Mesh formats (by extension): .stl .obj .ply .vtp .vtk .off. Lengths in the mesh's unit.\n"
  "\n"
  "options:\n"
  "  --before MESH             the same mesh before a warp (same points and triangles):\n"
  "                            also report triangles whose orientation flipped (space\n"
  "                            inversion, paper 3.8)\n"
  "  --closed                  open boundaries count as problems (default: reported only;\n"
  "                            vessels are open at their inlets and outlets)\n"
  "  --no-self-intersections   skip the self-intersection search\n"
  "  --json                    print a JSON object instead of text\n"
  "  -h, --help                this help\n"
  "\n"
  "exit status: 0 clean, 1 problems found, 2 the mesh could not be read or usage error\n";

std::string BaseName(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}
} // namespace

int RunCheckCommand(const std::vector<std::string>& args)
{
  std::vector<std::string> positional;
  std::string beforePath;
  bool json = false;
  bender::MeshCheckOptions options;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help")
    {
      std::fputs(Usage, stdout);
      return 0;
    }
    else if (a == "--json")
    {
      json = true;
    }
    else if (a == "--closed")
    {
      options.requireClosed = true;
    }
    else if (a == "--no-self-intersections")
    {
      options.selfIntersections = false;
    }
    else if (a == "--before")
    {
      if (i + 1 >= args.size())
      {
        std::fprintf(stderr, "bender-cli check: --before needs a mesh file\n");
        return 2;
      }
      beforePath = args[++i];
    }
    else if (a.size() > 1 && a[0] == '-')
    {
      std::fprintf(stderr, "bender-cli check: unknown option '%s'\n%s", a.c_str(), Usage);
      return 2;
    }
    else
    {
      positional.push_back(a);
    }
  }
  if (positional.size() != 1)
  {
    std::fprintf(stderr, "bender-cli check: expected one MESH\n%s", Usage);
    return 2;
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkSmartPointer<vtkPolyData> mesh, before;
  try
  {
    mesh = bender::ReadMesh(positional[0]);
    if (!beforePath.empty())
    {
      before = bender::ReadMesh(beforePath);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bender-cli check: %s\n", e.what());
    return 2;
  }
  const bender::MeshCheckReport report = bender::CheckMesh(mesh, before, options);
  const std::string name = BaseName(positional[0]);
  const std::string text =
    json ? bender::FormatReportJson(report, name) : bender::FormatReportText(report, name);
  std::fputs(text.c_str(), stdout);
  return report.Clean() ? 0 : 1;
}
