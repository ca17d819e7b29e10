// bench_centerlines: centerlines (Voronoi diagram, minimal paths, smoothing, branches) of the
// gmsh aneurysm (about 20 k triangles, 3 open ends) and of the demo segmentation (about 55 k
// triangles, closed), with the time of each stage. Prints the machine, every run and the
// median, min and max of each stage, then the Delaunay stage against a reference measured in the
// same run: the surface's points tetrahedralised by the centerlines' own Delaunay and by Qhull.
// Target: at most 1 s for the 55 k-triangle surface on a 2-core machine. Figures taken
// on a loaded machine are not final: say so when quoting them.
//
// With --invariance it also prints how far the centerline moves under a rigid motion, a finer
// (linear subdivision, 4 x the triangles) and a coarser (quadric decimation to half) remeshing of
// each surface, and between the gmsh aneurysm and its segmentation-path phantom (the demo
// segmentation). The measure: for every point of the new centerlines (the paths from the inlet
// to each outlet) farther than 2 x the largest end radius from every endpoint and every
// bifurcation point, the distance to the reference centerlines (polylines, point to segment),
// over the point's inscribed radius; the largest of these ratios (target: 2 %) and the
// largest distance in mm (0.3 mm between the aneurysm and its phantom), with where the worst
// point is (position, abscissa on its path, radius).
//
// usage: bench_centerlines [--invariance] [REPEATS] [SURFACE ...]   (default 5 repeats, the
// two surfaces)

#include "DelaunayTetrahedra.h"
#include "DemoPipeline.h"
#include "MeshIO.h"
#include "VesselArrayNames.h"
#include "VesselCenterlines.h"

#include "BenchMachine.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkLinearSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkQuadricDecimation.h>
#include <vtkSmartPointer.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using bender::Point3;

void Run(const std::string& name, vtkPolyData* surface, int repeats)
{
  std::printf("\n%s: %lld points, %lld triangles\n",
    name.c_str(),
    static_cast<long long>(surface->GetNumberOfPoints()),
    static_cast<long long>(surface->GetNumberOfPolys()));
  std::vector<std::vector<double>> stages(8);
  for (int r = 0; r < repeats; ++r)
  {
    const auto t0 = std::chrono::steady_clock::now();
    const bender::CenterlineResult result = bender::ComputeCenterlines(surface);
    const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto& t = result.times;
    const double values[8] = {
      t.preparation, t.delaunay, t.voronoi, t.endpoints, t.paths, t.smoothing, t.branches, total
    };
    for (int k = 0; k < 8; ++k)
    {
      stages[k].push_back(values[k]);
    }
    std::printf("  run %d: %s, %zu endpoints, %lld branches, %d Delaunay points, %d Voronoi "
                "vertices; prep %.3f delaunay %.3f voronoi %.3f endpoints %.3f paths %.3f "
                "smoothing %.3f branches %.3f total %.3f s\n",
      r + 1,
      result.ok ? "ok" : result.message.c_str(),
      result.endpoints.size(),
      static_cast<long long>(result.branches->GetNumberOfCells()),
      result.numberOfDelaunayPoints,
      result.numberOfVoronoiVertices,
      values[0],
      values[1],
      values[2],
      values[3],
      values[4],
      values[5],
      values[6],
      values[7]);
  }
  const char* names[8] = {
    "prep", "delaunay", "voronoi", "endpoints", "paths", "smoothing", "branches", "total"
  };
  std::printf("  s, median [min, max]:");
  for (int k = 0; k < 8; ++k)
  {
    const std::string spread = bender_bench::Format(bender_bench::Summarise(stages[k]), 3);
    std::printf(" %s %s", names[k], spread.c_str());
  }
  std::printf("\n");
}

