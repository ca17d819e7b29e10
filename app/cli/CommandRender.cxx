// bender-cli render MESH -o OUT.png [--plan PLAN --show-ribbon] [--view ...]: an off-screen
// VTK rendering for documentation and tests.

#include "CliCommands.h"

#include "MeshIO.h"
#include "WarpPlanIO.h"
#include "vtkBenderRibbonSource.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace
{
const char* const Usage =
  "usage: bender-cli render MESH -o OUT.png [options]\n"
  "\n"
  "Renders MESH off screen (no display needed where VTK offers off-screen rendering; under\n"
  "Xvfb otherwise) and writes a PNG.\n"
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

vtkSmartPointer<vtkActor> RibbonActor(const bender::RibbonSpec& ribbon, double width,
  const double color[3])
{
  vtkNew<vtkBenderRibbonSource> source;
  source->SetRibbon(ribbon);
  source->SetWidth(width);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort(0));
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(color[0], color[1], color[2]);
  actor->GetProperty()->BackfaceCullingOff();
  // The strip's normals face one side only: light it mostly ambiently so both sides show.
  actor->GetProperty()->SetAmbient(0.5);
  actor->GetProperty()->SetDiffuse(0.5);
  return actor;
}
} // namespace

int RunRenderCommand(const std::vector<std::string>& args)
{
  std::vector<std::string> positional;
  std::string outPath, planPath, view = "iso";
  bool showRibbon = false, wireframe = false;
  int width = 800, height = 600;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= args.size())
      {
        std::fprintf(stderr, "bender-cli render: %s needs a value\n", a.c_str());
        return false;
      }
      out = args[++i];
      return true;
    };
    if (a == "-h" || a == "--help")
    {
      std::fputs(Usage, stdout);
      return 0;
    }
    else if (a == "-o" || a == "--output")
    {
      if (!value(outPath))
      {
        return 2;
      }
    }
    else if (a == "--plan")
    {
      if (!value(planPath))
      {
        return 2;
      }
    }
    else if (a == "--view")
    {
      if (!value(view))
      {
        return 2;
      }
      if (view != "iso" && view != "front" && view != "back" && view != "left" &&
        view != "right" && view != "top" && view != "bottom")
      {
        std::fprintf(stderr, "bender-cli render: --view: unknown value '%s'\n", view.c_str());
        return 2;
      }
    }
    else if (a == "--size")
    {
      std::string v;
      if (!value(v) || std::sscanf(v.c_str(), "%dx%d", &width, &height) != 2 || width < 16 ||
        height < 16 || width > 8192 || height > 8192)
      {
        std::fprintf(stderr, "bender-cli render: --size: expected WxH in 16..8192\n");
        return 2;
      }
    }
    else if (a == "--show-ribbon")
    {
      showRibbon = true;
    }
    else if (a == "--wireframe")
    {
      wireframe = true;
    }
    else if (a.size() > 1 && a[0] == '-')
    {
      std::fprintf(stderr, "bender-cli render: unknown option '%s'\n%s", a.c_str(), Usage);
      return 2;
    }
    else
    {
      positional.push_back(a);
    }
  }
  if (positional.size() != 1 || outPath.empty())
  {
    std::fprintf(stderr, "bender-cli render: expected MESH -o OUT.png\n%s", Usage);
    return 2;
  }
  if (showRibbon && planPath.empty())
  {
    std::fprintf(stderr, "bender-cli render: --show-ribbon needs --plan PLAN\n");
    return 2;
  }
  if (bender::SameFile(positional[0], outPath) || (!planPath.empty() && bender::SameFile(planPath, outPath)))
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

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(mesh);
  normals->SplittingOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.85, 0.78, 0.70);
  actor->GetProperty()->SetSpecular(0.2);
  if (wireframe)
  {
    actor->GetProperty()->EdgeVisibilityOn();
    actor->GetProperty()->SetEdgeColor(0.3, 0.3, 0.3);
  }
  renderer->AddActor(actor);
  if (showRibbon)
  {
    // See the ribbons through the surface.
    actor->GetProperty()->SetOpacity(0.45);
    const double diag = mesh->GetLength();
    const double blue[3] = { 0.2, 0.4, 0.9 }, orange[3] = { 0.95, 0.5, 0.1 };
    for (const bender::WarpSpec& w : plan.warps)
    {
      renderer->AddActor(RibbonActor(w.initial, 0.02 * diag, blue));
      renderer->AddActor(RibbonActor(w.final, 0.02 * diag, orange));
    }
  }

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  // LPS: +x left, +y posterior, +z superior. "front" looks from anterior (-y) along +y.
  double position[3] = { 1, -1, 0.8 }, up[3] = { 0, 0, 1 };
  if (view == "front")
  {
    position[0] = 0, position[1] = -1, position[2] = 0;
  }
  else if (view == "back")
  {
    position[0] = 0, position[1] = 1, position[2] = 0;
  }
  else if (view == "left")
  {
    position[0] = 1, position[1] = 0, position[2] = 0;
  }
  else if (view == "right")
  {
    position[0] = -1, position[1] = 0, position[2] = 0;
  }
  else if (view == "top" || view == "bottom")
  {
    position[0] = 0, position[1] = 0, position[2] = view == "top" ? 1 : -1;
    up[0] = 0, up[1] = -1, up[2] = 0;
  }
  camera->SetPosition(position);
  camera->SetViewUp(up);
  renderer->ResetCamera();

  // Debian's VTK renders through GLX: without an X server the render window would abort the
  // process. Say so instead (under CI and on servers, run inside xvfb-run).
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    std::fprintf(stderr,
      "bender-cli render: no display: this VTK renders through an X server; run under "
      "xvfb-run (e.g. xvfb-run -a bender-cli render ...)\n");
    return 1;
  }
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();

  // Atomic: write a temporary PNG beside the target, then rename it over the target.
  const std::string tmp = outPath + ".tmp." + std::to_string(getpid()) + ".png";
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(tmp.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0 || std::rename(tmp.c_str(), outPath.c_str()) != 0)
  {
    std::remove(tmp.c_str());
    return Fail(outPath + ": cannot write the image");
  }
  return 0;
}
