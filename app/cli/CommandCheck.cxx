// bender-cli check MESH [--json] [--before MESH [--max-narrowing PERCENT]] [--closed]: what a
// CFD engineer checks before meshing a surface, and what a bend did to its lumen.

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
         "With --before, also the lumen guard: the centerlines of both shapes (the after's "
         "seeded with the before's ends), each branch's minimal inscribed radius before and "
         "after; a branch the bend moved that narrows by more than --max-narrowing is a problem "
         "(a false stenosis).\n"
         "\n"
         "Mesh formats (by extension): " +
    bender::MeshExtensionList(bender::MeshAccess::Read) +
    ". Lengths in millimetres (a file that states metres, as an export in metres does, is read "
    "in millimetres).\n"
    "\n"
    "exit status: 0 clean, 1 problems found (or a branch narrowed), 2 a mesh could not be read "
    "(missing, unreadable) or usage error";
}

struct CheckArguments
{
  bender::CheckSurfaceOptions options;
  bool json = false;
  bool noSelfIntersections = false;
  bool noLumen = false;
  double maxNarrowingPercent = 5.0;
};

int RunCheck(CheckArguments a)
{
  a.options.check.selfIntersections = !a.noSelfIntersections;
  a.options.lumen.enabled = !a.noLumen;
  a.options.lumen.maxNarrowing = a.maxNarrowingPercent / 100.0;
  bender::SurfaceCheck check;
  try
  {
    check = bender::CheckSurfaceAndLumen(a.options);
  }
  catch (const bender::Error& e)
  {
    bender::CommandError("check", e.what());
    return 2; // unreadable: not a verdict on the mesh
  }
  const std::string name = bender::DisplayName(a.options.input);
  std::string text;
  if (a.json)
  {
    nlohmann::ordered_json json = bender::ToJson(check.report, name);
    if (check.lumen)
    {
      json["lumen"] = bender::LumenCheckToJson(*check.lumen);
    }
    text = json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
  }
  else
  {
    text = bender::FormatReportText(check.report, name) +
      (check.lumen ? bender::LumenCheckText(*check.lumen) : std::string());
  }
  std::fputs(text.c_str(), stdout);
  return check.Passed() ? 0 : 1;
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
  // A missing file is bad input, said by the reader as for every command ("FILE: no such
  // file"), not a usage error.
  check->add_option("MESH", a->options.input, "the mesh to check")->required();
  check
    ->add_option("--before",
      a->options.before,
      "the same mesh before a warp: also report triangles whose orientation flipped (same "
      "points and triangles; space inversion, paper 3.8) and each branch's narrowing")
    ->type_name("MESH");
  check
    ->add_option("--max-narrowing",
      a->maxNarrowingPercent,
      "with --before: the largest loss of a branch's minimal inscribed radius that passes, in "
      "percent (default 5)")
    ->type_name("PERCENT")
    ->check(CLI::Range(0.0, 99.0));
  check->add_flag("--no-lumen", a->noLumen, "with --before: skip the lumen guard (centerlines)");
  check->add_flag("--closed",
    a->options.check.requireClosed,
    "open boundaries count as problems (default: reported only; vessels are open at their "
    "inlets and outlets)");
  check->add_flag(
    "--no-self-intersections", a->noSelfIntersections, "skip the self-intersection search");
  check->add_flag("--json", a->json, "print a JSON object instead of text");
}
