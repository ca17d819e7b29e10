// bender-cli igtl-send SURFACE --to HOST:PORT [--name NAME]: sends a surface to an
// OpenIGTLink server (3D Slicer's OpenIGTLinkIF connector in server mode) as POLYDATA in RAS.
// The sending itself is bender::SlicerLink (modules/Logic), which the application's "Send to
// Slicer" uses too.

#include "CliCommands.h"
#include "CliParsing.h"

#include "IgtlSender.h"
#include "IgtlSocket.h"
#include "IgtlSurfaceFromMesh.h"
#include "MeshIO.h"
#include "SlicerLink.h"
#include "TrackingErrors.h"
#include "WarpPlanIO.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli igtl-send SURFACE --to HOST:PORT [options]\n"
  "\n"
  "Sends a surface (.stl .obj .ply .vtp .vtk .off, LPS millimetres) to an OpenIGTLink server\n"
  "as one POLYDATA message in RAS millimetres (x and y negated), e.g. to 3D Slicer: add an\n"
  "OpenIGTLinkIF connector of type Server on port 18944, activate it, then run\n"
  "  bender-cli igtl-send vessel.vtp --to 127.0.0.1:18944 --name BenderVessel\n"
  "Polygons are sent as polygons; triangle strips, lines and vertices are not sent.\n"
  "\n"
  "options:\n"
  "  --to HOST:PORT   the server (required)\n"
  "  --name NAME      device name of the message, 1 to 20 characters (default BenderSurface)\n"
  "  --timeout S      seconds allowed to connect and to send (default 5)\n"
  "  --plan PLAN      also send the final ribbon of the plan's last warp as two TRANSFORMs,\n"
  "                   <NAME>RibbonStart and <NAME>RibbonEnd (NAME cut to 9 characters;\n"
  "                   x = tangent, z = normal, in RAS)\n"
  "  -h, --help       this help\n"
  "\n"
  "exit status: 0 sent, 1 unreadable surface or the server cannot be reached, 2 usage error\n"
  "See docs/tracking.md (OpenIGTLink).\n";
} // namespace

int RunIgtlSendCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("igtl-send", Usage);
  std::vector<std::string> positional;
  std::string to, name = "BenderSurface", planPath;
  double timeout = 5.0;
  cli.App.add_option("surface", positional);
  cli.App.add_option("--to", to);
  cli.App.add_option("--name", name);
  cli.App.add_option("--timeout", timeout);
  cli.App.add_option("--plan", planPath);
  if (const int status = cli.Parse(args); status >= 0)
  {
    return status;
  }
  if (positional.size() != 1)
  {
    return cli.UsageError("expected one SURFACE");
  }
  if (to.empty())
  {
    return cli.UsageError("--to HOST:PORT is required");
  }
  if (name.empty() || name.size() > 20)
  {
    return cli.UsageError("--name '" + name + "': expected 1 to 20 characters");
  }
  if (!(timeout > 0.0 && timeout <= 3600.0))
  {
    return cli.UsageError("--timeout: expected seconds in (0, 3600]");
  }
  bender::IgtlSender::Options options;
  try
  {
    bender::ParseHostPort(to, "--to", options.host, options.port);
  }
  catch (const bender::TrackingError& e)
  {
    return cli.UsageError(e.what());
  }
  options.connectTimeout = std::chrono::milliseconds(long(timeout * 1000.0));
  options.writeTimeout = options.connectTimeout;

  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  bender::IgtlSurface surface;
  std::optional<bender::RibbonSpec> ribbon;
  try
  {
    if (!planPath.empty())
    {
      const bender::WarpPlan plan = bender::ReadWarpPlan(planPath);
      if (plan.warps.empty())
      {
        std::fprintf(stderr, "bender-cli igtl-send: %s: the plan has no warp\n", planPath.c_str());
        return 1;
      }
      ribbon = plan.warps.back().final;
      bender::IgtlRibbonEndFrame(ribbon->start); // refuse a degenerate frame before sending
      bender::IgtlRibbonEndFrame(ribbon->end);
    }
    surface = bender::MakeIgtlSurface(bender::ReadMesh(positional[0]), positional[0]);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bender-cli igtl-send: %s\n", e.what());
    return 1;
  }
  try
  {
    bender::SlicerLink::Options link;
    link.sender = options;
    link.surfaceName = name;
    link.ribbonPrefix = name.substr(0, 9) + "Ribbon";
    auto frame = std::make_shared<bender::SlicerLink::Frame>();
    frame->surface = surface;
    frame->ribbon = ribbon;
    frame->final = true;
    bender::SlicerLink sender(link);
    sender.Submit(frame);
    sender.Finish();
    std::printf("sent POLYDATA '%s' (%zu points, %zu polygons, %llu bytes) to %s:%d\n",
      name.c_str(),
      surface.points.size(),
      surface.polygons.size(),
      static_cast<unsigned long long>(sender.GetCounters().bytes),
      options.host.c_str(),
      options.port);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bender-cli igtl-send: %s\n", e.what());
    return 1;
  }
  return 0;
}
