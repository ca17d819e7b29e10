// Benchmark of vtkBenderWarpFilter: binding (per grab) and evaluation (per move of the final
// ribbon) on a 1,000,000-vertex mesh with every vertex inside R and with about 10% inside R,
// against vtkWarpVector on the same mesh as the memory-bound reference, and the evaluation
// rate on the paper's ~70,000-triangle bunny (glmark2-data).
//
// Usage: bench_warp [--vertices N] [--repeats K]

#include "vtkBenderWarpFilter.h"

#include "BenchMachine.h"
#include "FastWarpKernel.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkWarpVector.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double Ms(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

using bender_bench::Spread;
using bender_bench::Summarise;

// A tube of radius 5 along x, from x0 to x1, with `rings` x `sides` vertices (triangulated).
vtkSmartPointer<vtkPolyData> MakeTube(double x0, double x1, int rings, int sides)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToFloat();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(rings) * sides);
  vtkIdType id = 0;
  for (int i = 0; i < rings; ++i)
  {
    const double x = x0 + (x1 - x0) * i / (rings - 1);
    for (int k = 0; k < sides; ++k)
    {
      const double a = 2.0 * 3.14159265358979 * k / sides;
      pts->SetPoint(id++, x, 5.0 * std::cos(a), 5.0 * std::sin(a));
    }
  }
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(2 * static_cast<vtkIdType>(rings - 1) * sides, 6 * (rings - 1) * sides);
  for (int i = 0; i + 1 < rings; ++i)
  {
    for (int k = 0; k < sides; ++k)
    {
      const vtkIdType a = static_cast<vtkIdType>(i) * sides + k;
      const vtkIdType b = static_cast<vtkIdType>(i) * sides + (k + 1) % sides;
      const vtkIdType t0[3] = { a, a + sides, b + sides };
      const vtkIdType t1[3] = { a, b + sides, b };
      polys->InsertNextCell(3, t0);
      polys->InsertNextCell(3, t1);
    }
  }
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  return pd;
}

// A ribbon along x from (x0,0,0) to (x0+L,0,0) bent in the xy plane by `angle` at its end.
bender::WarpSpec Bend(double x0, double length, double angle, double radius)
{
  bender::WarpSpec w;
  w.initial.start = { { x0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.initial.end = { { x0 + length, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.final = w.initial;
  w.final.end.position = { x0 + length * (1.0 - 0.25 * angle), length * 0.5 * angle, 0.0 };
  w.final.end.tangent = { std::cos(angle), std::sin(angle), 0.0 };
  w.radius = radius;
  w.decay = { bender::DecayShape::Bell, 0.5 };
  return w;
}

struct Figures
{
  // Medians over the runs (the table's figures) with their min and max.
  Spread bind;
  Spread evalExact;
  Spread evalTable;
  vtkIdType bound = 0;
};

Figures MeasureWarp(vtkPolyData* mesh, bender::WarpSpec spec, int repeats)
{
  Figures f;
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(mesh);
  filter->SetWarp(spec);
  filter->SetPrecision(bender::WarpPrecision::Table);
  // Binding: the first update after a grab (includes one evaluation, subtracted below).
  std::vector<double> bindTimes;
  for (int r = 0; r < std::max(3, repeats / 3); ++r)
  {
    spec.radius *= (r % 2 ? 1.0 / 1.000001 : 1.000001); // a new R forces a new binding
    filter->SetWarp(spec);
    const auto t0 = Clock::now();
    filter->Update();
    bindTimes.push_back(Ms(t0, Clock::now()));
  }
  f.bound = filter->GetNumberOfBoundPoints();
  for (auto precision : { bender::WarpPrecision::Table, bender::WarpPrecision::Exact })
  {
    filter->SetPrecision(precision);
    filter->Update();
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r)
    {
      // Move the final ribbon as a drag would.
      bender::RibbonSpec fin = spec.final;
      fin.end.position.z += 0.01 * (r % 7);
      filter->SetFinalRibbon(fin);
      const auto t0 = Clock::now();
      filter->Update();
      times.push_back(Ms(t0, Clock::now()));
    }
    (precision == bender::WarpPrecision::Table ? f.evalTable : f.evalExact) = Summarise(times);
  }
  for (double& t : bindTimes)
  {
    t = std::max(0.0, t - f.evalTable.median);
  }
  f.bind = Summarise(bindTimes);
  return f;
}

Spread MeasureWarpVector(vtkPolyData* mesh, int repeats)
{
  vtkNew<vtkPolyData> withVectors;
  withVectors->ShallowCopy(mesh);
  vtkNew<vtkDoubleArray> v;
  v->SetName("displacement");
  v->SetNumberOfComponents(3);
  v->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    v->SetTuple3(i, 0.1, 0.2, 0.3);
  }
  withVectors->GetPointData()->SetVectors(v);
  vtkNew<vtkWarpVector> warp;
  warp->SetInputData(withVectors);
  warp->SetScaleFactor(1.0);
  warp->Update();
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r)
  {
    // A new factor every run (the warm-up used 1.0), so that every sample executes the filter.
    warp->SetScaleFactor(1.0 + 0.01 * ((r + 1) % 2));
    const auto t0 = Clock::now();
    warp->Update();
    times.push_back(Ms(t0, Clock::now()));
  }
  return Summarise(times);
}

/// The spread of one row: "case: bind ms med [min, max], ..." printed below the table.
std::string SpreadLine(const std::string& name, const Figures& f, const Spread& wv, int decimals)
{
  using bender_bench::Format;
  return name + ": bind " + Format(f.bind, decimals) + ", eval " + Format(f.evalTable, decimals) +
    ", exact " + Format(f.evalExact, decimals) + ", warpvec " + Format(wv, decimals);
}
} // namespace

