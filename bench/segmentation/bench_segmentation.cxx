// bench_segmentation [aneurysm.stl] [--no-large] [--vtk-only]
// Builds the phantom (0.4 mm) and a 512x512x400 resampling of it, then times the default
// pipeline (threshold + seeded region + fill holes, marching cubes, smoothing 0.5, normals) with
// both extractors (--vtk-only: the default one only) and prints per-stage wall times (the
// segmentation's stages from its progress reports), wall and CPU time of each run, accuracy
// against the STL and ITK/VTK ratios.

#include "MeshIO.h"
#include "SurfaceExtraction.h"
#include "SurfaceMetrics.h"
#include "VesselPhantom.h"
#include "VesselSegmentation.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

/// CPU time of the process (all threads), seconds.
double CpuSeconds()
{
  return double(std::clock()) / CLOCKS_PER_SEC;
}

/// Records when each stage named in the progress reports starts.
struct StageLog
{
  std::vector<std::pair<std::string, Clock::time_point>> starts;
  bender::ProgressReporter Reporter()
  {
    bender::ProgressReporter reporter;
    reporter.onProgress = [this](const std::string& stage, double) {
      if (this->starts.empty() || this->starts.back().first != stage)
      {
        this->starts.emplace_back(stage, Clock::now());
      }
    };
    return reporter;
  }
  void Print(Clock::time_point begin, Clock::time_point end) const
  {
    Clock::time_point previous = begin;
    std::string name = "setup";
    for (const auto& s : this->starts)
    {
      std::printf(" %s %.3f", name.c_str(), Seconds(previous, s.second));
      name = s.first;
      previous = s.second;
    }
    std::printf(" %s %.3f", name.c_str(), Seconds(previous, end));
  }
};

struct Run
{
  double segmentation = 0.0;
  double marchingCubes = 0.0;
  double surface = 0.0;
  double cpu = 0.0;
  std::size_t triangles = 0;
  bender::SurfaceAccuracy accuracy;
  bender::TriangleQuality quality;
};

Run Measure(const bender::Volume& volume, const bender::Phantom& phantom, vtkPolyData* truth,
  bender::SurfaceExtractor extractor, int repeats)
{
  Run best;
  best.segmentation = best.marchingCubes = best.surface = best.cpu = 1e300;
  for (int r = 0; r < repeats; ++r)
  {
    bender::SegmentationParameters segmentation;
    segmentation.seeds = { phantom.seed };
    StageLog log;
    const double c0 = CpuSeconds();
    const Clock::time_point t0 = Clock::now();
    const bender::LabelMap mask = bender::SegmentVessels(volume, segmentation, log.Reporter());
    const Clock::time_point t1 = Clock::now();
    const double c1 = CpuSeconds();
    bender::SurfaceParameters parameters;
    parameters.extractor = extractor;
    parameters.seeds = segmentation.seeds;
    const bender::SurfaceResult result = bender::ExtractSurface(mask, parameters);
    const Clock::time_point t2 = Clock::now();
    const double c2 = CpuSeconds();
    best.cpu = std::min(best.cpu, c2 - c0);
    best.segmentation = std::min(best.segmentation, Seconds(t0, t1));
    best.surface = std::min(best.surface, Seconds(t1, t2));
    std::printf("    %s run %d: segmentation %.3f s (cpu %.3f s) [", extractor == bender::SurfaceExtractor::Vtk ? "vtk" : "itk",
      r + 1, Seconds(t0, t1), c1 - c0);
    log.Print(t0, t1);
    std::printf(" ] surface %.3f s (cpu %.3f s) |", Seconds(t1, t2), c2 - c1);
    for (const bender::StageTime& t : result.timings)
    {
      std::printf(" %s %.3f", t.stage.c_str(), t.seconds);
      if (t.stage == "marching cubes")
      {
        best.marchingCubes = std::min(best.marchingCubes, t.seconds);
      }
    }
    std::printf(" | total %.3f s, cpu %.3f s\n", Seconds(t0, t2), c2 - c0);
    if (r == repeats - 1)
    {
      best.triangles = std::size_t(result.surface->GetNumberOfPolys());
      best.accuracy = bender::MeasureSurfaceAccuracy(result.surface, truth, phantom.caps, 1.0);
      best.quality = bender::MeasureTriangleQuality(result.surface);
    }
  }
  return best;
}

