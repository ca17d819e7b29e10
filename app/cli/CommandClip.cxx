// bender-cli clip SURFACE -o OUT [--centerlines CL.vtp] [--end x,y,z[:DIST] ...]
// [--name x,y,z=NAME ...] [--extend-inlet F] [--extend-outlet F] [--no-cap]: a vessel made
// ready for CFD meshing (modules/Logic/PrepareForCfd.h).

#include "CliCommands.h"
#include "CliParsing.h"

#include "FileIdentity.h"
#include "MeshIO.h"
#include "PrepareForCfd.h"
#include "VesselWorkflows.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli clip SURFACE -o OUT [options]\n"
  "\n"
  "Makes a vessel surface ready for CFD meshing: each vessel end is cut by a plane\n"
  "perpendicular to the centerline (where the inscribed radius has settled, at least one\n"
  "radius inside the end, unless --end says where), only the vessel at the cut is cut; flow\n"
  "extensions are added along each end's normal (10 radii at the inlet, 5 at the outlets);\n"
  "every end is closed by a flat cap. The output carries the labels CellEntityIds and\n"
  "ModelFaceID (wall 1, ends 2, 3, ...) and the patch names (largest end 'inlet', the others\n"
  "'outlet_1', ... by decreasing area) in .vtp/.vtk; export it with `bender-cli export`.\n"
  "Works on closed (segmented) and open surfaces.\n"
  "\n"
  "Surface formats: .stl .obj .ply .vtp .vtk .off. Lengths in the surface's unit.\n"
  "\n"
  "options:\n"
  "  -o, --output FILE       the labelled surface (.vtp or .vtk keep the labels); required\n"
  "  --centerlines FILE      centerlines (bender-cli centerline); computed when absent\n"
  "  --end x,y,z[:DIST]      x,y,z near a vessel end and DIST the cut's distance from it\n"
  "                          along the centerline; without DIST, cut at the centerline point\n"
  "                          nearest to x,y,z (repeat per end)\n"
  "  --name x,y,z=NAME       the end nearest to x,y,z is called NAME ('inlet' makes it the\n"
  "                          inlet; letters, digits, '_')\n"
  "  --extend-inlet F        inlet flow extension, F x its radius (default 10; 0: none)\n"
  "  --extend-outlet F       outlet flow extensions (default 5; 0: none)\n"
  "  --no-clip               keep the surface's open ends as they are (no centerline needed)\n"
  "  --no-cap                leave the ends open (the output is labelled all wall)\n"
  "  -h, --help              this help\n"
  "\n"
  "exit status: 0 written, 1 unreadable input or a clip that cannot be made, 2 usage error\n";

int Fail(const std::string& message)
{
  std::fprintf(stderr, "bender-cli clip: %s\n", message.c_str());
  return 1;
}
} // namespace

int RunClipCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("clip", Usage);
  std::vector<std::string> positional, ends, names;
  std::string output, centerlinesPath;
  double extendInlet = 10.0, extendOutlet = 5.0;
  bool noCap = false, noClip = false;
  cli.App.add_option("surface", positional);
  cli.App.add_option("-o,--output", output);
  cli.App.add_option("--centerlines", centerlinesPath);
  cli.App.add_option("--end", ends);
  cli.App.add_option("--name", names);
  cli.App.add_option("--extend-inlet", extendInlet);
  cli.App.add_option("--extend-outlet", extendOutlet);
  cli.App.add_flag("--no-cap", noCap);
  cli.App.add_flag("--no-clip", noClip);
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
    return cli.UsageError("give the output file with -o OUT");
  }
  for (const double f : { extendInlet, extendOutlet })
  {
    if (!std::isfinite(f) || f < 0 || f > 100)
    {
      return cli.UsageError("--extend-inlet/--extend-outlet: give a factor in [0, 100]");
    }
  }
  if (noClip && (!ends.empty() || !centerlinesPath.empty()))
  {
    return cli.UsageError("--no-clip: --end and --centerlines choose clip planes");
  }
  const std::string& input = positional[0];
  if (bender::SameFile(input, output) ||
    (!centerlinesPath.empty() && bender::SameFile(centerlinesPath, output)))
  {
    return Fail(output + ": refusing to overwrite an input file; choose another output");
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  try
  {
    bender::PrepareForCfdOptions options;
    options.InputName = input;
    options.Clip = !noClip;
    options.Cap = !noCap;
    options.InletExtension = extendInlet;
    options.OutletExtension = extendOutlet;
    for (const std::string& e : ends)
    {
      bender::ClipEndRequest request;
      const auto colon = e.find(':');
      const bender::Point3 p = bender::ParsePoint(e.substr(0, colon), "--end");
      request.Position = { { p[0], p[1], p[2] } };
      if (colon != std::string::npos)
      {
        const std::string distance = e.substr(colon + 1);
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
          return cli.UsageError("--end " + e + ": DIST must be a number >= 0");
        }
        request.Distance = d;
      }
      options.Ends.push_back(request);
    }
    for (const std::string& n : names)
    {
      const auto equal = n.find('=');
      if (equal == std::string::npos)
      {
        return cli.UsageError("--name " + n + ": expected x,y,z=NAME");
      }
      const bender::Point3 p = bender::ParsePoint(n.substr(0, equal), "--name");
      bender::CfdEndName entry;
      entry.Position = { { p[0], p[1], p[2] } };
      entry.Name = n.substr(equal + 1);
      options.Names.push_back(entry);
    }
    vtkSmartPointer<vtkPolyData> surface;
    try
    {
      surface = bender::ReadMesh(input);
      if (!centerlinesPath.empty())
      {
        options.Centerlines = bender::ReadMesh(centerlinesPath);
      }
    }
    catch (const bender::MeshIOError& e)
    {
      return Fail(e.what());
    }
    const bender::PrepareForCfdResult result = bender::PrepareForCfd(surface, options);
    try
    {
      bender::WriteMesh(result.Surface, output);
    }
    catch (const bender::MeshIOError& e)
    {
      return Fail(e.what());
    }
    std::printf("%s: %zu ends -> %s\n", input.c_str(), result.Ends.size(), output.c_str());
    for (const bender::CfdEnd& end : result.Ends)
    {
      std::printf("  %d %-16s %-6s centre (%.3f, %.3f, %.3f) normal (%.3f, %.3f, %.3f) "
                  "radius %.3f extension %.3f\n",
        end.Id,
        end.Name.c_str(),
        bender::PatchTypeName(end.Type),
        end.Centre[0],
        end.Centre[1],
        end.Centre[2],
        end.Normal[0],
        end.Normal[1],
        end.Normal[2],
        end.Radius,
        end.ExtensionLength);
    }
    for (const std::string& w : result.Warnings)
    {
      std::printf("warning: %s\n", w.c_str());
    }
  }
  catch (const bender::Error& e)
  {
    return Fail(e.what());
  }
  return 0;
}
