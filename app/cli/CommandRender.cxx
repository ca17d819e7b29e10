// bender-cli render MESH -o OUT.png [--plan PLAN --show-ribbon] [--view ...]: an off-screen
// VTK rendering for documentation and tests.

#include "CliCommand.h"
#include "CliParsing.h"
#include "HeadlessDisplay.h"

#include "MeshIO.h"
#include "RenderToPng.h"
#include "WarpPlanIO.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdio>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Renders MESH off screen and writes a PNG. Without a display a private Xvfb is started when "
  "installed (else the command says so and fails).\n"
  "\n"
  "exit status: 0 written, 1 bad input or rendering failure, 2 usage error";

struct RenderArguments
{
  std::string input, planPath, view = "iso", size = "800x600";
  bool showRibbon = false;
  bender::RenderToPngOptions options;
};

// "WxH" in pixels, each in [16, 8192].
bool ReadSize(const std::string& text, int& width, int& height)
{
  char tail = 0;
  return std::sscanf(text.c_str(), "%dx%d%c", &width, &height, &tail) == 2 && width >= 16 &&
    height >= 16 && width <= 8192 && height <= 8192;
}

int RunRender(RenderArguments a)
{
  bender::RenderToPngOptions& options = a.options;
  bender::ParseRenderView(a.view, options.view);
  ReadSize(a.size, options.width, options.height);
  if (bender::SameFile(a.input, options.output) ||
    (!a.planPath.empty() && bender::SameFile(a.planPath, options.output)))
  {
    return bender::CommandError("render", options.output + ": refusing to overwrite an input file");
  }
  const vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(a.input);
  const bender::WarpPlan plan =
    a.planPath.empty() ? bender::WarpPlan() : bender::ReadWarpPlan(a.planPath);
  if (a.showRibbon)
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
    return bender::CommandError("render", options.output + ": " + problem);
  }
  bender::RenderToPng(mesh, options);
  return 0;
}
} // namespace

void bender::AddRenderCommand(CLI::App& cli)
{
  auto a = std::make_shared<RenderArguments>();
  CLI::App* render = AddCommand(cli,
    "render",
    "render a mesh (optionally with a plan's ribbons) to a PNG",
    Details,
    [a] { return RunRender(*a); });
  render->add_option("MESH", a->input, "the mesh to render")->required();
  render->add_option("-o,--output", a->options.output, "the image")
    ->required()
    ->type_name("OUT.png");
  CLI::Option* plan =
    render->add_option("--plan", a->planPath, "a .bender.json plan, for --show-ribbon")
      ->type_name("PLAN");
  render
    ->add_flag(
      "--show-ribbon", a->showRibbon, "draw the plan's ribbons: initial (blue) and final (orange)")
    ->needs(plan);
  OneOf(render->add_option("--view", a->view, "camera direction; LPS: front looks along +y"),
    { "iso", "front", "back", "left", "right", "top", "bottom" })
    ->capture_default_str();
  render->add_option("--size", a->size, "image size in pixels, each in [16, 8192]")
    ->type_name("WxH")
    ->check(CLI::Validator(
      [](std::string& text) -> std::string
      {
        int width = 0, height = 0;
        return ReadSize(text, width, height) ? "" : "'" + text + "' is not WxH in 16..8192";
      },
      "WxH"))
    ->capture_default_str();
  render->add_flag("--wireframe", a->options.wireframe, "draw the triangle edges on the surface");
}
