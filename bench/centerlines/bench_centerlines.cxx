// bench_centerlines: centerlines (Voronoi diagram, minimal paths, smoothing, branches) of the
// gmsh aneurysm (about 20 k triangles, 3 open ends) and of the demo segmentation (about 55 k
// triangles, closed), with the time of each stage. Prints the machine, every run and the
// median, min and max of each stage. Target (issue 10): at most 1 s for the 55 k-triangle
// surface on a 2-core machine. Figures taken on a loaded machine are not final: say so when
// quoting them.
//
// usage: bench_centerlines [REPEATS] [SURFACE ...]   (default 5 repeats, the two surfaces)

#include "DemoPipeline.h"
#include "MeshIO.h"
#include "VesselCenterlines.h"

#include "BenchMachine.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
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
    const auto& t = result.Times;
    const double values[8] = {
      t.Preparation, t.Delaunay, t.Voronoi, t.Endpoints, t.Paths, t.Smoothing, t.Branches, total
    };
    for (int k = 0; k < 8; ++k)
    {
      stages[k].push_back(values[k]);
    }
    std::printf("  run %d: %s, %zu endpoints, %lld branches, %d Voronoi vertices; "
                "prep %.3f delaunay %.3f voronoi %.3f endpoints %.3f paths %.3f smoothing %.3f "
                "branches %.3f total %.3f s\n",
      r + 1,
      result.Ok ? "ok" : result.Message.c_str(),
      result.Endpoints.size(),
      static_cast<long long>(result.Branches->GetNumberOfCells()),
      result.NumberOfVoronoiVertices,
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
} // namespace

int main(int argc, char* argv[])
{
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::printf(
    "bench_centerlines: %s; medians of %d runs\n", bender_bench::MachineLine().c_str(), repeats);
  try
  {
    if (argc > 2)
    {
      for (int i = 2; i < argc; ++i)
      {
        Run(argv[i], bender::ReadMesh(argv[i]), repeats);
      }
      return 0;
    }
    const std::string aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
    Run("gmsh aneurysm (open)", bender::ReadMesh(aneurysm), repeats);
    const bender::DemoVessel demo = bender::SegmentDemoVessel(bender::DemoVesselPath());
    Run("demo segmentation (closed)", demo.surface, repeats);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_centerlines: %s\n", e.what());
    return 1;
  }
  return 0;
}
