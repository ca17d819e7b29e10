// bench_segmentation [aneurysm.stl] [--no-large] [--vtk-only] [--seeding-only]
// [--smoothing-only] [--ch2 FILE] [--repeats K]
// Builds the phantom (0.4 mm) and a 512x512x400 resampling of it, then times the
// default pipeline (threshold + seeded region + fill holes, marching cubes, smoothing 0.5, normals)
// with both extractors (--vtk-only: the default one only) and prints per-stage wall times (the
// segmentation's stages from its progress reports), wall and CPU time of each run, accuracy
// against the STL and ITK/VTK ratios. Then the segmentation without a seed (the largest
// component, as for a head MRI) against the seeded segmentation of the same component (the
// reference, measured in the same run, interleaved) on both phantoms and on ch2.nii.gz (the
// Colin27 T1 head, data/external; window: 40 to its maximum, as in docs/segmentation.md),
// with a check that both masks are equal (--seeding-only: this part alone). Then the surface
// smoothing's own windowed-sinc filter (the path ExtractSurface takes for closed surfaces)
// against vtkWindowedSincPolyDataFilter with the same parameters on the same unsmoothed surface,
// in the same run: times and the largest distance between their points (--smoothing-only: this
// part alone). Every figure: median [min, max] over the runs.

#include "MeshIO.h"
#include "SurfaceExtraction.h"
#include "SurfaceMetrics.h"
#include "VesselPhantom.h"
#include "VesselSegmentation.h"
#include "VolumeIO.h"

#include "BenchMachine.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
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
    reporter.onProgress = [this](const std::string& stage, double)
    {
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
  std::vector<double> segmentation, marchingCubes, surface, total, cpu;
  std::size_t triangles = 0;
  bender::SurfaceAccuracy accuracy;
  bender::TriangleQuality quality;
};

Run Measure(const bender::Volume& volume,
  const bender::Phantom& phantom,
  vtkPolyData* truth,
  bender::SurfaceExtractor extractor,
  int repeats)
{
  Run runs;
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
    runs.cpu.push_back(c2 - c0);
    runs.segmentation.push_back(Seconds(t0, t1));
    runs.surface.push_back(Seconds(t1, t2));
    runs.total.push_back(Seconds(t0, t2));
    std::printf("    %s run %d: segmentation %.3f s (cpu %.3f s) [",
      extractor == bender::SurfaceExtractor::Vtk ? "vtk" : "itk",
      r + 1,
      Seconds(t0, t1),
      c1 - c0);
    log.Print(t0, t1);
    std::printf(" ] surface %.3f s (cpu %.3f s) |", Seconds(t1, t2), c2 - c1);
    for (const bender::StageTime& t : result.timings)
    {
      std::printf(" %s %.3f", t.stage.c_str(), t.seconds);
      if (t.stage == "marching cubes")
      {
        runs.marchingCubes.push_back(t.seconds);
      }
    }
    std::printf(" | total %.3f s, cpu %.3f s\n", Seconds(t0, t2), c2 - c0);
    if (r == repeats - 1)
    {
      runs.triangles = std::size_t(result.surface->GetNumberOfPolys());
      runs.accuracy = bender::MeasureSurfaceAccuracy(result.surface, truth, phantom.caps, 1.0);
      runs.quality = bender::MeasureTriangleQuality(result.surface);
    }
  }
  return runs;
}

