// bench_subdivision: one adaptive subdivision pass (spec 7) after a ribbon warp on a surface of
// about 1 M triangles, against VTK's one-level linear subdivision of the same mesh measured in
// the same run (the reference: a uniform 1 -> 4 split with no warp evaluation at all).
//
// usage: bench_subdivision [TRIANGLES] [REPEATS]   (defaults 1000000 and 5; prints medians
// with min and max, the ratio of medians)

#include "WarpPlan.h"
#include "vtkBenderAdaptiveSubdivisionFilter.h"
#include "vtkBenderWarpFilter.h"

#include "BenchMachine.h"

#include <vtkLinearSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

namespace
{
using bender_bench::Spread;

Spread TimeMs(int repeats, const std::function<void()>& run)
{
  return bender_bench::Summarise(bender_bench::TimeRunsMs(repeats, run));
}
} // namespace

int main(int argc, char* argv[])
{
  const long target = argc > 1 ? std::atol(argv[1]) : 1000000;
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  if (target < 2)
  {
    std::fprintf(stderr, "usage: bench_subdivision [TRIANGLES >= 2] [REPEATS]\n");
    return 2;
  }
  // A unit square grid in z = 0 of n x n quads (2 n^2 triangles).
  const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(target / 2.0))));
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.5, -0.5, 0);
  plane->SetPoint1(0.5, -0.5, 0);
  plane->SetPoint2(-0.5, 0.5, 0);
  plane->SetResolution(n, n);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  vtkPolyData* mesh = triangles->GetOutput();

  // The paper's Fig. 13 "fin": a wire along x lifted out of the plane, bell decay.
  bender::WarpSpec warp;
  warp.initial.start = { { -0.3, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  warp.initial.end = { { 0.3, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  warp.final.start = { { -0.3, 0, 0.25 }, { 1, 0, 0 }, { 0, 0, 1 } };
  warp.final.end = { { 0.3, 0, 0.25 }, { 1, 0, 0 }, { 0, 0, 1 } };
  warp.radius = 0.2;
  warp.decay.shape = bender::DecayShape::Bell;
  const double tolerance = 2e-6;

  std::printf("bench_subdivision: %s\n", bender_bench::MachineLine().c_str());
  std::printf("%lld triangles, %lld points (grid %d x %d), ms: median [min, max] of %d runs\n",
    static_cast<long long>(mesh->GetNumberOfPolys()),
    static_cast<long long>(mesh->GetNumberOfPoints()),
    n,
    n,
    repeats);

  vtkIdType warpedCount = 0;
  const Spread warpMs = TimeMs(repeats,
    [&]
    {
      vtkNew<vtkBenderWarpFilter> filter;
      filter->SetInputData(mesh);
      filter->SetWarp(warp);
      filter->Update();
      warpedCount = filter->GetOutput()->GetNumberOfPolys();
    });
  vtkIdType onePassCount = 0, splits = 0;
  const Spread onePassMs = TimeMs(repeats,
    [&]
    {
      vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivide;
      subdivide->SetInputData(mesh);
      subdivide->SetWarp(warp);
      subdivide->SetTolerance(tolerance);
      subdivide->SetMaxPasses(1);
      subdivide->Update();
      onePassCount = subdivide->GetOutput()->GetNumberOfPolys();
      splits = subdivide->GetSplitsPerPass().empty() ? 0 : subdivide->GetSplitsPerPass()[0];
    });
  vtkIdType linearCount = 0;
  const Spread linearMs = TimeMs(repeats,
    [&]
    {
      vtkNew<vtkLinearSubdivisionFilter> linear;
      linear->SetInputData(mesh);
      linear->SetNumberOfSubdivisions(1);
      linear->Update();
      linearCount = linear->GetOutput()->GetNumberOfPolys();
    });

  std::printf("  %-58s %24s  %9lld triangles\n",
    "warp (vtkBenderWarpFilter, exact)",
    bender_bench::Format(warpMs).c_str(),
    static_cast<long long>(warpedCount));
  std::printf("  %-58s %24s  %9lld triangles (%lld edges split, tolerance %g)\n",
    "warp + 1 adaptive pass (Bender subdivision)",
    bender_bench::Format(onePassMs).c_str(),
    static_cast<long long>(onePassCount),
    static_cast<long long>(splits),
    tolerance);
  std::printf("  %-58s %24s  %9lld triangles\n",
    "reference (same run): vtkLinearSubdivisionFilter, 1 level",
    bender_bench::Format(linearMs).c_str(),
    static_cast<long long>(linearCount));
  std::printf("  ratio adaptive pass / reference: %.2f; adaptive pass alone (minus warp): %.1f ms "
              "(medians)\n",
    onePassMs.median / linearMs.median,
    onePassMs.median - warpMs.median);
  return 0;
}
