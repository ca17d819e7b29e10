// bender-cli clip SURFACE -o OUT [--centerlines CL.vtp] [--end x,y,z[:DIST] ...]
// [--name x,y,z=NAME ...] [--extend-inlet F] [--extend-outlet F] [--no-cap]: a vessel made
// ready for CFD meshing (modules/Logic/PrepareForCfd.h).

#include "CliCommand.h"
#include "CliParsing.h"

#include "FileIdentity.h"
#include "MeshIO.h"
#include "PrepareForCfd.h"
#include "VesselWorkflows.h"

#include <vtkPolyData.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Makes a vessel surface ready for CFD meshing: each vessel end is cut by a plane "
  "perpendicular to the centerline (where the inscribed radius has settled, at least one radius "
  "inside the end, unless --end says where), only the vessel at the cut is cut; flow extensions "
  "are added along each end's normal (10 radii at the inlet, 5 at the outlets); every end is "
  "closed by a flat cap. The output carries the labels CellEntityIds and ModelFaceID (wall 1, "
  "ends 2, 3, ...) and the patch names (largest end 'inlet', the others 'outlet_1', ... by "
  "decreasing area) in .vtp/.vtk; export it with `bender-cli export`. Works on closed "
  "(segmented) and open surfaces.\n"
  "\n"
  "Surface formats: .stl .obj .ply .vtp .vtk .off. Lengths in the surface's unit.\n"
  "\n"
  "example: bender-cli clip vessel.vtp -o vessel-cfd.vtp --end 12.5,-3,40:5\n"
  "\n"
  "exit status: 0 written, 1 unreadable input or a clip that cannot be made, 2 usage error";

struct ClipArguments
{
  std::string input, output, centerlines;
  std::vector<std::string> ends, names;
  bender::PrepareForCfdOptions options;
  bool noCap = false, noClip = false;
};

// "x,y,z[:DIST]" into `end`; the problem, or "" when the text is right.
std::string ReadEnd(const std::string& text, bender::ClipEndRequest& end)
{
  const auto colon = text.find(':');
  try
  {
    const bender::Point3 p = bender::ParsePoint(text.substr(0, colon), "--end");
    end.position = { { p[0], p[1], p[2] } };
  }
  catch (const bender::InputError&)
  {
    return "'" + text + "' is not x,y,z[:DIST]";
  }
  if (colon == std::string::npos)
  {
    return {};
  }
  const std::string distance = text.substr(colon + 1);
  std::size_t used = 0;
  double d = -1.0;
  try
  {
    d = std::stod(distance, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used != distance.size() || !std::isfinite(d) || d < 0)
  {
    return "'" + text + "': DIST must be a number >= 0";
  }
  end.distance = d;
  return {};
}

// "x,y,z=NAME" into `entry`; the problem, or "" when the text is right.
std::string ReadName(const std::string& text, bender::CfdEndName& entry)
{
  const auto equal = text.find('=');
  try
  {
    if (equal == std::string::npos)
    {
      return "'" + text + "': expected x,y,z=NAME";
    }
    const bender::Point3 p = bender::ParsePoint(text.substr(0, equal), "--name");
    entry.position = { { p[0], p[1], p[2] } };
    entry.name = text.substr(equal + 1);
    return {};
  }
  catch (const bender::InputError&)
  {
    return "'" + text + "': expected x,y,z=NAME";
  }
}

void PrintEnds(const bender::PrepareForCfdResult& result)
{
  for (const bender::CfdEnd& end : result.ends)
  {
    std::printf("  %d %-16s %-6s centre (%.3f, %.3f, %.3f) normal (%.3f, %.3f, %.3f) "
                "radius %.3f extension %.3f\n",
      end.id,
      end.name.c_str(),
      bender::PatchTypeName(end.type),
      end.centre[0],
      end.centre[1],
      end.centre[2],
      end.normal[0],
      end.normal[1],
      end.normal[2],
      end.radius,
      end.extensionLength);
  }
  for (const std::string& w : result.warnings)
  {
    std::printf("warning: %s\n", w.c_str());
  }
}

int RunClip(ClipArguments a)
{
  if (bender::SameFile(a.input, a.output) ||
    (!a.centerlines.empty() && bender::SameFile(a.centerlines, a.output)))
  {
    return bender::CommandError(
      "clip", a.output + ": refusing to overwrite an input file; choose another output");
  }
  bender::PrepareForCfdOptions& options = a.options;
  options.inputName = a.input;
  options.clip = !a.noClip;
  options.cap = !a.noCap;
  for (const std::string& text : a.ends)
  {
    options.ends.emplace_back();
    ReadEnd(text, options.ends.back());
  }
  for (const std::string& text : a.names)
  {
    options.names.emplace_back();
    ReadName(text, options.names.back());
  }
  const vtkSmartPointer<vtkPolyData> surface = bender::ReadMesh(a.input);
  if (!a.centerlines.empty())
  {
    options.centerlines = bender::ReadMesh(a.centerlines);
  }
  const bender::PrepareForCfdResult result = bender::PrepareForCfd(surface, options);
  bender::WriteMesh(result.surface, a.output);
  std::printf("%s: %zu ends -> %s\n", a.input.c_str(), result.ends.size(), a.output.c_str());
  PrintEnds(result);
  return 0;
}

// A CLI11 check made of one of the readers above.
template<typename Entry>
CLI::Validator Check(std::string (*read)(const std::string&, Entry&), const char* form)
{
  return CLI::Validator(
    [read](std::string& text)
    {
      Entry entry;
      return read(text, entry);
    },
    form);
}
} // namespace