void Compare(const char* name,
  const bender::Volume& volume,
  const bender::Phantom& phantom,
  vtkPolyData* truth,
  int repeats,
  bool withItk)
{
  const auto& g = volume.geometry;
  std::printf("\n== %s: %zux%zux%zu voxels of %.3f x %.3f x %.3f mm (%d runs each)\n",
    name,
    g.size[0],
    g.size[1],
    g.size[2],
    g.spacing[0],
    g.spacing[1],
    g.spacing[2],
    repeats);
  const Run vtk = Measure(volume, phantom, truth, bender::SurfaceExtractor::Vtk, repeats);
  const Run itk =
    withItk ? Measure(volume, phantom, truth, bender::SurfaceExtractor::Itk, repeats) : Run{};
  std::printf("  times in s, median [min, max] of %d runs\n", repeats);
  std::printf("  %-4s %-24s %-24s %-24s %-24s %10s %9s %9s %9s %9s %8s %8s\n",
    "",
    "segment s",
    "MC s",
    "surface s",
    "total s",
    "triangles",
    "to mean",
    "to p95",
    "from mean",
    "from p95",
    "minang",
    "<10deg%");
  for (const auto* r : { &vtk, &itk })
  {
    if (r == &itk && !withItk)
    {
      continue;
    }
    using bender_bench::Format;
    using bender_bench::Summarise;
    std::printf("  %-4s %-24s %-24s %-24s %-24s %10zu %9.4f %9.4f %9.4f %9.4f %8.2f %8.4f\n",
      r == &vtk ? "vtk" : "itk",
      Format(Summarise(r->segmentation), 3).c_str(),
      Format(Summarise(r->marchingCubes), 3).c_str(),
      Format(Summarise(r->surface), 3).c_str(),
      Format(Summarise(r->total), 3).c_str(),
      r->triangles,
      r->accuracy.toTruth.mean,
      r->accuracy.toTruth.p95,
      r->accuracy.fromTruth.mean,
      r->accuracy.fromTruth.p95,
      r->quality.meanMinAngle,
      100.0 * r->quality.fractionBelow10Deg);
  }
  std::printf("  cpu s (all threads, whole pipeline): vtk %s",
    bender_bench::Format(bender_bench::Summarise(vtk.cpu), 3).c_str());
  if (!withItk)
  {
    std::printf("\n");
    return;
  }
  std::printf(", itk %s\n", bender_bench::Format(bender_bench::Summarise(itk.cpu), 3).c_str());
  const auto median = [](const std::vector<double>& v)
  { return bender_bench::Summarise(v).median; };
  std::printf(
    "  ITK/VTK marching cubes time: %.2fx; surface stage: %.2fx; whole pipeline: %.2fx (medians)\n",
    median(itk.marchingCubes) / median(vtk.marchingCubes),
    median(itk.surface) / median(vtk.surface),
    median(itk.total) / median(vtk.total));
}

/// The segmentation without a seed (largest component) against the seeded segmentation of the
/// same component, the reference, in the same run: the two alternate, `repeats` runs each.
/// Without `seed`, the seed is the first voxel (raster order) of the no-seed result.
void CompareSeeding(const char* name,
  const bender::Volume& volume,
  bender::SegmentationParameters parameters,
  const bender::Point3* seed,
  int repeats)
{
  const auto& g = volume.geometry;
  parameters.seeds.clear();
  const bender::LabelMap first = bender::SegmentVessels(volume, parameters);
  bender::SegmentationParameters seeded = parameters;
  if (seed)
  {
    seeded.seeds = { *seed };
  }
  else
  {
    // A voxel of the largest component that is in the window (a filled hole is not).
    for (std::size_t i = 0; i < first.voxels.size(); ++i)
    {
      if (first.voxels[i] && volume.voxels[i] >= parameters.lower &&
        volume.voxels[i] <= parameters.upper)
      {
        const std::size_t x = i % g.size[0], y = (i / g.size[0]) % g.size[1],
                          z = i / (g.size[0] * g.size[1]);
        seeded.seeds = { g.IndexToPhysical({ { double(x), double(y), double(z) } }) };
        break;
      }
    }
  }
  std::vector<double> withSeed, withoutSeed;
  bool same = true;
  for (int r = 0; r < repeats; ++r)
  {
    bender::LabelMap a, b;
    withSeed.push_back(
      bender_bench::TimeRunsMs(1, [&] { a = bender::SegmentVessels(volume, seeded); })[0]);
    withoutSeed.push_back(
      bender_bench::TimeRunsMs(1, [&] { b = bender::SegmentVessels(volume, parameters); })[0]);
    same = same && a.voxels == b.voxels;
  }
  const bender_bench::Spread s = bender_bench::Summarise(withSeed);
  const bender_bench::Spread n = bender_bench::Summarise(withoutSeed);
  std::printf("  %-34s %4zux%4zux%4zu %10zu %-26s %-26s %7.2f %s\n",
    name,
    g.size[0],
    g.size[1],
    g.size[2],
    first.CountInside(),
    bender_bench::Format(s, 1).c_str(),
    bender_bench::Format(n, 1).c_str(),
    n.median / s.median,
    same ? "yes" : "NO");
}

