// bender-cli render MESH -o OUT.png [--plan PLAN --show-ribbon] [--view ...]: an off-screen
// VTK rendering for documentation and tests.

#include "CliCommands.h"
#include "CliParsing.h"
#include "HeadlessDisplay.h"

#include "MeshIO.h"
#include "RenderToPng.h"
#include "WarpPlanIO.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdio>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli render MESH -o OUT.png [options]\n"
  "\n"
  "Renders MESH off screen and writes a PNG. Without a display a private Xvfb is started\n"
  "when installed (else the command says so and fails).\n"
  "\n"
  "options:\n"
  "  -o, --output OUT.png      the image (required)\n"
  "  --plan PLAN               a .bender.json plan, for --show-ribbon\n"
  "  --show-ribbon             draw the plan's ribbons: initial (blue) and final (orange)\n"
  "  --view iso|front|back|left|right|top|bottom\n"
  "                            camera direction (default iso); LPS: front looks along +y\n"
  "  --size WxH                image size in pixels (default 800x600)\n"
  "  --wireframe               draw the triangle edges on the surface\n"
  "  -h, --help                this help\n"
  "\n"
  "exit status: 0 written, 1 bad input or rendering failure, 2 usage error\n";

int Fail(const std::string& message)
{
  std::fprintf(stderr, "bender-cli render: %s\n", message.c_str());
  return 1;
}
} // namespace

int RunRenderCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("render", Usage);
  std::vector<std::string> positional;
  std::string outPath, planPath, view = "iso", size;
  bool showRibbon = false;
  bender::RenderToPngOptions options;
  cli.App.add_option("mesh", positional);
  cli.App.add_option("-o,--output", outPath);
  cli.App.add_option("--plan", planPath);
  cli.App.add_option("--view", view);
  cli.App.add_option("--size", size);
  cli.App.add_flag("--show-ribbon", showRibbon);
  cli.App.add_flag("--wireframe", options.wireframe);
  if (const int status = cli.Parse(args); status >= 0)
  {
    return status;
  }
  if (!bender::ParseRenderView(view, options.view))
  {
    return cli.UsageError("--view: unknown value '" + view + "'");
  }
  if (!size.empty())
  {
    char tail = 0;
    if (std::sscanf(size.c_str(), "%dx%d%c", &options.width, &options.height, &tail) != 2 ||
      options.width < 16 || options.height < 16 || options.width > 8192 || options.height > 8192)
    {
      return cli.UsageError("--size: expected WxH in 16..8192");
    }
  }
  if (positional.size() != 1 || outPath.empty())
  {
    return cli.UsageError("expected MESH -o OUT.png");
  }
  if (showRibbon && planPath.empty())
  {
    return cli.UsageError("--show-ribbon needs --plan PLAN");
  }
  if (bender::SameFile(positional[0], outPath) ||
    (!planPath.empty() && bender::SameFile(planPath, outPath)))
  {
    return Fail(outPath + ": refusing to overwrite an input file");
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkSmartPointer<vtkPolyData> mesh;
  bender::WarpPlan plan;
  try
  {
    mesh = bender::ReadMesh(positional[0]);
    if (!planPath.empty())
    {
      plan = bender::ReadWarpPlan(planPath);
    }
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
  options.output = outPath;
  if (showRibbon)
  {
    // See the ribbons through the surface: initial blue, final orange.
    options.opacity = 0.45;
    const double width = 0.02 * mesh->GetLength();
    for (const bender::WarpSpec& w : plan.warps)
    {
      options.ribbons.push_back({ w.initial, width, { { 0.2, 0.4, 0.9 } } });
      options.ribbons.push_back({ w.final, width, { { 0.95, 0.5, 0.1 } } });
    }
  }
  if (const std::string problem = bender::EnsureHeadlessDisplay(); !problem.empty())
  {
    return Fail(outPath + ": " + problem);
  }
  try
  {
    bender::RenderToPng(mesh, options);
  }
  catch (const bender::Error& e)
  {
    return Fail(e.what());
  }
  return 0;
}
