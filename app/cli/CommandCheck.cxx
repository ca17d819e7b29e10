// bender-cli check MESH [--json] [--before MESH] [--closed]: what a CFD engineer checks
// before meshing a surface.

#include "CliCommand.h"
#include "CliParsing.h"

#include "CheckSurface.h"
#include "MeshFormats.h"
#include "StringUtil.h"

#include <cstdio>
#include <memory>
#include <string>

namespace
{
// The formats are the mesh-format table's readable rows (.smesh and .poly, which export
// writes, included).
std::string Details()
{
  return "Reports what a CFD engineer checks before meshing a surface: triangle and point "
         "counts, connected components, boundary loops (open vessel ends) with their sizes, "
         "non-manifold edges and vertices, inconsistently oriented edges, degenerate triangles, "
         "self-intersections (pairs of triangles sharing no vertex), area, enclosed volume when "
         "closed, edge-length and minimum-angle statistics.\n"
         "\n"
         "Mesh formats (by extension): " +
    bender::MeshExtensionList(bender::MeshAccess::Read) +
    ". Lengths in millimetres (a file that states metres, as an export in metres does, is read "
    "in millimetres).\n"
    "\n"
    "exit status: 0 clean, 1 problems found, 2 the mesh could not be read or usage error";
}

struct CheckArguments
{
  bender::CheckSurfaceOptions options;
  bool json = false;
  bool noSelfIntersections = false;
};

int RunCheck(CheckArguments a)
{
  a.options.check.selfIntersections = !a.noSelfIntersections;
  bender::MeshCheckReport report;
  try
  {
    report = bender::CheckSurface(a.options);
  }
  catch (const bender::Error& e)
  {
    bender::CommandError("check", e.what());
    return 2; // unreadable: not a verdict on the mesh
  }
  const std::string name = bender::DisplayName(a.options.input);
  const std::string text =
    a.json ? bender::FormatReportJson(report, name) : bender::FormatReportText(report, name);
  std::fputs(text.c_str(), stdout);
  return report.Clean() ? 0 : 1;
}
} // namespace

void bender::AddCheckCommand(CLI::App& cli)
{
  auto a = std::make_shared<CheckArguments>();
  CLI::App* check = AddCommand(cli,
    "check",
    "check a mesh for CFD: watertight, manifold, flips, self-intersections",
    Details(),
    [a] { return RunCheck(*a); });
  check->add_option("MESH", a->options.input, "the mesh to check")
    ->required()
    ->check(CLI::ExistingFile);
  check
    ->add_option("--before",
      a->options.before,
      "the same mesh before a warp (same points and triangles): also report triangles whose "
      "orientation flipped (space inversion, paper 3.8)")
    ->type_name("MESH")
    ->check(CLI::ExistingFile);
  check->add_flag("--closed",
    a->options.check.requireClosed,
    "open boundaries count as problems (default: reported only; vessels are open at their "
    "inlets and outlets)");
  check->add_flag(
    "--no-self-intersections", a->noSelfIntersections, "skip the self-intersection search");
  check->add_flag("--json", a->json, "print a JSON object instead of text");
}