int main(int argc, char** argv)
{
  int vertices = 1000000;
  int repeats = 15;
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--vertices"))
    {
      vertices = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--repeats"))
    {
      repeats = std::max(1, std::atoi(argv[++i]));
    }
  }
  std::printf("bench_warp: %s; vtkSMPTools backend %s (%d threads)\n",
    bender_bench::MachineLine().c_str(),
    vtkSMPTools::GetBackend(),
    vtkSMPTools::GetEstimatedNumberOfThreads());
  std::printf("warp kernels: %s (table and exact precision, chosen at run time)\n",
    bender::FastWarpKernel::LevelName(bender::FastWarpKernel::BestLevel()));
  std::vector<std::string> spreads;

  const int sides = 1000;
  const int rings = std::max(2, vertices / sides);
  std::printf("\n%-34s %9s %10s %10s %10s %10s %8s %8s\n",
    "case",
    "bound",
    "bind ms",
    "eval ms",
    "exact ms",
    "warpvec ms",
    "eval/wv",
    "exact/wv");
  // All inside: a tube of radius 5 along the whole 40 mm wire, R = 12.
  {
    auto mesh = MakeTube(0.0, 40.0, rings, sides);
    const Figures f = MeasureWarp(mesh, Bend(0.0, 40.0, 1.2, 12.0), repeats);
    const Spread wv = MeasureWarpVector(mesh, repeats);
    std::printf("%-34s %9lld %10.1f %10.1f %10.1f %10.1f %8.2f %8.2f\n",
      ("1M vertices, all inside R"),
      static_cast<long long>(f.bound),
      f.bind.median,
      f.evalTable.median,
      f.evalExact.median,
      wv.median,
      f.evalTable.median / wv.median,
      f.evalExact.median / wv.median);
    spreads.push_back(SpreadLine("1M vertices, all inside R", f, wv, 1));
  }
  // About 10% inside: the same wire on a tube ten times longer.
  {
    auto mesh = MakeTube(-180.0, 220.0, rings, sides);
    const Figures f = MeasureWarp(mesh, Bend(0.0, 40.0, 1.2, 12.0), repeats);
    const Spread wv = MeasureWarpVector(mesh, repeats);
    std::printf("%-34s %9lld %10.1f %10.1f %10.1f %10.1f %8.2f %8.2f\n",
      "1M vertices, ~10% inside R",
      static_cast<long long>(f.bound),
      f.bind.median,
      f.evalTable.median,
      f.evalExact.median,
      wv.median,
      f.evalTable.median / wv.median,
      f.evalExact.median / wv.median);
    spreads.push_back(SpreadLine("1M vertices, ~10% inside R", f, wv, 1));
  }
  // The paper's speed case: the bunny (69,666 triangles), a ribbon through the ear region.
  {
    const std::string path = std::string(BENDER_EXTERNAL_DATA_DIR) + "/bunny.obj";
    vtkNew<vtkOBJReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkPolyData* bunny = reader->GetOutput();
    if (bunny->GetNumberOfPoints() == 0)
    {
      std::printf("bunny: %s not found (run scripts/fetch-data)\n", path.c_str());
      return 1;
    }
    double b[6];
    bunny->GetBounds(b);
    const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
    bender::WarpSpec spec;
    const bender::Vec3 c{ 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    spec.initial.start = { { c.x, b[2], c.z }, { 0, 1, 0 }, { 0, 0, 1 } };
    spec.initial.end = { { c.x, b[3], c.z }, { 0, 1, 0 }, { 0, 0, 1 } };
    spec.final = spec.initial;
    spec.final.end.position = { c.x + 0.3 * size, b[3] - 0.1 * size, c.z };
    spec.final.end.tangent = { 0.6, 0.8, 0.0 };
    spec.radius = 0.3 * size;
    const Figures f = MeasureWarp(bunny, spec, repeats);
    const Spread wv = MeasureWarpVector(bunny, repeats);
    std::printf("%-34s %9lld %10.2f %10.2f %10.2f %10.2f %8.2f %8.2f\n",
      ("bunny (" + std::to_string(bunny->GetNumberOfPolys()) + " triangles)").c_str(),
      static_cast<long long>(f.bound),
      f.bind.median,
      f.evalTable.median,
      f.evalExact.median,
      wv.median,
      f.evalTable.median / wv.median,
      f.evalExact.median / wv.median);
    spreads.push_back(SpreadLine("bunny", f, wv, 2));
    std::printf("\nbunny evaluation rate: %.0f warps/s (table), %.0f warps/s (exact); the paper "
                "reported 10 frames/s including rendering\n",
      1000.0 / f.evalTable.median,
      1000.0 / f.evalExact.median);
  }
  std::printf("\nbind ms: per grab (projection of every vertex); eval ms: per move, table "
              "precision; exact ms: per move, exact precision; warpvec ms: vtkWarpVector on the "
              "same mesh (memory-bound reference, same run); medians of %d runs (bind: %d runs)\n",
    repeats,
    std::max(3, repeats / 3));
  std::printf("\nspread, ms, median [min, max]:\n");
  for (const std::string& line : spreads)
  {
    std::printf("  %s\n", line.c_str());
  }
  return 0;
}
