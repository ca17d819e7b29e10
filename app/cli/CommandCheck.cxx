// bender-cli check MESH [--json] [--before MESH] [--closed]: what a CFD engineer checks
// before meshing a surface.

#include "CliCommands.h"
#include "CliParsing.h"

#include "CheckSurface.h"

#include <vtkOutputWindow.h>

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
  bender::CommandLine cli("check", Usage);
  std::vector<std::string> positional;
  bool json = false, noSelfIntersections = false;
  bender::CheckSurfaceOptions options;
  cli.App.add_option("mesh", positional);
  cli.App.add_flag("--json", json);
  cli.App.add_flag("--closed", options.check.requireClosed);
  cli.App.add_flag("--no-self-intersections", noSelfIntersections);
  cli.App.add_option("--before", options.before);
  if (const int status = cli.Parse(args); status >= 0)
  {
    return status;
  }
  options.check.selfIntersections = !noSelfIntersections;
  if (positional.size() != 1)
  {
    return cli.UsageError("expected one MESH");
  }
  options.input = positional[0];
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  bender::MeshCheckReport report;
  try
  {
    report = bender::CheckSurface(options);
  }
  catch (const bender::Error& e)
  {
    std::fprintf(stderr, "bender-cli check: %s\n", e.what());
    return 2;
  }
  const std::string name = BaseName(positional[0]);
  const std::string text =
    json ? bender::FormatReportJson(report, name) : bender::FormatReportText(report, name);
  std::fputs(text.c_str(), stdout);
  return report.Clean() ? 0 : 1;
}
