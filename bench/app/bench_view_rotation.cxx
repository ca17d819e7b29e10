// bench_view_rotation: frames per second while the camera is rotated with the mouse in the
// application's 3D view (BenderView: the session's live surface, the ribbon layer, the marker
// and the scale bar), on the demo vessel subdivided 64-fold (1.3 M triangles, or a mesh given
// with --mesh), with the level of detail off (the whole surface drawn every frame) and on (a
// vtkQuadricClustering copy while the button is down). Each frame: one mouse move through the
// interactor (the trackball style rotates), the render finished with glFinish.
//
// usage: bench_view_rotation [--frames N] [--size WxH] [--mesh FILE]   (xvfb-run)
#include "BenderSession.h"
#include "BenderView.h"
#include "DemoPipeline.h"
#include "MeshIO.h"

#include <QApplication>
#include <QSurfaceFormat>

#include <QVTKOpenGLNativeWidget.h>

#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLinearSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPolyData.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{
using Clock = std::chrono::steady_clock;

// Frames per second of `frames` rotation steps (press, moves, release).
double Rotate(BenderView& view, int frames)
{
  vtkRenderWindow* window = view.renderer()->GetRenderWindow();
  vtkRenderWindowInteractor* interactor = window->GetInteractor();
  const int* size = view.renderer()->GetSize();
  const int x0 = size[0] / 2, y0 = size[1] / 2;
  interactor->SetEventInformation(x0, y0);
  interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  // One warm-up frame: the decimated copy is made at the first rotation of a new surface.
  interactor->SetEventInformation(x0 + 2, y0);
  interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  window->Render();
  const auto start = Clock::now();
  for (int i = 1; i <= frames; ++i)
  {
    interactor->SetEventInformation(x0 + 2 + 4 * i, y0 + (i % 7));
    interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
    window->Render(); // the style asked for one; make sure it is drawn and finished
    static_cast<vtkOpenGLRenderWindow*>(window)->WaitForCompletion();
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
  return frames / seconds;
}
}

int main(int argc, char** argv)
{
  int frames = 30, width = 1024, height = 768;
  std::string mesh;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
      frames = std::max(3, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--size") && i + 1 < argc)
      std::sscanf(argv[++i], "%dx%d", &width, &height);
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc)
      mesh = argv[++i];
  }
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  try
  {
    vtkSmartPointer<vtkPolyData> surface;
    if (mesh.empty())
    {
      vtkSmartPointer<vtkPolyData> vessel = bender::ReadMesh(bender::DemoVesselPath());
      vtkNew<vtkTriangleFilter> triangles;
      triangles->SetInputData(vessel);
      vtkNew<vtkLinearSubdivisionFilter> subdivide;
      subdivide->SetInputConnection(triangles->GetOutputPort());
      subdivide->SetNumberOfSubdivisions(3);
      subdivide->Update();
      surface = subdivide->GetOutput();
    }
    else
    {
      surface = bender::ReadMesh(mesh);
    }
    bender::BenderSession session;
    session.SetSurface(surface, "bench");
    BenderView view(session.GetOutputPort());
    // As the window's gesture controller connects it: the session's decimated copy.
    view.setLevelOfDetail(
      session.GetProxyOutputPort(), [&session]() { return session.IsDraggingProxy(); });
    view.resize(width, height);
    view.show();
    for (int i = 0; i < 20; ++i)
      QApplication::processEvents();
    view.resetCamera();
    std::printf("mesh: %lld triangles, view %dx%d, %d frames\n",
      static_cast<long long>(surface->GetNumberOfPolys()),
      width,
      height,
      frames);
    view.setLevelOfDetailThreshold(-1 + (1LL << 62)); // off: the whole surface every frame
    const double full = Rotate(view, frames);
    std::printf("rotate, whole surface:        %6.2f frames/s\n", full);
    view.setLevelOfDetailThreshold(500000);
    const auto start = Clock::now();
    const double lod = Rotate(view, frames);
    const double build = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("rotate, level of detail:      %6.2f frames/s (copy of %lld triangles; the "
                "first rotation, copy made, took %.2f s)\n",
      lod,
      static_cast<long long>(session.GetProxySurface()->GetNumberOfPolys()),
      build);
    const double again = Rotate(view, frames);
    std::printf("rotate, level of detail again: %6.2f frames/s\n", again);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_view_rotation: %s\n", e.what());
    return 1;
  }
  return 0;
}
