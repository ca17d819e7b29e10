// bender-cli centerline SURFACE -o CENTERLINES.vtp [--seeds x,y,z ...] [--json]: the vessel
// centerlines with the maximal-inscribed-sphere radius (modules/Vessels, workflow in Logic).

#include "CliCommands.h"
#include "CliParsing.h"

#include "VesselWorkflows.h"

#include <vtkOutputWindow.h>

#include <cstdio>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli centerline SURFACE -o CENTERLINES.vtp [options]\n"
  "\n"
  "Computes the centerlines of a vessel lumen surface (open at its ends, or closed): paths\n"
  "through the surface's internal Voronoi diagram minimising the integral of 1/R from the\n"
  "inlet to every outlet, re-centred and resampled, split into branches where they separate.\n"
  "Endpoints are found automatically (open ends; the tips of long branches of a closed\n"
  "surface) unless seeds are given. The output has point data MaximumInscribedSphereRadius,\n"
  "Abscissa, FrenetTangent, FrenetNormal, Curvature, Torsion and cell data BranchId,\n"
  "ParentBranchId, StartBifurcationId, EndBifurcationId, EndpointId (VMTK's names).\n"
  "\n"
  "Surface formats: .stl .obj .ply .vtp .vtk .off. Lengths in the surface's unit.\n"
  "\n"
  "options:\n"
  "  -o, --output FILE         centerlines (.vtp or .vtk); required\n"
  "  --seeds x,y,z ...         endpoints, the inlet first (at least two)\n"
  "  --json                    print one JSON object (endpoints, bifurcations, branches with\n"
  "                            their measures) instead of text\n"
  "  -h, --help                this help\n"
  "\n"
  "exit status: 0 written, 1 unreadable surface or no centerline, 2 usage error\n";
} // namespace

int RunCenterlineCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("centerline", Usage);
  std::vector<std::string> positional, seeds;
  std::string output;
  bool json = false;
  cli.App.add_option("surface", positional);
  cli.App.add_option("-o,--output", output);
  cli.App.add_option("--seeds", seeds);
  cli.App.add_flag("--json", json);
  if (const int status = cli.Parse(args); status >= 0)
  {
    return status;
  }
  if (positional.size() != 1)
  {
    return cli.UsageError("expected one SURFACE");
  }
  if (output.empty())
  {
    return cli.UsageError("give the output file with -o CENTERLINES.vtp");
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  try
  {
    bender::CenterlineWorkflowOptions options;
    options.input = positional[0];
    options.output = output;
    for (const auto& s : seeds)
    {
      options.seeds.push_back(bender::ParsePoint(s, "--seeds"));
    }
    if (options.seeds.size() == 1)
    {
      return cli.UsageError("--seeds: give at least two points (the inlet first)");
    }
    const bender::CenterlineWorkflowResult result = bender::ComputeCenterlinesOfFile(options);
    if (json)
    {
      std::printf("%s\n", bender::CenterlinesToJson(result).c_str());
    }
    else
    {
      std::printf("%s: %zu endpoints, %zu branches, %zu bifurcations -> %s\n",
        positional[0].c_str(),
        result.centerlines.Endpoints.size(),
        result.measures.Branches.size(),
        result.measures.Bifurcations.size(),
        output.c_str());
      for (const auto& w : result.centerlines.Warnings)
      {
        std::printf("warning: %s\n", w.c_str());
      }
    }
  }
  catch (const bender::Error& e)
  {
    std::fprintf(stderr, "bender-cli centerline: %s\n", e.what());
    return 1;
  }
  return 0;
}
