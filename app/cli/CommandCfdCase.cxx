// bender-cli cfd-case SURFACE -o CASE_DIR [...] [--run]: a steady laminar OpenFOAM case of a
// labelled vessel surface, optionally run (workflow in modules/Logic/CfdCase).

#include "CliCommands.h"
#include "CliParsing.h"

#include "CfdCase.h"
#include "MeshIO.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

#include <cstdio>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli cfd-case SURFACE -o CASE_DIR [options]\n"
  "\n"
  "Writes a complete steady laminar OpenFOAM case (v1912 or later) of a closed vessel surface\n"
  "whose ends are labelled (bender-cli clip, or export --cap to .vtp): the surface in metres\n"
  "as one named solid per patch, blockMesh's background box, surfaceFeatureExtract,\n"
  "snappyHexMesh with each patch a named region and a point inside the lumen, simpleFoam with\n"
  "the inlet's velocity or flow rate normal to it, outlets at zero pressure, no-slip walls,\n"
  "function objects for the flow and mean pressure of every end, decomposeParDict and\n"
  "an Allrun. The folder is written whole or not at all.\n"
  "\n"
  "SURFACE: .vtp/.vtk with the labels CellEntityIds + PatchNames/PatchTypes (or the legacy\n"
  "PatchId of export --cap), in millimetres (Bender's unit).\n"
  "\n"
  "options:\n"
  "  -o, --output CASE_DIR  the case folder: new or empty; required\n"
  "  --force                replace a non-empty CASE_DIR\n"
  "  --inlet NAME           the inlet patch (default: the end labelled inlet)\n"
  "  --flow-rate Q          inlet volumetric flow rate, m^3/s (flowRateInletVelocity)\n"
  "  --velocity V           uniform inlet velocity normal to the inlet, m/s (default 0.2)\n"
  "  --cell-size H          cell size at the wall, m (default: smallest end diameter / 8;\n"
  "                         the background mesh is 2H)\n"
  "  --viscosity NU         kinematic viscosity, m^2/s (default 3.5e-6, blood)\n"
  "  --iterations N         simpleFoam iteration limit (default 1000; stops earlier when the\n"
  "                         initial residuals fall below 1e-4 for p and 1e-5 for U)\n"
  "  --processors N         decomposeParDict subdomains; N > 1 runs mpirun -np N (default 1)\n"
  "  --decomposition M      hierarchical (default), scotch (where OpenFOAM has it; Debian's\n"
  "                         openfoam 1912 has not) or simple\n"
  "  --run                  run the case (OpenFOAM must be installed) and report the flow\n"
  "                         split between the outlets, the pressure drop from the inlet to\n"
  "                         each outlet (Pa, rho 1060 kg/m^3), the mass imbalance, residuals\n"
  "  --json                 print one JSON object instead of text\n"
  "  -h, --help             this help\n"
  "\n"
  "exit status: 0 written (and run), 1 bad surface, folder, OpenFOAM missing or failed,\n"
  "2 usage error\n";
} // namespace

int RunCfdCaseCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("cfd-case", Usage);
  std::vector<std::string> positional;
  bender::CfdCaseOptions options;
  double flowRate = 0.0, velocity = 0.0;
  bool run = false, json = false;
  cli.App.add_option("surface", positional);
  cli.App.add_option("-o,--output", options.caseDirectory);
  cli.App.add_flag("--force", options.force);
  cli.App.add_option("--inlet", options.inlet);
  CLI::Option* flowRateOption = cli.App.add_option("--flow-rate", flowRate);
  CLI::Option* velocityOption = cli.App.add_option("--velocity", velocity);
  cli.App.add_option("--cell-size", options.cellSize);
  cli.App.add_option("--viscosity", options.viscosity);
  cli.App.add_option("--iterations", options.iterations);
  cli.App.add_option("--processors", options.processors);
  cli.App.add_option("--decomposition", options.decomposition);
  cli.App.add_flag("--run", run);
  cli.App.add_flag("--json", json);
  if (const int status = cli.Parse(args); status >= 0)
  {
    return status;
  }
  if (positional.size() != 1)
  {
    return cli.UsageError("expected one SURFACE");
  }
  if (options.caseDirectory.empty())
  {
    return cli.UsageError("give the case folder with -o CASE_DIR");
  }
  const bool hasFlowRate = flowRateOption->count() > 0;
  const bool hasVelocity = velocityOption->count() > 0;
  if (hasFlowRate && hasVelocity)
  {
    return cli.UsageError("give --flow-rate or --velocity, not both");
  }
  if ((hasFlowRate && !(flowRate > 0.0)) || (hasVelocity && !(velocity > 0.0)))
  {
    return cli.UsageError(hasFlowRate ? "--flow-rate must be > 0" : "--velocity must be > 0");
  }
  if (hasFlowRate)
  {
    options.flowRate = flowRate;
  }
  if (hasVelocity)
  {
    options.velocity = velocity;
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  const std::string& input = positional[0];
  try
  {
    if (run)
    {
      // Before writing anything: a clear error when OpenFOAM is missing.
      if (const std::string problem = bender::FindOpenFoamProblem(options.processors);
          !problem.empty())
      {
        throw bender::EnvironmentError(problem);
      }
    }
    vtkSmartPointer<vtkPolyData> surface = bender::ReadMesh(input);
    options.sourceName = input;
    const bender::CfdCaseResult written = bender::WriteOpenFoamCase(surface, options);
    if (!json)
    {
      std::printf("%s", bender::FormatCfdCase(written).c_str());
      std::fflush(stdout);
    }
    if (!run)
    {
      if (json)
      {
        std::printf("%s\n", bender::CfdToJson(written, nullptr).c_str());
      }
      return 0;
    }
    bender::CfdRunOptions runOptions;
    if (!json)
    {
      runOptions.onLine = [](const std::string& line)
      {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
      };
    }
    const bender::CfdRunResult result = bender::RunOpenFoamCase(written.caseDirectory, runOptions);
    if (json)
    {
      std::printf("%s\n", bender::CfdToJson(written, &result).c_str());
    }
    else
    {
      std::printf("%s", bender::FormatCfdRun(result).c_str());
    }
  }
  catch (const bender::Error& e)
  {
    std::fprintf(stderr, "bender-cli cfd-case: %s\n", e.what());
    return 1;
  }
  return 0;
}