void bender::AddClipCommand(CLI::App& cli)
{
  auto a = std::make_shared<ClipArguments>();
  CLI::App* clip = AddCommand(cli,
    "clip",
    "clip vessel ends for CFD: perpendicular cuts, flow extensions, labelled caps",
    Details,
    [a] { return RunClip(*a); });
  clip->add_option("SURFACE", a->input, "the vessel surface")->required();
  clip->add_option("-o,--output", a->output, "the labelled surface (.vtp or .vtk keep the labels)")
    ->required()
    ->type_name("OUT");
  CLI::Option* centerlines = clip
                               ->add_option("--centerlines",
                                 a->centerlines,
                                 "centerlines (bender-cli centerline); computed when absent")
                               ->type_name("FILE");
  CLI::Option* ends =
    clip
      ->add_option("--end",
        a->ends,
        "x,y,z near a vessel end and DIST the cut's distance from it along the centerline; "
        "without DIST, cut at the centerline point nearest to x,y,z (repeat the flag per end)")
      ->type_name("x,y,z[:DIST]")
      ->allow_extra_args(false)
      ->check(Check(ReadEnd, "x,y,z[:DIST]"));
  clip
    ->add_option("--name",
      a->names,
      "the end nearest to x,y,z is called NAME ('inlet' makes it the inlet; letters, digits, "
      "'_'; repeat the flag per end)")
    ->type_name("x,y,z=NAME")
    ->allow_extra_args(false)
    ->check(Check(ReadName, "x,y,z=NAME"));
  clip
    ->add_option(
      "--extend-inlet", a->options.inletExtension, "inlet flow extension, F x its radius; 0: none")
    ->type_name("F")
    ->check(NumberIn(0, 100))
    ->capture_default_str();
  clip->add_option("--extend-outlet", a->options.outletExtension, "outlet flow extensions")
    ->type_name("F")
    ->check(NumberIn(0, 100))
    ->capture_default_str();
  clip
    ->add_flag(
      "--no-clip", a->noClip, "keep the surface's open ends as they are (no centerline needed)")
    ->excludes(ends)
    ->excludes(centerlines);
  clip->add_flag("--no-cap", a->noCap, "leave the ends open (the output is labelled all wall)");
}
