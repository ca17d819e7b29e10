// bench_mesh_check: the mesh check's self-intersection search (its own uniform grid of triangle
// bounding boxes, modules/Filters/MeshSelfIntersections.cxx) against the same search written with
// VTK's vtkStaticCellLocator, in the same run, on the same meshes:
// - the demo vessel (the segmented demo volume, about 55 k triangles, no self-intersection);
// - the demo vessel with a copy of itself moved by 1 mm (about 110 k triangles, thousands of
//   crossing pairs), so that both searches have pairs to find;
// - with --large, the 1 M-triangle sphere of the mesh check's tests.
// The grid's time is the mesh check with the search minus the mesh check without it (medians).
// The locator's: build the locator, then (vtkSMPTools, in parallel as the grid) one
// FindCellsWithinBounds per triangle, the same box-overlap and shared-vertex rules, and VTK's
// triangle-triangle test (non-coplanar crossings, as in MeshCheck.SelfIntersectionPairs-
// MatchAnAllPairsSearch). Prints both wall and processor times, the ratios, and whether both
// found the same pairs.
//
// usage: bench_mesh_check [--large] [REPEATS]   (default 5 repeats)

#include "BenderMeshCheck.h"
#include "DemoPipeline.h"
#include "MeshTopology.h"

#include "BenchMachine.h"

