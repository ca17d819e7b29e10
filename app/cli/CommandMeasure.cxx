// bender-cli measure SURFACE [--after SURFACE2 | --plan PLAN] [--json]: per-branch vessel
// measures, and their change after a warp with the branches matched.

#include "CliCommand.h"
#include "CliParsing.h"

#include "VesselWorkflows.h"

#include <cstdio>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Measures every branch of a vessel surface's centerlines: length, tortuosity (length over "
  "end-to-end distance), maximal and mean curvature, bend angle between the end tangents, "
  "minimal / mean / maximal inscribed radius and where the minimum is, and the angles at each "
  "bifurcation. With --after (the same vessel warped) or --plan (a .bender.json plan applied to "
  "SURFACE), also the other surface, its branches matched with SURFACE's (its centerlines are "
  "seeded with SURFACE's endpoints carried along) and the change of every measure, including "
  "how far each branch's end directions turned.\n"
  "\n"
  "Surface formats: .stl .obj .ply .vtp .vtk .off. Lengths in the surface's unit, angles in "
  "degrees.\n"
  "\n"
  "exit status: 0 measured, 1 unreadable input or no centerline, 2 usage error";

struct MeasureArguments
{
  bender::MeasureWorkflowOptions options;
  std::vector<std::string> seeds;
  bool json = false;
};

int RunMeasure(MeasureArguments a)
{
  a.options.seeds = bender::EndpointSeeds(a.seeds);
  const bender::MeasureWorkflowResult result = bender::MeasureVessels(a.options);
  const std::string text =
    a.json ? bender::MeasurementsToJson(result) + "\n" : bender::MeasurementsToText(result);
  std::fputs(text.c_str(), stdout);
  return 0;
}
} // namespace

void bender::AddMeasureCommand(CLI::App& cli)
{
  auto a = std::make_shared<MeasureArguments>();
  CLI::App* measure = AddCommand(cli,
    "measure",
    "per-branch vessel measures, before and after a warp",
    Details,
    [a] { return RunMeasure(*a); });
  measure->add_option("SURFACE", a->options.input, "the vessel surface (before)")->required();
  CLI::Option* after =
    measure->add_option("--after", a->options.after, "the surface after")->type_name("FILE");
  measure
    ->add_option("--plan", a->options.plan, "a plan to apply to SURFACE (bender-cli warp's rule)")
    ->type_name("FILE")
    ->excludes(after);
  AddPointsOption(
    *measure, "--seeds", a->seeds, "endpoints of SURFACE, the inlet first (at least two)");
  measure->add_flag("--json", a->json, "print one JSON object instead of a table");
}