// The Delaunay stage against a reference in the same run: the surface's points (jittered by
// 1e-7 of the diagonal, the order of the centerlines' own jitter of 1e-4 mean edge) tetrahedralised
// by the centerlines' incremental Delaunay and by Qhull (the library doing the same job).
void DelaunayReference(vtkPolyData* surface, int repeats)
{
  std::vector<std::array<double, 3>> points(static_cast<std::size_t>(surface->GetNumberOfPoints()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    surface->GetPoint(static_cast<vtkIdType>(i), points[i].data());
  }
  const double diagonal = surface->GetLength();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-1e-7 * diagonal, 1e-7 * diagonal);
  for (auto& p : points)
  {
    for (double& c : p)
    {
      c += jitter(random);
    }
  }
  std::vector<std::array<vtkIdType, 4>> ours, qhull;
  std::string error;
  std::vector<double> oursMs, qhullMs;
  for (int r = 0; r < repeats; ++r)
  {
    // Interleaved, so that a change of the machine's speed shows in both columns.
    oursMs.push_back(bender_bench::TimeRunsMs(1,
      [&]
      {
        auto copy = points;
        if (!bender::DelaunayTetrahedra(copy, ours, error))
        {
          throw std::runtime_error("Delaunay: " + error);
        }
      })[0]);
    qhullMs.push_back(bender_bench::TimeRunsMs(1,
      [&]
      {
        if (!bender::QhullTetrahedra(points, qhull, error))
        {
          throw std::runtime_error("Qhull: " + error);
        }
      })[0]);
  }
  // The result compared: the tetrahedra both give, as sets of four point ids.
  const auto canonical = [](std::vector<std::array<vtkIdType, 4>> tets)
  {
    for (auto& t : tets)
    {
      std::sort(t.begin(), t.end());
    }
    std::sort(tets.begin(), tets.end());
    return tets;
  };
  const auto a4 = canonical(ours), b4 = canonical(qhull);
  std::vector<std::array<vtkIdType, 4>> common;
  std::set_intersection(a4.begin(), a4.end(), b4.begin(), b4.end(), std::back_inserter(common));
  const auto a = bender_bench::Summarise(oursMs), b = bender_bench::Summarise(qhullMs);
  std::printf("  Delaunay of the %zu surface points, ms: incremental %s (%zu tetrahedra), Qhull %s "
              "(%zu), %zu tetrahedra in both (%.2f %%): Qhull / incremental %.1fx\n",
    points.size(),
    bender_bench::Format(a).c_str(),
    ours.size(),
    bender_bench::Format(b).c_str(),
    qhull.size(),
    common.size(),
    100.0 * double(common.size()) / double(std::max(a4.size(), b4.size())),
    b.median / a.median);
}

double SegmentDistance(const Point3& p, const Point3& a, const Point3& b)
{
  double ab[3], ap[3], l2 = 0, t = 0;
  for (int c = 0; c < 3; ++c)
  {
    ab[c] = b[c] - a[c];
    ap[c] = p[c] - a[c];
    l2 += ab[c] * ab[c];
    t += ab[c] * ap[c];
  }
  t = l2 > 0 ? std::clamp(t / l2, 0.0, 1.0) : 0.0;
  double d2 = 0;
  for (int c = 0; c < 3; ++c)
  {
    const double x = ap[c] - t * ab[c];
    d2 += x * x;
  }
  return std::sqrt(d2);
}

std::vector<std::vector<Point3>> Polylines(vtkPolyData* lines)
{
  std::vector<std::vector<Point3>> out;
  vtkCellArray* cells = lines->GetLines();
  cells->InitTraversal();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  while (cells->GetNextCell(n, ids))
  {
    std::vector<Point3> line(static_cast<std::size_t>(n));
    for (vtkIdType k = 0; k < n; ++k)
    {
      lines->GetPoint(ids[k], line[k].data());
    }
    out.push_back(line);
  }
  return out;
}

struct Deviation
{
  double millimetres = 0;
  double ofRadius = 0; // largest distance / local inscribed radius
  int points = 0;
  Point3 worst{ { 0, 0, 0 } }; // where the largest distance / radius is
  double worstAbscissa = 0;    // its abscissa on its path (mm)
  double worstRadius = 0;      // its inscribed radius (mm)
};