#include <vtkAppendPolyData.h>
#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkIntersectionPolyDataFilter.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkStaticCellLocator.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace
{

using Pairs = std::vector<std::pair<vtkIdType, vtkIdType>>;

/// The triangles of `mesh` as a polydata whose cell i is triangle i of CollectTriangles, so that
/// the locator's cell ids are the mesh check's triangle ids.
vtkSmartPointer<vtkPolyData> TrianglesOnly(vtkPolyData* mesh, const std::vector<std::int64_t>& tris)
{
  vtkNew<vtkCellArray> cells;
  for (std::size_t t = 0; t + 2 < tris.size(); t += 3)
  {
    const vtkIdType ids[3] = { tris[t], tris[t + 1], tris[t + 2] };
    cells->InsertNextCell(3, ids);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(mesh->GetPoints());
  out->SetPolys(cells);
  return out;
}

/// The self-intersecting pairs (i < j, sorted) found through vtkStaticCellLocator.
Pairs LocatorPairs(vtkPolyData* triangles, double& buildMs, double& searchMs)
{
  vtkNew<vtkStaticCellLocator> locator;
  buildMs = bender_bench::TimeRunsMs(1,
    [&]
    {
      locator->SetDataSet(triangles);
      locator->BuildLocator();
    })[0];
  const vtkIdType n = triangles->GetNumberOfCells();
  std::vector<std::array<double, 6>> boxes(static_cast<std::size_t>(n));
  std::vector<std::array<vtkIdType, 3>> corners(static_cast<std::size_t>(n));
  vtkSMPThreadLocal<Pairs> found;
  searchMs = bender_bench::TimeRunsMs(1,
    [&]
    {
      vtkCellArray* polys = triangles->GetPolys();
      vtkIdType npts = 0;
      const vtkIdType* ids = nullptr;
      vtkIdType t = 0;
      for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++t)
      {
        auto& b = boxes[static_cast<std::size_t>(t)];
        b = { std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity() };
        for (int k = 0; k < 3; ++k)
        {
          corners[static_cast<std::size_t>(t)][k] = ids[k];
          double p[3];
          triangles->GetPoint(ids[k], p);
          for (int a = 0; a < 3; ++a)
          {
            b[2 * a] = std::min(b[2 * a], p[a]);
            b[2 * a + 1] = std::max(b[2 * a + 1], p[a]);
          }
        }
      }
      vtkSMPThreadLocal<vtkSmartPointer<vtkIdList>> lists;
      vtkSMPTools::For(0,
        n,
        [&](vtkIdType begin, vtkIdType end)
        {
          vtkSmartPointer<vtkIdList>& list = lists.Local();
          if (!list)
          {
            list = vtkSmartPointer<vtkIdList>::New();
          }
          Pairs& local = found.Local();
          for (vtkIdType i = begin; i < end; ++i)
          {
            auto& bi = boxes[static_cast<std::size_t>(i)];
            locator->FindCellsWithinBounds(bi.data(), list);
            const auto& vi = corners[static_cast<std::size_t>(i)];
            for (vtkIdType k = 0; k < list->GetNumberOfIds(); ++k)
            {
              const vtkIdType j = list->GetId(k);
              if (j <= i)
              {
                continue;
              }
              const auto& bj = boxes[static_cast<std::size_t>(j)];
              bool overlap = true;
              for (int a = 0; a < 3; ++a)
              {
                overlap = overlap && bi[2 * a] <= bj[2 * a + 1] && bj[2 * a] <= bi[2 * a + 1];
              }
              const auto& vj = corners[static_cast<std::size_t>(j)];
              bool shared = false;
              for (int a = 0; a < 3; ++a)
              {
                shared = shared || vi[a] == vj[0] || vi[a] == vj[1] || vi[a] == vj[2];
              }
              if (!overlap || shared)
              {
                continue;
              }
              double p[6][3];
              for (int c = 0; c < 3; ++c)
              {
                triangles->GetPoint(vi[c], p[c]);
                triangles->GetPoint(vj[c], p[3 + c]);
              }
              int coplanar = 0;
              double x0[3], x1[3];
              double surface[2] = { 0, 0 };
              if (vtkIntersectionPolyDataFilter::TriangleTriangleIntersection(
                    p[0], p[1], p[2], p[3], p[4], p[5], coplanar, x0, x1, surface, 1e-12) &&
                !coplanar)
              {
                local.emplace_back(i, j);
              }
            }
          }
        });
    })[0];
  Pairs all;
  for (auto it = found.begin(); it != found.end(); ++it)
  {
    all.insert(all.end(), it->begin(), it->end());
  }
  std::sort(all.begin(), all.end());
  return all;
}

void Compare(const char* name, vtkPolyData* mesh, int repeats)
{
  const std::vector<std::int64_t> tris = bender::CollectTriangles(mesh);
  std::printf("\n%s: %lld points, %zu triangles\n",
    name,
    static_cast<long long>(mesh->GetNumberOfPoints()),
    tris.size() / 3);
  bender::MeshCheckOptions with;
  with.maxExamples = std::numeric_limits<std::size_t>::max();
  bender::MeshCheckOptions without = with;
  without.selfIntersections = false;
  bender::MeshCheckReport report;
  std::vector<double> gridMs, buildMs, searchMs, locatorMs, gridCpuMs, locatorCpuMs;
  // Processor time of the whole process (all threads), ms: steadier than wall time on a
  // machine shared with other work.
  const auto cpuMs = [] { return 1000.0 * double(std::clock()) / CLOCKS_PER_SEC; };
  Pairs viaLocator;
  vtkSmartPointer<vtkPolyData> triangles = TrianglesOnly(mesh, tris);
  for (int r = 0; r < repeats; ++r)
  {
    // Interleaved, so that a change of the machine's speed shows in both columns.
    const double c0 = cpuMs();
    const double on =
      bender_bench::TimeRunsMs(1, [&] { report = bender::CheckMesh(mesh, nullptr, with); })[0];
    const double c1 = cpuMs();
    const double off =
      bender_bench::TimeRunsMs(1, [&] { bender::CheckMesh(mesh, nullptr, without); })[0];
    const double c2 = cpuMs();
    gridMs.push_back(on - off);
    gridCpuMs.push_back((c1 - c0) - (c2 - c1));
    double build = 0, search = 0;
    viaLocator = LocatorPairs(triangles, build, search);
    locatorCpuMs.push_back(cpuMs() - c2);
    buildMs.push_back(build);
    searchMs.push_back(search);
    locatorMs.push_back(build + search);
    std::printf("  run %d: grid %.1f ms (check %.1f - %.1f without the search), cpu %.1f ms; "
                "locator build %.1f + search %.1f ms, cpu %.1f ms\n",
      r + 1,
      on - off,
      on,
      off,
      gridCpuMs.back(),
      build,
      search,
      locatorCpuMs.back());
  }
  const bender_bench::Spread grid = bender_bench::Summarise(gridMs);
  const bender_bench::Spread locator = bender_bench::Summarise(locatorMs);
  const bool same = viaLocator == report.intersectingPairs &&
    static_cast<std::size_t>(report.selfIntersections) == viaLocator.size();
  const bender_bench::Spread gridCpu = bender_bench::Summarise(gridCpuMs);
  const bender_bench::Spread locatorCpu = bender_bench::Summarise(locatorCpuMs);
  std::printf("  ms, median [min, max] of %d: grid %s (cpu %s), %lld pairs; vtkStaticCellLocator "
              "%s (cpu %s; build %s, search %s), %zu pairs; locator / grid %.2fx (cpu %.2fx); "
              "same pairs: %s\n",
    repeats,
    bender_bench::Format(grid).c_str(),
    bender_bench::Format(gridCpu).c_str(),
    static_cast<long long>(report.selfIntersections),
    bender_bench::Format(locator).c_str(),
    bender_bench::Format(locatorCpu).c_str(),
    bender_bench::Format(bender_bench::Summarise(buildMs)).c_str(),
    bender_bench::Format(bender_bench::Summarise(searchMs)).c_str(),
    viaLocator.size(),
    locator.median / grid.median,
    locatorCpu.median / gridCpu.median,
    same ? "yes" : "NO");
}

vtkSmartPointer<vtkPolyData> WithMovedCopy(vtkPolyData* mesh, double dx)
{
  vtkNew<vtkTransform> move;
  move->Translate(dx, 0.0, 0.0);
  vtkNew<vtkTransformPolyDataFilter> moved;
  moved->SetInputData(mesh);
  moved->SetTransform(move);
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(mesh);
  append->AddInputConnection(moved->GetOutputPort());
  append->Update();
  return append->GetOutput();
}

} // namespace

int main(int argc, char* argv[])
{
  bool large = false;
  int repeats = 5;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--large") == 0)
    {
      large = true;
    }
    else
    {
      repeats = std::max(1, std::atoi(argv[i]));
    }
  }
  std::printf("bench_mesh_check: %s; %d threads (vtkSMPTools %s)\n",
    bender_bench::MachineLine().c_str(),
    vtkSMPTools::GetEstimatedNumberOfThreads(),
    vtkSMPTools::GetBackend());
  try
  {
    const bender::DemoVessel demo = bender::SegmentDemoVessel(bender::DemoVesselPath());
    Compare("demo vessel", demo.surface, repeats);
    Compare("demo vessel and a copy moved by 1 mm", WithMovedCopy(demo.surface, 1.0), repeats);
    if (large)
    {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetRadius(10.0);
      sphere->SetThetaResolution(710);
      sphere->SetPhiResolution(710);
      sphere->Update();
      Compare("sphere", sphere->GetOutput(), std::min(repeats, 3));
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_mesh_check: %s\n", e.what());
    return 1;
  }
  return 0;
}
