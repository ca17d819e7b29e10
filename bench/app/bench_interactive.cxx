// bench_interactive: frames per second of the interactive bend and the share of each frame
// spent warping vs rendering, on the demo vessel and on a ~1 M-triangle mesh (the demo vessel
// subdivided 64-fold, 1.3 M triangles). One frame = the ribbon's end handle moves (as a drag does),
// the session warps the surface live (vtkBenderWarpFilter, Precision Table), the window renders it
// (finished with glFinish). Target: warp <= 20% of a frame, >= 30 fps on the demo vessel.
//
// usage: bench_interactive [--frames N] [--size WxH]   (needs an X display: xvfb-run)
#include "BenderSession.h"
#include "DemoPipeline.h"
#include "MeshIO.h"
#include "WarpPlanIO.h"
#include "vtkBenderRibbonRepresentation.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkLinearSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTriangleFilter.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

struct Result
{
  double staticMs = 0.0; ///< a frame with nothing changed: the renderer's floor
  double fps = 0.0;
  double warpMs = 0.0;
  double renderMs = 0.0;
  long long bound = 0;
};

Result Run(vtkPolyData* surface, const bender::WarpSpec& warp, int frames, int width, int height)
{
  bender::BenderSession session;
  session.SetSurface(surface, "bench");
  bender::WarpParameters parameters;
  parameters.radius = warp.radius;
  parameters.decay = warp.decay;
  session.SetParameters(parameters);

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkPolyDataMapper> mapper;
  // The application's pipeline: the session's output port, connected once.
  mapper->SetInputConnection(session.GetOutputPort());
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.86, 0.36, 0.32);
  renderer->AddActor(actor);
  vtkNew<vtkBenderRibbonRepresentation> ribbon;
  ribbon->SetRibbon(warp.initial);
  ribbon->SetRadius(warp.radius);
  ribbon->SetRenderer(renderer);
  renderer->AddViewProp(ribbon);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  window->Render();

  Result result;
  const auto s0 = Clock::now();
  for (int frame = 0; frame < 20; ++frame)
  {
    renderer->GetActiveCamera()->Azimuth(0.01);
    window->Render();
    window->WaitForCompletion();
  }
  result.staticMs = 1000.0 * Seconds(s0, Clock::now()) / 20;

  session.Grab(warp.initial);
  result.bound = session.GetNumberOfBoundPoints();
  double warpTime = 0.0, renderTime = 0.0;
  const auto start = Clock::now();
  for (int frame = 0; frame < frames; ++frame)
  {
    // The end of the ribbon swings back and forth towards the plan's final ribbon.
    const double t = 0.5 - 0.5 * std::cos(6.283185307179586 * frame / 60.0);
    bender::RibbonSpec moved = warp.initial;
    moved.end.position = (1 - t) * warp.initial.end.position + t * warp.final.end.position;
    moved.end.tangent =
      bender::Normalized((1 - t) * warp.initial.end.tangent + t * warp.final.end.tangent);
    moved.end.normal = (1 - t) * warp.initial.end.normal + t * warp.final.end.normal;
    const auto t0 = Clock::now();
    ribbon->SetRibbon(moved);
    session.MoveFinal(moved);
    const auto t1 = Clock::now();
    window->Render();
    window->WaitForCompletion();
    const auto t2 = Clock::now();
    warpTime += Seconds(t0, t1);
    renderTime += Seconds(t1, t2);
  }
  const double total = Seconds(start, Clock::now());
  result.fps = frames / total;
  result.warpMs = 1000.0 * warpTime / frames;
  result.renderMs = 1000.0 * renderTime / frames;
  return result;
}

void Report(const char* name, vtkPolyData* surface, const Result& r)
{
  const double frame = r.warpMs + r.renderMs;
  std::printf("%-28s %9lld tris %8lld bound  %6.1f fps  frame %7.2f ms  warp %6.2f ms (%4.1f%%)  "
              "render %7.2f ms (%4.1f%%)  [static frame %6.2f ms]\n",
    name,
    static_cast<long long>(surface->GetNumberOfPolys()),
    r.bound,
    r.fps,
    frame,
    r.warpMs,
    100.0 * r.warpMs / frame,
    r.renderMs,
    100.0 * r.renderMs / frame,
    r.staticMs);
}

}

int main(int argc, char** argv)
{
  int frames = 120;
  int width = 1024, height = 768;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
      frames = std::max(10, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--size") && i + 1 < argc &&
      std::sscanf(argv[++i], "%dx%d", &width, &height) == 2)
      continue;
    else
    {
      std::fprintf(stderr, "usage: bench_interactive [--frames N] [--size WxH]\n");
      return 2;
    }
  }
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    std::fprintf(stderr, "bench_interactive: needs an X display (run it under xvfb-run)\n");
    return 2;
  }
  try
  {
    const bender::WarpPlan plan = bender::ReadWarpPlan(bender::DemoPlanPath());
    vtkSmartPointer<vtkPolyData> vessel = bender::ReadMesh(bender::DemoVesselPath());
    std::printf(
      "Interactive loop: handle moved -> live warp (Table) -> frame rendered, %dx%d, %d frames\n",
      width,
      height,
      frames);
    const Result demo = Run(vessel, plan.warps[0], frames, width, height);
    Report("demo vessel", vessel, demo);

    // About 1 M triangles: the demo vessel split 4x three times (linear: same shape).
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(vessel);
    vtkNew<vtkLinearSubdivisionFilter> subdivide;
    subdivide->SetInputConnection(triangles->GetOutputPort());
    subdivide->SetNumberOfSubdivisions(3);
    subdivide->Update();
    vtkPolyData* large = subdivide->GetOutput();
    const Result big = Run(large, plan.warps[0], std::max(10, frames / 8), width, height);
    Report("demo vessel x64 (~1M tris)", large, big);
    const double share = 100.0 * demo.warpMs / (demo.warpMs + demo.renderMs);
    std::printf(
      "target on the demo vessel: >= 30 fps and warp <= 20%% of a frame: %s (%.1f fps, %.1f%%)\n",
      (demo.fps >= 30.0 && share <= 20.0) ? "met" : "NOT met",
      demo.fps,
      share);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_interactive: %s\n", e.what());
    return 1;
  }
  return 0;
}
