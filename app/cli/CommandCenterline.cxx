// bender-cli centerline SURFACE -o CENTERLINES.vtp [--seeds x,y,z ...] [--json]: the vessel
// centerlines with the maximal-inscribed-sphere radius (modules/Vessels, workflow in Logic).

#include "CliCommand.h"
#include "CliParsing.h"

#include "VesselWorkflows.h"

#include <cstdio>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Computes the centerlines of a vessel lumen surface (open at its ends, or closed): paths "
  "through the surface's internal Voronoi diagram minimising the integral of 1/R from the inlet "
  "to every outlet, re-centred and resampled, split into branches where they separate. "
  "Endpoints are found automatically (open ends; the tips of long branches of a closed "
  "surface) unless seeds are given. The output has point data MaximumInscribedSphereRadius, "
  "Abscissa, FrenetTangent, FrenetNormal, Curvature, Torsion and cell data BranchId, "
  "ParentBranchId, StartBifurcationId, EndBifurcationId, EndpointId (VMTK's names).\n"
  "\n"
  "Surface formats: .stl .obj .ply .vtp .vtk .off. Lengths in the surface's unit.\n"
  "\n"
  "exit status: 0 written, 1 unreadable surface or no centerline, 2 usage error";

struct CenterlineArguments
{
  bender::CenterlineWorkflowOptions options;
  std::vector<std::string> seeds;
  bool json = false;
};

int RunCenterline(CenterlineArguments a)
{
  a.options.seeds = bender::EndpointSeeds(a.seeds);
  const bender::CenterlineWorkflowResult result = bender::ComputeCenterlinesOfFile(a.options);
  if (a.json)
  {
    std::printf("%s\n", bender::CenterlinesToJson(result).c_str());
    return 0;
  }
  std::printf("%s: %zu endpoints, %zu branches, %zu bifurcations -> %s\n",
    a.options.input.c_str(),
    result.centerlines.endpoints.size(),
    result.measures.branches.size(),
    result.measures.bifurcations.size(),
    a.options.output.c_str());
  for (const auto& w : result.centerlines.warnings)
  {
    std::printf("warning: %s\n", w.c_str());
  }
  return 0;
}
} // namespace

void bender::AddCenterlineCommand(CLI::App& cli)
{
  auto a = std::make_shared<CenterlineArguments>();
  CLI::App* centerline = AddCommand(cli,
    "centerline",
    "vessel centerlines with the inscribed-sphere radius",
    Details,
    [a] { return RunCenterline(*a); });
  centerline->add_option("SURFACE", a->options.input, "the vessel lumen surface")->required();
  centerline->add_option("-o,--output", a->options.output, "centerlines (.vtp or .vtk)")
    ->required()
    ->type_name("CENTERLINES.vtp");
  AddPointsOption(*centerline, "--seeds", a->seeds, "endpoints, the inlet first (at least two)");
  centerline->add_flag("--json",
    a->json,
    "print one JSON object (endpoints, bifurcations, branches with their measures) instead of "
    "text");
}