/// The smoothing of ExtractSurface (its own windowed-sinc filter on closed surfaces: 20
/// iterations, pass band 10^(-4 * 0.5), normalised coordinates, no feature edges) against
/// vtkWindowedSincPolyDataFilter with the same parameters on the same unsmoothed surface, the
/// two alternating, `repeats` runs each. The own filter's time is ExtractSurface's "smoothing"
/// stage; the result compared is the largest distance between corresponding points.
void CompareSmoothing(const char* name,
  const bender::Volume& volume,
  const bender::Phantom& phantom,
  int repeats)
{
  bender::SegmentationParameters segmentation;
  segmentation.seeds = { phantom.seed };
  const bender::LabelMap mask = bender::SegmentVessels(volume, segmentation);
  bender::SurfaceParameters raw;
  raw.seeds = segmentation.seeds;
  raw.smoothing = 0.0;
  const bender::SurfaceResult unsmoothed = bender::ExtractSurface(mask, raw);
  // Points and triangles only: the filter gets what the own filter gets.
  vtkNew<vtkPolyData> input;
  input->SetPoints(unsmoothed.surface->GetPoints());
  input->SetPolys(unsmoothed.surface->GetPolys());
  bender::SurfaceParameters smoothed = raw;
  smoothed.smoothing = 0.5;
  std::vector<double> ownMs, vtkMs;
  double worst = 0.0;
  bool samePoints = true;
  for (int r = 0; r < repeats; ++r)
  {
    const bender::SurfaceResult own = bender::ExtractSurface(mask, smoothed);
    for (const bender::StageTime& t : own.timings)
    {
      if (t.stage == "smoothing")
      {
        ownMs.push_back(1000.0 * t.seconds);
      }
    }
    vtkNew<vtkWindowedSincPolyDataFilter> filter;
    vtkMs.push_back(bender_bench::TimeRunsMs(1,
      [&]
      {
        filter->SetInputData(input);
        filter->SetNumberOfIterations(20);
        filter->SetPassBand(std::pow(10.0, -4.0 * smoothed.smoothing));
        filter->BoundarySmoothingOff();
        filter->FeatureEdgeSmoothingOff();
        filter->NonManifoldSmoothingOn();
        filter->NormalizeCoordinatesOn();
        filter->Update();
      })[0]);
    vtkPolyData* reference = filter->GetOutput();
    samePoints = samePoints && reference->GetNumberOfPoints() == own.surface->GetNumberOfPoints();
    for (vtkIdType i = 0; samePoints && i < reference->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      own.surface->GetPoint(i, a);
      reference->GetPoint(i, b);
      worst = std::max(worst, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  }
  const bender_bench::Spread own = bender_bench::Summarise(ownMs);
  const bender_bench::Spread vtk = bender_bench::Summarise(vtkMs);
  char distance[64] = "point counts differ";
  if (samePoints)
  {
    std::snprintf(distance, sizeof distance, "%.2g mm", worst);
  }
  std::printf("  %-30s %10lld %-26s %-26s %7.2f %s\n",
    name,
    static_cast<long long>(unsmoothed.surface->GetNumberOfPolys()),
    bender_bench::Format(own, 1).c_str(),
    bender_bench::Format(vtk, 1).c_str(),
    vtk.median / own.median,
    distance);
}

} // namespace

int main(int argc, char** argv)
{
  std::string stl = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
  std::string ch2 = std::string(BENDER_EXTERNAL_DATA_DIR) + "/ch2.nii.gz";
  bool large = true;
  bool withItk = true;
  bool pipeline = true;
  bool seeding = true;
  int repeats = 5;
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
    else if (std::strcmp(argv[i], "--seeding-only") == 0)
    {
      pipeline = false;
    }
    else if (std::strcmp(argv[i], "--smoothing-only") == 0)
    {
      pipeline = false;
      seeding = false;
    }
    else if (std::strcmp(argv[i], "--ch2") == 0 && i + 1 < argc)
    {
      ch2 = argv[++i];
    }
    else if (std::strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
    {
      repeats = std::max(1, std::atoi(argv[++i]));
    }
    else
    {
      stl = argv[i];
    }
  }
  try
  {
    std::printf("bench_segmentation: %s\n", bender_bench::MachineLine().c_str());
    vtkSmartPointer<vtkPolyData> truth = bender::ReadMesh(stl);
    const Clock::time_point t0 = Clock::now();
    const bender::Phantom phantom = bender::MakeVesselPhantom(truth);
    std::printf("phantom (0.4 mm) built in %.3f s\n", Seconds(t0, Clock::now()));
    if (pipeline)
    {
      Compare("phantom 0.4 mm", phantom.volume, phantom, truth, repeats, withItk);
    }
    bender::Volume big;
    if (large)
    {
      const Clock::time_point t1 = Clock::now();
      big = bender::ResampleVolume(phantom.volume, { { 512, 512, 400 } });
      std::printf("\nresampled to 512x512x400 in %.3f s\n", Seconds(t1, Clock::now()));
      if (pipeline)
      {
        Compare(
          "phantom resampled 512x512x400", big, phantom, truth, std::max(1, repeats / 2), withItk);
      }
    }

    if (seeding)
    {
      std::printf(
        "\n== segmentation without a seed (largest component) vs the seeded reference, same "
        "component, same run; ms, median [min, max] of %d runs each\n",
        repeats);
      std::printf("  %-34s %14s %10s %-26s %-26s %7s %s\n",
        "volume",
        "voxels",
        "component",
        "seeded ms (reference)",
        "no seed ms",
        "ratio",
        "same mask");
      bender::SegmentationParameters threshold; // the default window (lower 250) fits the phantom
      CompareSeeding("phantom 0.4 mm", phantom.volume, threshold, &phantom.seed, repeats);
      if (large)
      {
        CompareSeeding("phantom resampled", big, threshold, &phantom.seed, repeats);
      }
      if (std::filesystem::exists(ch2))
      {
        const bender::Volume head = bender::ReadVolume(ch2);
        bender::SegmentationParameters headWindow;
        headWindow.lower = 40.0; // the head's threshold in docs/segmentation.md
        CompareSeeding("ch2.nii.gz (head T1)", head, headWindow, nullptr, repeats);
        std::printf("  ch2 window: [%.1f, max]\n", headWindow.lower);
      }
      else
      {
        std::printf("  ch2: %s not found (run scripts/fetch-data)\n", ch2.c_str());
      }
    }
    std::printf("\n== surface smoothing: own windowed-sinc filter vs "
                "vtkWindowedSincPolyDataFilter, same input and parameters, same run; ms, median "
                "[min, max] of %d runs each\n",
      repeats);
    std::printf("  %-30s %10s %-26s %-26s %7s %s\n",
      "surface of",
      "triangles",
      "own ms",
      "vtkWindowedSinc ms",
      "vtk/own",
      "largest point distance");
    CompareSmoothing("phantom 0.4 mm", phantom.volume, phantom, repeats);
    if (large)
    {
      CompareSmoothing("phantom resampled 512x512x400", big, phantom, repeats);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "bench_segmentation: %s\n", e.what());
    return 1;
  }
  return 0;
}
