// bender-cli cfd-case SURFACE -o CASE_DIR [...] [--run]: a steady laminar OpenFOAM case of a
// labelled vessel surface, optionally run (workflow in modules/Logic/CfdCase).

#include "CliCommand.h"
#include "CliParsing.h"

#include "BenderErrors.h"
#include "CfdBoundaryConditions.h"
#include "CfdCase.h"
#include "CfdConvergenceStudy.h"
#include "MeshIO.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace
{
const char* const Details =
  "Writes a complete steady laminar OpenFOAM case (v1912 or later) of a closed vessel surface "
  "whose ends are labelled (bender-cli clip, or export --cap to .vtp): the surface in metres as "
  "one named solid per patch, blockMesh's background box, surfaceFeatureExtract, snappyHexMesh "
  "with each patch a named region, a point inside the lumen and prism layers on the wall, "
  "simpleFoam with the inlet's flow rate (the same flow for compared shapes) as a developed "
  "Poiseuille profile on the inlet's shape (or a plug), the outlets at zero pressure, a "
  "prescribed split, Murray's law or resistances, no-slip walls, function objects for the flow "
  "and mean pressure of every end, decomposeParDict and an Allrun. The folder is written whole "
  "or not at all.\n"
  "\n"
  "SURFACE: .vtp/.vtk with the labels CellEntityIds + PatchNames/PatchTypes (or the legacy "
  "PatchId of export --cap), in millimetres (Bender's unit).\n"
  "\n"
  "example: bender-cli cfd-case vessel-cfd.vtp -o case-original --run --iterations 500\n"
  "\n"
  "exit status: 0 written (and run), 1 bad surface, folder, OpenFOAM missing or failed, 2 usage "
  "error";

struct CfdCaseArguments
{
  std::string input;
  bender::CfdCaseOptions options;
  std::string inletProfile = "poiseuille", outlets;
  std::vector<std::string> split, resistance;
  bool run = false, json = false, convergence = false;
  double ratio = 1.3;
};

int RunCfdCase(CfdCaseArguments a)
{
  bender::CfdCaseOptions& options = a.options;
  options.inletProfile =
    a.inletProfile == "plug" ? bender::CfdInletProfile::Plug : bender::CfdInletProfile::Poiseuille;
  const std::string outlets = !a.outlets.empty() ? a.outlets
                                                 : (!a.split.empty()           ? "split"
                                                       : !a.resistance.empty() ? "resistance"
                                                                               : "");
  options.outlets = outlets == "split" ? bender::CfdOutletCondition::Split
    : outlets == "murray"              ? bender::CfdOutletCondition::Murray
    : outlets == "resistance"          ? bender::CfdOutletCondition::Resistance
                                       : bender::CfdOutletCondition::ZeroPressure;
  options.outletValues = !a.split.empty()
    ? bender::ParseCfdOutletValues("--split", a.split)
    : bender::ParseCfdOutletValues("--resistance", a.resistance);
  if (a.run || a.convergence)
  {
    // Before writing anything: a clear error when OpenFOAM is missing.
    if (const std::string problem = bender::FindOpenFoamProblem(options.processors);
        !problem.empty())
    {
      throw bender::EnvironmentError(problem);
    }
  }
  const vtkSmartPointer<vtkPolyData> surface = bender::ReadMesh(a.input);
  options.sourceName = a.input;
  if (a.convergence)
  {
    bender::CfdConvergenceOptions study;
    study.caseOptions = options;
    study.ratio = a.ratio;
    // The three meshes at once where the cores allow (each serial, or on its processors).
    study.jobs = std::clamp(
      static_cast<int>(std::thread::hardware_concurrency()) / std::max(1, options.processors),
      1,
      3);
    if (!a.json)
    {
      study.onLine = [](const std::string& line)
      {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
      };
    }
    const bender::CfdConvergenceResult result = bender::RunCfdConvergence(surface, study);
    std::printf("%s",
      (a.json ? bender::CfdConvergenceToJson(result) + "\n" : bender::FormatCfdConvergence(result))
        .c_str());
    return 0;
  }
  const bender::CfdCaseResult written = bender::WriteOpenFoamCase(surface, options);
  if (!a.json)
  {
    std::printf("%s", bender::FormatCfdCase(written).c_str());
    std::fflush(stdout);
  }
  if (!a.run)
  {
    if (a.json)
    {
      std::printf("%s\n", bender::CfdToJson(written, nullptr).c_str());
    }
    return 0;
  }
  bender::CfdRunOptions runOptions;
  if (!a.json)
  {
    runOptions.onLine = [](const std::string& line)
    {
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
    };
  }
  const bender::CfdRunResult result = bender::RunOpenFoamCase(written.caseDirectory, runOptions);
  if (a.json)
  {
    std::printf("%s\n", bender::CfdToJson(written, &result).c_str());
  }
  else
  {
    std::printf("%s", bender::FormatCfdRun(result).c_str());
  }
  return 0;
}
} // namespace

