#include "RenderToPng.h"

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "vtkBenderRibbonSource.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <cstdlib>

namespace bender
{

namespace
{
const std::pair<const char*, RenderView> ViewNames[] = { { "iso", RenderView::Iso },
  { "front", RenderView::Front },
  { "back", RenderView::Back },
  { "left", RenderView::Left },
  { "right", RenderView::Right },
  { "top", RenderView::Top },
  { "bottom", RenderView::Bottom } };
} // namespace

bool ParseRenderView(const std::string& name, RenderView& view)
{
  for (const auto& entry : ViewNames)
  {
    if (name == entry.first)
    {
      view = entry.second;
      return true;
    }
  }
  return false;
}

std::string RenderViewName(RenderView view)
{
  for (const auto& entry : ViewNames)
  {
    if (view == entry.second)
    {
      return entry.first;
    }
  }
  return "iso";
}

namespace
{
vtkSmartPointer<vtkActor> RibbonActor(const RenderRibbon& r)
{
  vtkNew<vtkBenderRibbonSource> source;
  source->SetRibbon(r.ribbon);
  source->SetWidth(r.width);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort(0));
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r.color[0], r.color[1], r.color[2]);
  actor->GetProperty()->BackfaceCullingOff();
  // The strip's normals face one side only: light it mostly ambiently so both sides show.
  actor->GetProperty()->SetAmbient(0.5);
  actor->GetProperty()->SetDiffuse(0.5);
  return actor;
}
} // namespace

void AimCamera(vtkCamera* camera, RenderView view)
{
  camera->SetFocalPoint(0, 0, 0);
  double position[3] = { 1, -1, 0.8 }, up[3] = { 0, 0, 1 };
  switch (view)
  {
    case RenderView::Iso:
      break;
    case RenderView::Front:
      position[0] = 0, position[1] = -1, position[2] = 0;
      break;
    case RenderView::Back:
      position[0] = 0, position[1] = 1, position[2] = 0;
      break;
    case RenderView::Left:
      position[0] = 1, position[1] = 0, position[2] = 0;
      break;
    case RenderView::Right:
      position[0] = -1, position[1] = 0, position[2] = 0;
      break;
    case RenderView::Top:
    case RenderView::Bottom:
      position[0] = 0, position[1] = 0, position[2] = view == RenderView::Top ? 1 : -1;
      up[0] = 0, up[1] = -1, up[2] = 0;
      break;
  }
  camera->SetPosition(position);
  camera->SetViewUp(up);
}

void WritePng(vtkImageData* image, const std::string& path)
{
  std::string writeProblem;
  const bool written = AtomicWrite(
    path,
    [image](const std::string& tempPath, std::string& why)
    {
      vtkNew<vtkPNGWriter> writer;
      writer->SetFileName(tempPath.c_str());
      writer->SetInputData(image);
      writer->Write();
      if (writer->GetErrorCode() != 0)
      {
        why = "cannot write the image";
        return false;
      }
      return true;
    },
    writeProblem);
  if (!written)
  {
    throw InputError(
      path + ": " + (writeProblem.empty() ? "cannot write the image" : writeProblem));
  }
}

void RenderToPng(vtkPolyData* surface, const RenderToPngOptions& options)
{
  const std::string& path = options.output;
  if (path.empty())
  {
    throw InputError("render: no output image given");
  }
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    throw InputError(path + ": there is no surface to render");
  }
  if (options.width < 16 || options.height < 16 || options.width > 8192 || options.height > 8192)
  {
    throw InputError(path + ": the image size must be in 16..8192 pixels");
  }
  // Debian's VTK renders through GLX: without an X server the render window would abort the
  // process. The application starts a private one (HeadlessDisplay) before it renders.
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    throw EnvironmentError(path +
      ": no display: DISPLAY is not set (run under xvfb-run -a, or through bender-cli, which "
      "starts a private Xvfb)");
  }

  vtkNew<vtkRenderer> renderer;
  if (options.darkBackground)
  {
    renderer->SetBackground(0.12, 0.13, 0.16);
    renderer->SetBackground2(0.32, 0.34, 0.40);
    renderer->GradientBackgroundOn();
  }
  else
  {
    renderer->SetBackground(1.0, 1.0, 1.0);
  }
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(surface);
  normals->SplittingOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(options.color[0], options.color[1], options.color[2]);
  actor->GetProperty()->SetSpecular(0.2);
  actor->GetProperty()->SetOpacity(options.opacity);
  if (options.wireframe)
  {
    actor->GetProperty()->EdgeVisibilityOn();
    actor->GetProperty()->SetEdgeColor(0.3, 0.3, 0.3);
  }
  renderer->AddActor(actor);
  vtkNew<vtkPolyDataMapper> ghostMapper;
  vtkNew<vtkActor> ghostActor;
  if (options.ghost)
  {
    ghostMapper->SetInputData(options.ghost);
    ghostMapper->ScalarVisibilityOff();
    ghostActor->SetMapper(ghostMapper);
    ghostActor->GetProperty()->SetColor(0.8, 0.85, 0.95);
    ghostActor->GetProperty()->SetOpacity(0.22);
    renderer->AddActor(ghostActor);
  }
  for (const RenderRibbon& ribbon : options.ribbons)
  {
    renderer->AddActor(RibbonActor(ribbon));
  }

  AimCamera(renderer->GetActiveCamera(), options.view);
  renderer->ResetCamera();

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(options.width, options.height);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  WriteRenderWindowPng(window, path);
}

void WriteRenderWindowPng(vtkRenderWindow* window, const std::string& path)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();

  WritePng(grab->GetOutput(), path);
}

} // namespace bender
