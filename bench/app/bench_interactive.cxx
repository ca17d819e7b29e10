// bench_interactive: the interactive bend in the application's 3D view (BenderView: the
// session's live surface, its level-of-detail copy, the ribbon layer, the ghost of the original
// shape, the marker and the scale bar), on the demo vessel and on the demo vessel subdivided
// 64-fold (1.3 M triangles). One frame = the ribbon's end handle moves (as a drag does), the
// session warps live (vtkBenderWarpFilter, Precision Table), the view renders and glFinish.
//
// Printed (medians with min/max over the frames, or over the rounds for the ratio):
//  - the machine: processor, cores, load average, OpenGL renderer;
//  - the demo vessel's drag (target >= 30 frames/s), without the ghost, and VTK's plain redraw
//    of the same mesh (the view's own share of a frame);
//  - the big vessel dragged with its level-of-detail copy (target >= 10 frames/s), the grab
//    (the copy is made at the first grab) and the release (exact warp, check, new copy);
//  - the big vessel's full-resolution drag frame against VTK's own cost of redrawing the same
//    mesh with modified points (a plain vtkPolyDataMapper in a view of the same size and kind,
//    points Modified(), Render and glFinish), measured in alternating rounds in the same run
//    (target: ratio <= 1.2).
//
// usage: bench_interactive [--frames N] [--rounds K] [--size WxH] [--demo-only]   (xvfb-run)
#include "BenderSession.h"
#include "BenderView.h"
#include "DemoPipeline.h"
#include "MeshIO.h"
#include "WarpPlanIO.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QApplication>
#include <QSurfaceFormat>

#include <QVTKOpenGLNativeWidget.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLinearSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{

using Clock = std::chrono::steady_clock;

double Milliseconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// Processor time of the whole process (all threads: the warp's and llvmpipe's), in ms: far
/// less sensitive than the wall clock to other programs loading the machine.
double ProcessCpuMs()
{
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

/// One frame's cost: wall clock and processor time.
struct FrameTimes
{
  std::vector<double> wall, cpu;
  void Add(const FrameTimes& other)
  {
    wall.insert(wall.end(), other.wall.begin(), other.wall.end());
    cpu.insert(cpu.end(), other.cpu.begin(), other.cpu.end());
  }
};

struct Stats
{
  double median = 0.0, min = 0.0, max = 0.0;
};

Stats Summarize(std::vector<double> values)
{
  Stats s;
  if (values.empty())
  {
    return s;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  s.min = values.front();
  s.max = values.back();
  return s;
}

std::string ReadLineOf(const char* path, const char* key)
{
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
  {
    if (!key || line.rfind(key, 0) == 0)
    {
      const auto colon = line.find(':');
      return key && colon != std::string::npos ? line.substr(colon + 2) : line;
    }
  }
  return "?";
}

std::string OpenGLRenderer(vtkRenderWindow* window)
{
  std::istringstream in(window->ReportCapabilities());
  std::string line;
  while (std::getline(in, line))
  {
    const auto at = line.find("OpenGL renderer string:");
    if (at != std::string::npos)
    {
      std::string name = line.substr(at + 23);
      name.erase(0, name.find_first_not_of(' '));
      return name;
    }
  }
  return "?";
}

void Pump()
{
  for (int i = 0; i < 10; ++i)
  {
    QApplication::processEvents();
  }
}

void Finish(vtkRenderWindow* window)
{
  window->Render();
  static_cast<vtkOpenGLRenderWindow*>(window)->WaitForCompletion();
}

// The ribbon's end swings back and forth towards the plan's final ribbon (60-frame period).
bender::RibbonSpec Moved(const bender::WarpSpec& warp, int frame)
{
  const double t = 0.5 - 0.5 * std::cos(6.283185307179586 * (frame + 1) / 60.0);
  bender::RibbonSpec moved = warp.initial;
  moved.end.position = (1 - t) * warp.initial.end.position + t * warp.final.end.position;
  moved.end.tangent =
    bender::Normalized((1 - t) * warp.initial.end.tangent + t * warp.final.end.tangent);
  moved.end.normal = (1 - t) * warp.initial.end.normal + t * warp.final.end.normal;
  return moved;
}

/// The application's view on a session, with the ribbon widget on the plan's ribbon.
struct AppView
{
  bender::BenderSession session;
  std::unique_ptr<BenderView> view;

  AppView(vtkPolyData* surface, const bender::WarpSpec& warp, int width, int height)
  {
    session.SetSurface(surface, "bench");
    bender::WarpParameters parameters;
    parameters.radius = warp.radius;
    parameters.decay = warp.decay;
    session.SetParameters(parameters);
    view = std::make_unique<BenderView>(session.GetOutputPort());
    // As the window's gesture controller connects it.
    view->setLevelOfDetailThreshold(session.GetLevelOfDetailThreshold());
    view->setLevelOfDetail(
      session.GetProxyOutputPort(), [this]() { return this->session.IsDraggingProxy(); });
    view->setOriginalInPlay([this]() { return this->session.GetOriginalInPlay(); });
    view->resize(width, height);
    view->show();
    Pump();
    auto* rep = view->ribbonWidget()->GetRibbonRepresentation();
    rep->SetRibbon(warp.initial);
    rep->SetRadius(warp.radius);
    view->ribbonWidget()->On();
    view->resetCamera();
    Finish(window());
  }
  vtkRenderWindow* window() const { return view->renderer()->GetRenderWindow(); }

  /// Grab, `frames` moves each drawn and finished. The ghost of the original shape is shown
  /// while grabbed, as the window does (unless `ghost` is false).
  FrameTimes Drag(const bender::WarpSpec& warp, int frames, bool ghost, double* grabMs = nullptr)
  {
    const auto g0 = Clock::now();
    session.Grab(warp.initial);
    view->setOriginalSurface(session.GetOriginalSurface(), ghost);
    Finish(window());
    if (grabMs)
    {
      *grabMs = Milliseconds(g0, Clock::now());
    }
    auto* rep = view->ribbonWidget()->GetRibbonRepresentation();
    FrameTimes times;
    for (int frame = 0; frame < frames; ++frame)
    {
      const bender::RibbonSpec moved = Moved(warp, frame);
      const auto t0 = Clock::now();
      const double c0 = ProcessCpuMs();
      // As GestureController::onRibbonInteraction: the widget's ribbon moved, the session
      // warps quietly, one frame drawn.
      rep->SetRibbon(moved);
      view->quietly([&]() { session.MoveFinal(moved); });
      Finish(window());
      times.wall.push_back(Milliseconds(t0, Clock::now()));
      times.cpu.push_back(ProcessCpuMs() - c0);
    }
    return times;
  }
};

/// VTK's own cost: a plain vtkPolyDataMapper on a copy of the same mesh in a view of the same
/// size and kind; each frame moves points (the bound region, as the warp does), Modified(),
/// Render, glFinish.
struct ReferenceView
{
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkActor> actor;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  QVTKOpenGLNativeWidget widget;
  std::vector<float> original;

  ReferenceView(vtkPolyData* surface, int width, int height)
  {
    mesh->DeepCopy(surface);
    mapper->SetInputData(mesh);
    mapper->ScalarVisibilityOff();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.86, 0.36, 0.32);
    actor->GetProperty()->SetSpecular(0.3);
    actor->GetProperty()->SetSpecularPower(20);
    renderer->AddActor(actor);
    renderer->SetBackground(0.12, 0.13, 0.16);
    window->SetMultiSamples(0);
    window->AddRenderer(renderer);
    widget.setRenderWindow(window);
    widget.resize(width, height);
    widget.show();
    Pump();
    renderer->ResetCamera();
    Finish(window);
    auto* xyz = vtkFloatArray::SafeDownCast(mesh->GetPoints()->GetData());
    if (xyz)
    {
      original.assign(xyz->GetPointer(0), xyz->GetPointer(0) + 3 * mesh->GetNumberOfPoints());
    }
  }

  FrameTimes Redraw(int frames, vtkIdType moved)
  {
    auto* xyz = vtkFloatArray::SafeDownCast(mesh->GetPoints()->GetData());
    FrameTimes times;
    for (int frame = 0; frame < frames; ++frame)
    {
      const auto t0 = Clock::now();
      const double c0 = ProcessCpuMs();
      if (xyz)
      {
        float* p = xyz->GetPointer(0);
        const float shift = 0.01f * static_cast<float>(frame % 7);
        for (vtkIdType i = 0; i < std::min(moved, mesh->GetNumberOfPoints()); ++i)
        {
          p[3 * i] = original[3 * i] + shift;
        }
      }
      mesh->GetPoints()->Modified();
      Finish(window);
      times.wall.push_back(Milliseconds(t0, Clock::now()));
      times.cpu.push_back(ProcessCpuMs() - c0);
    }
    return times;
  }
};

void PrintFrames(const char* what, const FrameTimes& t)
{
  const Stats wall = Summarize(t.wall);
  const Stats cpu = Summarize(t.cpu);
  std::printf("  %-46s %5.1f frames/s  frame %6.1f ms (min %6.1f, max %6.1f)  processor %6.1f ms "
              "(min %6.1f, max %6.1f)  %zu frames\n",
    what,
    1000.0 / wall.median,
    wall.median,
    wall.min,
    wall.max,
    cpu.median,
    cpu.min,
    cpu.max,
    t.wall.size());
}

}