void Compare(const char* name, const bender::Volume& volume, const bender::Phantom& phantom, vtkPolyData* truth, int repeats,
  bool withItk)
{
  const auto& g = volume.geometry;
  std::printf("\n== %s: %zux%zux%zu voxels of %.3f x %.3f x %.3f mm (best of %d)\n", name, g.size[0], g.size[1],
    g.size[2], g.spacing[0], g.spacing[1], g.spacing[2], repeats);
  const Run vtk = Measure(volume, phantom, truth, bender::SurfaceExtractor::Vtk, repeats);
  const Run itk = withItk ? Measure(volume, phantom, truth, bender::SurfaceExtractor::Itk, repeats) : Run{};
  std::printf("  %-4s %10s %10s %10s %10s %10s %10s %9s %9s %9s %9s %8s %8s\n", "", "segment s", "MC s", "surface s",
    "total s", "cpu s", "triangles", "to mean", "to p95", "from mean", "from p95", "minang", "<10deg%");
  for (const auto* r : { &vtk, &itk })
  {
    if (r == &itk && !withItk)
    {
      continue;
    }
    std::printf("  %-4s %10.3f %10.3f %10.3f %10.3f %10.3f %10zu %9.4f %9.4f %9.4f %9.4f %8.2f %8.4f\n",
      r == &vtk ? "vtk" : "itk", r->segmentation, r->marchingCubes, r->surface, r->segmentation + r->surface,
      r->cpu, r->triangles, r->accuracy.toTruth.mean, r->accuracy.toTruth.p95, r->accuracy.fromTruth.mean,
      r->accuracy.fromTruth.p95, r->quality.meanMinAngle, 100.0 * r->quality.fractionBelow10Deg);
  }
  if (!withItk)
  {
    return;
  }
  std::printf("  ITK/VTK marching cubes time: %.2fx; surface stage: %.2fx; whole pipeline: %.2fx\n",
    itk.marchingCubes / vtk.marchingCubes, itk.surface / vtk.surface,
    (itk.segmentation + itk.surface) / (vtk.segmentation + vtk.surface));
}

} // namespace

int main(int argc, char** argv)
{
  std::string stl = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
  bool large = true;
  bool withItk = true;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--no-large") == 0)
    {
      large = false;
    }
    else if (std::strcmp(argv[i], "--vtk-only") == 0)
    {
      withItk = false;
    }
    else
    {
      stl = argv[i];
    }
  }
  try
  {
    std::printf("bench_segmentation: %u hardware threads\n", std::thread::hardware_concurrency());
    vtkSmartPointer<vtkPolyData> truth = bender::ReadMesh(stl);
    const Clock::time_point t0 = Clock::now();
    const bender::Phantom phantom = bender::MakeVesselPhantom(truth);
    std::printf("phantom (0.4 mm) built in %.3f s\n", Seconds(t0, Clock::now()));
    Compare("phantom 0.4 mm", phantom.volume, phantom, truth, 3, withItk);
    if (large)
    {
      const Clock::time_point t1 = Clock::now();
      const bender::Volume big = bender::ResampleVolume(phantom.volume, { { 512, 512, 400 } });
      std::printf("\nresampled to 512x512x400 in %.3f s\n", Seconds(t1, Clock::now()));
      Compare("phantom resampled 512x512x400", big, phantom, truth, 2, withItk);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_segmentation: %s\n", e.what());
    return 1;
  }
  return 0;
}
