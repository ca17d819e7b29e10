// bender-cli cfd-verify [-o DIR]: the built-in verification cases, generated tubes solved by the
// ordinary OpenFOAM case and measured against published laminar results (workflow in
// modules/Logic/CfdVerification).

#include "CliCommand.h"
#include "CliParsing.h"

#include "CfdVerification.h"

#include <cstdio>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Generates two closed, labelled tubes, meshes and solves each with the same OpenFOAM case as "
  "cfd-case (steady laminar simpleFoam, blood nu 3.5e-6 m^2/s, rho 1060 kg/m^3), and measures:\n"
  "  straight tube (D 4 mm, 40 D, Re 100, uniform inlet): the pressure drop against Shah's "
  "developing-flow correlation (1978), within 3 %; the wall shear stress from 8 to 38 D against "
  "Poiseuille's 8 mu U / D, within 5 %;\n"
  "  curved tube (a 300-degree torus section, bend radius 2.5 D, Re 200, Dean 89): the friction "
  "ratio f_curved / f_straight from 180 to 270 degrees against White's correlation (1929), "
  "within 10 %.\n"
  "Each figure is printed against its reference and tolerance.\n"
  "\n"
  "example: bender-cli cfd-verify -o verification\n"
  "\n"
  "exit status: 0 every figure within its tolerance, 1 a figure outside it (or OpenFOAM missing "
  "or failed), 2 usage error";

struct CfdVerifyArguments
{
  bender::CfdVerificationOptions options;
  std::string only;
  bool json = false;
};

int RunCfdVerify(CfdVerifyArguments a)
{
  bender::CfdVerificationOptions& options = a.options;
  options.straight = a.only.empty() || a.only == "straight";
  options.curved = a.only.empty() || a.only == "curved";
  if (!a.json)
  {
    options.onLine = [](const std::string& line)
    {
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
    };
  }
  const bender::CfdVerificationResult result = bender::RunCfdVerification(options);
  std::printf("%s",
    (a.json ? bender::CfdVerificationToJson(result) + "\n" : bender::FormatCfdVerification(result))
      .c_str());
  return result.Passed() ? 0 : 1;
}
} // namespace

void bender::AddCfdVerifyCommand(CLI::App& cli)
{
  auto a = std::make_shared<CfdVerifyArguments>();
  CLI::App* verify = AddCommand(cli,
    "cfd-verify",
    "the built-in CFD verification cases against published laminar flows",
    Details,
    [a] { return RunCfdVerify(*a); });
  CfdVerificationOptions& options = a->options;
  verify
    ->add_option("-o,--output",
      options.folder,
      "keep the cases in DIR (new or empty; default: a temporary folder, removed)")
    ->type_name("DIR");
  OneOf(verify->add_option("--only", a->only, "run one case (default: both)"),
    { "straight", "curved" });
  verify
    ->add_option("--cells-across",
      options.cellsAcross,
      "wall cells across the tubes' diameter, the cell size being D / N (default: 12 for the "
      "straight tube, 16 for the curved one)")
    ->type_name("N")
    ->check(NumberIn(4, 200));
  verify->add_option("--processors", options.processors, "OpenFOAM subdomains; N > 1 runs mpirun")
    ->type_name("N")
    ->check(IntegerIn(1, 4096))
    ->capture_default_str();
  verify->add_flag("--json", a->json, "print one JSON object instead of text");
}
