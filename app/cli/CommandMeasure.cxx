// bender-cli measure SURFACE [--after SURFACE2 | --plan PLAN] [--json]: per-branch vessel
// measures, and their change after a warp with the branches matched.

#include "CliCommands.h"
#include "CliParsing.h"

#include "VesselWorkflows.h"

#include <vtkOutputWindow.h>

#include <cstdio>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli measure SURFACE [--after SURFACE2 | --plan PLAN] [options]\n"
  "\n"
  "Measures every branch of a vessel surface's centerlines: length, tortuosity (length over\n"
  "end-to-end distance), maximal and mean curvature, bend angle between the end tangents,\n"
  "minimal / mean / maximal inscribed radius and where the minimum is, and the angles at each\n"
  "bifurcation. With --after (the same vessel warped) or --plan (a .bender.json plan applied\n"
  "to SURFACE), also the other surface, its branches matched with SURFACE's (its centerlines\n"
  "are seeded with SURFACE's endpoints carried along) and the change of every measure,\n"
  "including how far each branch's end directions turned.\n"
  "\n"
  "Surface formats: .stl .obj .ply .vtp .vtk .off. Lengths in the surface's unit, angles\n"
  "in degrees.\n"
  "\n"
  "options:\n"
  "  --after FILE              the surface after\n"
  "  --plan FILE               a plan to apply to SURFACE (bender-cli warp's rule)\n"
  "  --seeds x,y,z ...         endpoints of SURFACE, the inlet first (at least two)\n"
  "  --json                    print one JSON object instead of a table\n"
  "  -h, --help                this help\n"
  "\n"
  "exit status: 0 measured, 1 unreadable input or no centerline, 2 usage error\n";
} // namespace

int RunMeasureCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("measure", Usage);
  std::vector<std::string> positional, seeds;
  bender::MeasureWorkflowOptions options;
  bool json = false;
  cli.App.add_option("surface", positional);
  cli.App.add_option("--after", options.after);
  cli.App.add_option("--plan", options.plan);
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
  if (!options.after.empty() && !options.plan.empty())
  {
    return cli.UsageError("give --after or --plan, not both");
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  try
  {
    options.input = positional[0];
    for (const auto& s : seeds)
    {
      options.seeds.push_back(bender::ParsePoint(s, "--seeds"));
    }
    if (options.seeds.size() == 1)
    {
      return cli.UsageError("--seeds: give at least two points (the inlet first)");
    }
    const bender::MeasureWorkflowResult result = bender::MeasureVessels(options);
    const std::string text =
      json ? bender::MeasurementsToJson(result) + "\n" : bender::MeasurementsToText(result);
    std::fputs(text.c_str(), stdout);
  }
  catch (const bender::Error& e)
  {
    std::fprintf(stderr, "bender-cli measure: %s\n", e.what());
    return 1;
  }
  return 0;
}