// Distances from the points of a's paths to b's paths, skipping points within `skip` x the
// largest end radius of the ends and bifurcations of a.
Deviation Compare(const bender::CenterlineResult& a, vtkPolyData* bPaths, double skip)
{
  Deviation d;
  double largest = 0;
  std::vector<Point3> excluded(a.bifurcations);
  for (const auto& e : a.endpoints)
  {
    largest = std::max(largest, e.radius);
    excluded.push_back(e.position);
  }
  const auto lines = Polylines(bPaths);
  vtkDataArray* radius =
    a.paths->GetPointData()->GetArray(bender::VesselArrays::MaximumInscribedSphereRadius);
  vtkDataArray* abscissa = a.paths->GetPointData()->GetArray(bender::VesselArrays::Abscissa);
  for (vtkIdType i = 0; i < a.paths->GetNumberOfPoints(); ++i)
  {
    Point3 p;
    a.paths->GetPoint(i, p.data());
    bool skipped = false;
    for (const auto& x : excluded)
    {
      skipped = skipped || std::hypot(p[0] - x[0], p[1] - x[1], p[2] - x[2]) < skip * largest;
    }
    if (skipped)
    {
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    for (const auto& line : lines)
    {
      for (std::size_t k = 0; k + 1 < line.size(); ++k)
      {
        best = std::min(best, SegmentDistance(p, line[k], line[k + 1]));
      }
    }
    d.millimetres = std::max(d.millimetres, best);
    if (best / radius->GetTuple1(i) > d.ofRadius)
    {
      d.ofRadius = best / radius->GetTuple1(i);
      d.worst = p;
      d.worstRadius = radius->GetTuple1(i);
      d.worstAbscissa = abscissa->GetTuple1(i);
    }
    ++d.points;
  }
  return d;
}

void Print(const char* what, const Deviation& d)
{
  std::printf("  %-34s %6.2f %% of the radius, %.3f mm (%d points); worst at (%.2f, %.2f, %.2f), "
              "abscissa %.2f mm, radius %.2f mm\n",
    what,
    100.0 * d.ofRadius,
    d.millimetres,
    d.points,
    d.worst[0],
    d.worst[1],
    d.worst[2],
    d.worstAbscissa,
    d.worstRadius);
}

void Invariance(const std::string& name, vtkPolyData* surface)
{
  std::printf(
    "\n%s: invariance, away from the ends and bifurcations (2 end radii)\n", name.c_str());
  const bender::CenterlineResult base = bender::ComputeCenterlines(surface);
  if (!base.ok)
  {
    std::printf("  failed: %s\n", base.message.c_str());
    return;
  }
  vtkNew<vtkTransform> motion;
  motion->Translate(12.0, -7.0, 30.0);
  motion->RotateWXYZ(37.0, 0.3, -0.8, 0.5);
  vtkNew<vtkTransformPolyDataFilter> moveSurface;
  moveSurface->SetInputData(surface);
  moveSurface->SetTransform(motion);
  moveSurface->Update();
  vtkNew<vtkTransformPolyDataFilter> moveLines;
  moveLines->SetInputData(base.paths);
  moveLines->SetTransform(motion);
  moveLines->Update();
  const bender::CenterlineResult moved = bender::ComputeCenterlines(moveSurface->GetOutput());
  if (moved.ok)
  {
    Print("rigid motion", Compare(moved, moveLines->GetOutput(), 2.0));
  }
  vtkNew<vtkLinearSubdivisionFilter> finer;
  finer->SetInputData(surface);
  finer->SetNumberOfSubdivisions(1);
  finer->Update();
  const bender::CenterlineResult fine = bender::ComputeCenterlines(finer->GetOutput());
  if (fine.ok)
  {
    Print("finer (linear subdivision x4)", Compare(fine, base.paths, 2.0));
  }
  vtkNew<vtkQuadricDecimation> coarser;
  coarser->SetInputData(surface);
  coarser->SetTargetReduction(0.5);
  coarser->Update();
  const bender::CenterlineResult coarse = bender::ComputeCenterlines(coarser->GetOutput());
  if (coarse.ok)
  {
    Print("coarser (quadric decimation / 2)", Compare(coarse, base.paths, 2.0));
  }
}
} // namespace

int main(int argc, char* argv[])
{
  int first = 1;
  bool invariance = false;
  if (argc > 1 && std::strcmp(argv[1], "--invariance") == 0)
  {
    invariance = true;
    ++first;
  }
  const int repeats = argc > first ? std::max(1, std::atoi(argv[first])) : 5;
  std::printf(
    "bench_centerlines: %s; medians of %d runs\n", bender_bench::MachineLine().c_str(), repeats);
  try
  {
    if (argc > first + 1)
    {
      for (int i = first + 1; i < argc; ++i)
      {
        auto surface = bender::ReadMesh(argv[i]);
        Run(argv[i], surface, repeats);
        DelaunayReference(surface, repeats);
        if (invariance)
        {
          Invariance(argv[i], surface);
        }
      }
      return 0;
    }
    const std::string aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
    auto source = bender::ReadMesh(aneurysm);
    Run("gmsh aneurysm (open)", source, repeats);
    DelaunayReference(source, repeats);
    const bender::DemoVessel demo = bender::SegmentDemoVessel(bender::DemoVesselPath());
    Run("demo segmentation (closed)", demo.surface, repeats);
    DelaunayReference(demo.surface, repeats);
    if (invariance)
    {
      Invariance("gmsh aneurysm (open)", source);
      Invariance("demo segmentation (closed)", demo.surface);
      const bender::CenterlineResult a = bender::ComputeCenterlines(demo.surface);
      const bender::CenterlineResult b = bender::ComputeCenterlines(source);
      if (a.ok && b.ok)
      {
        std::printf("\nphantom (demo segmentation) vs gmsh aneurysm\n");
        Print("segmented to source", Compare(a, b.paths, 2.0));
      }
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_centerlines: %s\n", e.what());
    return 1;
  }
  return 0;
}