int main(int argc, char** argv)
{
  int frames = 40, rounds = 3, width = 1024, height = 768;
  bool demoOnly = false;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
      frames = std::max(5, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc)
      rounds = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--size") && i + 1 < argc &&
      std::sscanf(argv[++i], "%dx%d", &width, &height) == 2)
      continue;
    else if (!std::strcmp(argv[i], "--demo-only"))
      demoOnly = true;
    else
    {
      std::fprintf(
        stderr, "usage: bench_interactive [--frames N] [--rounds K] [--size WxH] [--demo-only]\n");
      return 2;
    }
  }
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    std::fprintf(stderr, "bench_interactive: needs an X display (run it under xvfb-run)\n");
    return 2;
  }
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  try
  {
    const bender::WarpPlan plan = bender::ReadWarpPlan(bender::DemoPlanPath());
    const bender::WarpSpec& warp = plan.warps.at(0);
    vtkSmartPointer<vtkPolyData> vessel = bender::ReadMesh(bender::DemoVesselPath());
    // The benchmark vessel: the demo vessel split 4x three times (linear: same shape).
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(vessel);
    vtkNew<vtkLinearSubdivisionFilter> subdivide;
    subdivide->SetInputConnection(triangles->GetOutputPort());
    subdivide->SetNumberOfSubdivisions(3);
    subdivide->Update();
    vtkSmartPointer<vtkPolyData> big = subdivide->GetOutput();

    std::printf("Interactive bend in the application's view, %dx%d, %d frames per drag\n",
      width,
      height,
      frames);
    std::printf("machine: %s, %u cores, load average at start %s\n",
      ReadLineOf("/proc/cpuinfo", "model name").c_str(),
      std::thread::hardware_concurrency(),
      ReadLineOf("/proc/loadavg", nullptr).c_str());

    // The demo vessel (20k triangles: drawn whole), with the ghost of the original as the
    // window shows it while grabbed, and without.
    double demoFps = 0.0;
    {
      AppView app(vessel, warp, width, height);
      std::printf("OpenGL: %s\n", OpenGLRenderer(app.window()).c_str());
      app.Drag(warp, 5, true);
      app.session.CancelGrab("bench");
      std::printf(
        "demo vessel, %lld triangles:\n", static_cast<long long>(vessel->GetNumberOfPolys()));
      const FrameTimes demo = app.Drag(warp, frames, true);
      app.session.CancelGrab("bench");
      PrintFrames("drag", demo);
      demoFps = 1000.0 / Summarize(demo.wall).median;
      PrintFrames("drag without the ghost of the original", app.Drag(warp, frames, false));
      app.session.CancelGrab("bench");
      // What VTK itself needs to redraw this mesh with moved points: the view's own share.
      ReferenceView plain(vessel, width, height);
      plain.Redraw(2, 2000);
      PrintFrames("VTK reference: plain mapper, points Modified()", plain.Redraw(frames, 2000));
    }

    if (demoOnly)
    {
      std::printf("load average at end: %s\n", ReadLineOf("/proc/loadavg", nullptr).c_str());
      std::printf(
        "target: demo >= 30 frames/s: %s (%.1f)\n", demoFps >= 30.0 ? "met" : "NOT met", demoFps);
      return 0;
    }

    // The big vessel dragged with its level-of-detail copy.
    std::printf(
      "benchmark vessel, %lld triangles:\n", static_cast<long long>(big->GetNumberOfPolys()));
    double proxyFps = 0.0;
    {
      AppView app(big, warp, width, height);
      double grabMs = 0.0;
      app.Drag(warp, 1, true, &grabMs);
      std::printf("  first grab (the copies of the surface and of the ghost made; %lld triangles, "
                  "%lld points bound): %.0f ms\n",
        static_cast<long long>(app.session.GetProxySurface()->GetNumberOfPolys()),
        app.session.GetNumberOfBoundPoints(),
        grabMs);
      app.session.CancelGrab("bench");
      double againMs = 0.0;
      const FrameTimes lod = app.Drag(warp, frames, true, &againMs);
      std::printf("  grab again (copies ready): %.0f ms; the view drew the copy: %s\n",
        againMs,
        app.view->isShowingProxy() ? "yes" : "NO");
      PrintFrames("drag with the level-of-detail copy", lod);
      proxyFps = 1000.0 / Summarize(lod.wall).median;
      // The release where the plan releases (it commits on the demo vessel).
      app.view->quietly([&]() { app.session.MoveFinal(warp.final); });
      Finish(app.window());
      app.session.ClearMessages();
      const auto r0 = Clock::now();
      const bool released = app.session.Release();
      Finish(app.window());
      std::printf("  release (exact warp of the whole surface, commit check, new copy; first "
                  "whole frame): %.0f ms, %s; the view draws the whole surface: %s\n",
        Milliseconds(r0, Clock::now()),
        app.session.GetMessages().empty() ? "?" : app.session.GetMessages().back().text.c_str(),
        app.view->isShowingProxy() ? "NO" : "yes");
      if (!released)
      {
        app.session.CancelGrab("bench");
      }
    }

    // The full-resolution frame against VTK's own redraw of the same mesh, in alternating rounds.
    FrameTimes full, reference;
    std::vector<double> wallRatios, cpuRatios;
    {
      AppView app(big, warp, width, height);
      app.session.SetLevelOfDetailThreshold(-1 + (1LL << 62)); // the whole surface while dragging
      ReferenceView plain(big, width, height);
      app.Drag(warp, 2, true);
      app.session.CancelGrab("bench");
      const vtkIdType bound = std::max<long long>(1, app.session.GetNumberOfBoundPoints());
      plain.Redraw(2, bound);
      for (int round = 0; round < rounds; ++round)
      {
        const FrameTimes a = app.Drag(warp, std::max(5, frames / 4), true);
        app.session.CancelGrab("bench");
        const FrameTimes b = plain.Redraw(std::max(5, frames / 4), bound);
        full.Add(a);
        reference.Add(b);
        wallRatios.push_back(Summarize(a.wall).median / Summarize(b.wall).median);
        cpuRatios.push_back(Summarize(a.cpu).median / Summarize(b.cpu).median);
      }
    }
    PrintFrames("drag, whole surface (level of detail off)", full);
    PrintFrames("VTK reference: plain mapper, points Modified()", reference);
    const Stats wallRatio = Summarize(wallRatios);
    const Stats cpuRatio = Summarize(cpuRatios);
    std::printf("  whole-surface frame / VTK reference: %.2f (min %.2f, max %.2f) wall clock, "
                "%.2f (min %.2f, max %.2f) processor time, over %d alternating rounds\n",
      wallRatio.median,
      wallRatio.min,
      wallRatio.max,
      cpuRatio.median,
      cpuRatio.min,
      cpuRatio.max,
      rounds);

    std::printf("load average at end: %s\n", ReadLineOf("/proc/loadavg", nullptr).c_str());
    std::printf("targets: drag with the copy >= 10 frames/s: %s (%.1f); whole-surface frame "
                "<= 1.2x VTK's: %s (%.2f); demo >= 30 frames/s: %s (%.1f)\n",
      proxyFps >= 10.0 ? "met" : "NOT met",
      proxyFps,
      wallRatio.median <= 1.2 ? "met" : "NOT met",
      wallRatio.median,
      demoFps >= 30.0 ? "met" : "NOT met",
      demoFps);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_interactive: %s\n", e.what());
    return 1;
  }
  return 0;
}