void bender::AddCfdCaseCommand(CLI::App& cli)
{
  auto a = std::make_shared<CfdCaseArguments>();
  CLI::App* cfd = AddCommand(cli,
    "cfd-case",
    "an OpenFOAM case of a labelled vessel (and its run)",
    Details,
    [a] { return RunCfdCase(*a); });
  CfdCaseOptions& options = a->options;
  cfd->add_option("SURFACE", a->input, "the labelled vessel surface")->required();
  cfd->add_option("-o,--output", options.caseDirectory, "the case folder: new or empty")
    ->required()
    ->type_name("CASE_DIR");
  cfd->add_flag("--force", options.force, "replace a non-empty CASE_DIR");
  cfd->add_option("--inlet", options.inlet, "the inlet patch (default: the end labelled inlet)")
    ->type_name("NAME");
  CLI::Option* flowRate =
    cfd
      ->add_option("--flow-rate",
        options.flowRate,
        "inlet volumetric flow rate, m^3/s (1e-5 = 600 ml/min): the same flow whatever the "
        "inlet's area")
      ->type_name("Q")
      ->check(NumberAbove(0))
      ->capture_default_str();
  cfd
    ->add_option("--velocity",
      options.velocity,
      "the inlet's mean velocity instead, m/s (the flow is V x the inlet's area)")
    ->type_name("V")
    ->check(NumberAbove(0))
    ->excludes(flowRate);
  OneOf(cfd->add_option("--inlet-profile",
          a->inletProfile,
          "developed (Poiseuille on the inlet's shape, timeVaryingMappedFixedValue) or plug"),
    { "poiseuille", "plug" })
    ->capture_default_str();
  OneOf(cfd->add_option("--outlets",
          a->outlets,
          "zero-pressure (default: p = 0 at each), split (--split), murray (Q ~ r^3 from the "
          "outlets' radii) or resistance (--resistance, p = R Q)"),
    { "zero-pressure", "split", "murray", "resistance" });
  CLI::Option* split = cfd
                         ->add_option("--split",
                           a->split,
                           "each outlet's share of the inlet's flow, percent, summing to 100 "
                           "(outlet_1=60,outlet_2=40)")
                         ->type_name("NAME=PERCENT")
                         ->delimiter(',');
  cfd
    ->add_option("--resistance",
      a->resistance,
      "each outlet's resistance R, Pa s/m^3: p = R Q (a steady Windkessel)")
    ->type_name("NAME=R")
    ->delimiter(',')
    ->excludes(split);
  cfd->add_option("--layers", options.layers, "prism layers on the wall (0: none)")
    ->type_name("N")
    ->check(IntegerIn(0, 10))
    ->capture_default_str();
  cfd
    ->add_option("--cell-size",
      options.cellSize,
      "the wall's base cell size, m (default: the largest end's diameter / the cells across; "
      "the background mesh is 2H; ends and narrower stretches of the lumen are refined until "
      "they have the cells across)")
    ->type_name("H")
    ->check(NumberIn(0, 1));
  cfd
    ->add_option("--cells-across",
      options.cellsAcross,
      "the wall cells across every end and (at least 0.9 x as many) across the lumen on the "
      "wall (default 8; with --cell-size, the smallest end's diameter / H)")
    ->type_name("N")
    ->check(NumberIn(2, 200));
  cfd->add_option("--viscosity", options.viscosity, "kinematic viscosity, m^2/s (blood)")
    ->type_name("NU")
    ->check(NumberAbove(0, 1))
    ->capture_default_str();
  cfd
    ->add_option("--iterations",
      options.iterations,
      "simpleFoam iteration limit (stops earlier when the initial residuals fall below 1e-4 for "
      "p and 1e-5 for U)")
    ->type_name("N")
    ->check(IntegerIn(1, 1000000))
    ->capture_default_str();
  cfd
    ->add_option(
      "--processors", options.processors, "decomposeParDict subdomains; N > 1 runs mpirun -np N")
    ->type_name("N")
    ->check(IntegerIn(1, 4096))
    ->capture_default_str();
  OneOf(cfd->add_option("--decomposition",
          options.decomposition,
          "scotch where OpenFOAM has it (Debian's openfoam 1912 has not)"),
    { "hierarchical", "scotch", "simple" })
    ->capture_default_str();
  cfd->add_flag("--run",
    a->run,
    "run the case (OpenFOAM must be installed), map the results onto the surface "
    "(CASE/results: surface.vtp with Pressure and WallShearStress in Pa, volume.vtu with U, "
    "flow.json) and report the flow split between the outlets, the pressure drop from the "
    "inlet to each outlet (Pa, rho 1060 kg/m^3), the mass imbalance, the wall shear stress "
    "(mean, 99th percentile, max; wall area below 0.4 Pa and above 15 Pa), the residuals "
    "(converged only when the residual control was met)");
  cfd->add_flag("--convergence",
    a->convergence,
    "run three meshes, cell sizes H, H/r, H/r^2, in CASE_DIR/mesh-1..3 and report for the "
    "pressure drop, flow split and mean WSS the three values, the Richardson-extrapolated value, "
    "the apparent order and the GCI (safety factor 1.25)");
  cfd->add_option("--refinement-ratio", a->ratio, "r of --convergence (at least 1.3)")
    ->type_name("R")
    ->check(NumberIn(1.3, 4))
    ->capture_default_str();
  cfd->add_flag("--json",
    a->json,
    "print one JSON object instead of text (with --run, flow.json's content as \"flow\")");
}
