// bender-cli igtl-send SURFACE --to HOST:PORT [--name NAME]: sends a surface to an
// OpenIGTLink server (3D Slicer's OpenIGTLinkIF connector in server mode) as POLYDATA in RAS.
// The sending itself is bender::SlicerLink (modules/Logic), which the application's "Send to
// Slicer" uses too.

#include "CliCommand.h"
#include "CliParsing.h"

#include "IgtlSender.h"
#include "IgtlSocket.h"
#include "IgtlSurfaceFromMesh.h"
#include "MeshIO.h"
#include "SlicerLink.h"
#include "TrackingErrors.h"
#include "WarpPlanIO.h"

#include <vtkPolyData.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

namespace
{
const char* const Details =
  "Sends a surface (.stl .obj .ply .vtp .vtk .off, LPS millimetres) to an OpenIGTLink server as "
  "one POLYDATA message in RAS millimetres (x and y negated), e.g. to 3D Slicer: add an "
  "OpenIGTLinkIF connector of type Server on port 18944, activate it, then run\n"
  "  bender-cli igtl-send vessel.vtp --to 127.0.0.1:18944 --name BenderVessel\n"
  "Polygons are sent as polygons; triangle strips, lines and vertices are not sent.\n"
  "\n"
  "exit status: 0 sent, 1 unreadable surface or the server cannot be reached, 2 usage error\n"
  "See docs/tracking.md (OpenIGTLink).";

struct IgtlSendArguments
{
  std::string input, to, name = "BenderSurface", planPath;
  double timeout = 5.0;
};

int RunIgtlSend(const IgtlSendArguments& a)
{
  const std::string& name = a.name;
  const std::string& planPath = a.planPath;
  bender::IgtlSender::Options options;
  bender::ParseHostPort(a.to, "--to", options.host, options.port);
  const double timeout = a.timeout;
  options.connectTimeout = std::chrono::milliseconds(long(timeout * 1000.0));
  options.writeTimeout = options.connectTimeout;

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
    surface = bender::MakeIgtlSurface(bender::ReadMesh(a.input), a.input);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bender-cli igtl-send: %s\n", bender::ErrorLine(e.what()).c_str());
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
    std::fprintf(stderr, "bender-cli igtl-send: %s\n", bender::ErrorLine(e.what()).c_str());
    return 1;
  }
  return 0;
}
} // namespace

void bender::AddIgtlSendCommand(CLI::App& cli)
{
  auto a = std::make_shared<IgtlSendArguments>();
  CLI::App* send = AddCommand(cli,
    "igtl-send",
    "send a surface to 3D Slicer (OpenIGTLink POLYDATA, RAS)",
    Details,
    [a] { return RunIgtlSend(*a); });
  send->add_option("SURFACE", a->input, "the surface to send")->required();
  send->add_option("--to", a->to, "the server")
    ->required()
    ->option_text("HOST:PORT")
    ->check(CLI::Validator(
      [](std::string& text) -> std::string
      {
        std::string host;
        int port = 0;
        try
        {
          bender::ParseHostPort(text, "address", host, port);
        }
        catch (const bender::TrackingError& e)
        {
          return e.what();
        }
        return {};
      },
      "HOST:PORT"));
  send->add_option("--name", a->name, "device name of the message, 1 to 20 characters")
    ->type_name("NAME")
    ->check(CLI::Validator(
      [](std::string& text) -> std::string
      {
        return text.empty() || text.size() > 20 ? "'" + text + "': expected 1 to 20 characters"
                                                : std::string();
      },
      "1 to 20 characters"))
    ->capture_default_str();
  send->add_option("--timeout", a->timeout, "seconds allowed to connect and to send")
    ->type_name("S")
    ->check(bender::NumberAbove(0, 3600))
    ->capture_default_str();
  send
    ->add_option("--plan",
      a->planPath,
      "also send the final ribbon of the plan's last warp as two TRANSFORMs, <NAME>RibbonStart "
      "and <NAME>RibbonEnd (NAME cut to 9 characters; x = tangent, z = normal, in RAS)")
    ->type_name("PLAN");
}
