// bench_cfd: the demo's original-vs-bent flow comparison (issue 23, "Speed"), timed stage by
// stage. The demo vessel is segmented from its MRA-like phantom, bent by the demo plan, and
// both shapes are made CFD-ready (ends clipped, flow extensions, labelled caps: "prepare", not
// part of the target); then two OpenFOAM cases at the defaults (3 prism layers, the default
// cell size, the inlet by flow rate) are written, meshed, solved and mapped onto their surfaces
// (RunOpenFoamCase), and compared as `bender-cli compare` does (the table and the bend
// measures, no PDF). Prints the machine, the date, the load average, each case's stages
// (mesh, layers, solve, map; the Allrun's steps with --steps) and the total from the cases
// written to the comparison, against the target: 4 minutes on 2 cores.
//
// The two cases run one after the other, each on --processors N (OpenFOAM's parallel run of
// simpleFoam: decomposePar, mpirun, reconstructPar; snappyHexMesh stays serial), or with
// --concurrent both at once, each on its own processors. Figures taken on a machine shared with
// other work are not final: the load average printed says how busy it was. Each case's stages
// are also given by OpenFOAM's own CPU clocks (snappyHexMesh's phases, simpleFoam's
// ExecutionTime), from which the bench estimates the comparison on an idle machine.
//
// usage: bench_cfd [--processors N] [--concurrent] [--iterations N] [--cell-size H_m]
//                  [--original A.vtp --bent B.vtp] [--spacing MM] [--keep DIR] [--steps]

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "CfdCase.h"
#include "CfdCaseComparison.h"
#include "CfdStageTimes.h"
#include "DemoPipeline.h"
#include "LabelledSurface.h"
#include "MeshIO.h"
#include "PrepareForCfd.h"
#include "WarpPlanIO.h"

#include "BenchMachine.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace
{
using Clock = std::chrono::steady_clock;

constexpr double kTargetSeconds = 240.0;

double Since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The 1-minute load average (/proc/loadavg), -1 when unknown.
double LoadAverage()
{
  std::ifstream in("/proc/loadavg");
  double load = -1.0;
  in >> load;
  return in ? load : -1.0;
}

std::string UtcNow()
{
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

struct Options
{
  int processors = 1;
  bool concurrent = false;
  int iterations = 0; ///< 0: the case's default
  double cellSize = 0.0;
  std::string original, bent;
  double spacing = 0.4; ///< the phantom's voxel, mm (bender-cli phantom's default)
  std::string keep;
  bool steps = false;
};

/// One shape of the comparison.
struct Shape
{
  std::string label;
  bender::LabelledSurface surface;
  std::string caseDirectory;
  bender::CfdRunResult run;
  double write = 0.0; ///< WriteOpenFoamCase, s
  double wall = 0.0;  ///< RunOpenFoamCase, s
  std::string error;
};

bender::LabelledSurface Prepared(vtkPolyData* surface, const std::string& name)
{
  bender::PrepareForCfdOptions prepare;
  prepare.inputName = name;
  const bender::PrepareForCfdResult result = bender::PrepareForCfd(surface, prepare);
  return { result.surface, result.patches };
}

void WriteCase(Shape& shape, const Options& options)
{
  const auto start = Clock::now();
  bender::CfdCaseOptions c;
  c.caseDirectory = shape.caseDirectory;
  c.force = true;
  c.sourceName = shape.label;
  c.processors = options.processors;
  c.cellSize = options.cellSize;
  if (options.iterations > 0)
  {
    c.iterations = options.iterations;
  }
  bender::WriteOpenFoamCase(shape.surface, c);
  shape.write = Since(start);
}

void RunCase(Shape& shape)
{
  const auto start = Clock::now();
  try
  {
    shape.run = bender::RunOpenFoamCase(shape.caseDirectory);
  }
  catch (const std::exception& e) // reported by the bench, which then stops
  {
    shape.error = e.what();
  }
  shape.wall = Since(start);
}

/// The last "ExecutionTime = X s" of an OpenFOAM log: the program's own CPU clock (its master
/// process under mpirun); 0 when the log has none.
double ExecutionSeconds(const fs::path& log)
{
  std::ifstream in(log);
  double seconds = 0.0;
  for (std::string line; std::getline(in, line);)
  {
    if (line.rfind("ExecutionTime = ", 0) == 0)
    {
      seconds = std::strtod(line.c_str() + 16, nullptr);
    }
  }
  return seconds;
}

/// The stages by OpenFOAM's CPU clocks where it has them (snappyHexMesh's phases,
/// surfaceFeatureExtract, simpleFoam), the wall clock for the short steps without one: about
/// what an idle core takes, whatever the load while the bench ran.
bender::CfdStageTimes CpuStages(const Shape& s)
{
  const fs::path dir(s.caseDirectory);
  std::ifstream snappyLog(dir / "log.snappyHexMesh");
  const std::string snappyText(
    (std::istreambuf_iterator<char>(snappyLog)), std::istreambuf_iterator<char>());
  const bender::SnappyPhaseTimes phases = bender::ParseSnappyPhaseTimes(snappyText);
  bender::CfdStageTimes cpu;
  for (const auto& [program, seconds] : s.run.stages.steps)
  {
    if (program == "snappyHexMesh")
    {
      cpu.mesh += phases.refine + phases.snap;
      cpu.layers += phases.layers;
    }
    else if (program == "surfaceFeatureExtract")
    {
      cpu.mesh += ExecutionSeconds(dir / "log.surfaceFeatureExtract");
    }
    else if (program == "simpleFoam" || program == "mpirun")
    {
      cpu.solve += ExecutionSeconds(dir / "log.simpleFoam");
    }
    else if (program == "blockMesh" || program == "checkMesh")
    {
      cpu.mesh += seconds;
    }
    else
    {
      cpu.solve += seconds;
    }
  }
  cpu.map = s.run.stages.map;
  return cpu;
}

void PrintShape(const Shape& s, bool steps)
{
  const bender::CfdStageTimes& t = s.run.stages;
  std::printf("%-9s %7lld cells, %s: mesh %6.1f s, layers %5.1f s, solve %6.1f s, map %4.1f s"
              " = %6.1f s (run %6.1f s, case written in %.1f s)\n",
    s.label.c_str(),
    s.run.mesh.cells,
    bender::CfdRunStatus(s.run).substr(0, bender::CfdRunStatus(s.run).find(';')).c_str(),
    t.mesh,
    t.layers,
    t.solve,
    t.map,
    t.Total(),
    s.wall,
    s.write);
  const bender::CfdStageTimes cpu = CpuStages(s);
  std::printf("          by OpenFOAM's CPU clocks: mesh %6.1f s, layers %5.1f s, solve %6.1f s\n",
    cpu.mesh,
    cpu.layers,
    cpu.solve);
  if (steps)
  {
    for (const auto& [program, seconds] : t.steps)
    {
      std::printf("            %-22s %6.1f s\n", program.c_str(), seconds);
    }
  }
}

int Usage(const char* problem)
{
  std::fprintf(stderr,
    "bench_cfd: %s\nusage: bench_cfd [--processors N] [--concurrent] [--iterations N] "
    "[--cell-size H_m] [--original A.vtp --bent B.vtp] [--spacing MM] [--keep DIR] [--steps]\n",
    problem);
  return 2;
}
} // namespace

int main(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--concurrent")
    {
      options.concurrent = true;
    }
    else if (a == "--steps")
    {
      options.steps = true;
    }
    else if (a == "--processors" && hasValue)
    {
      options.processors = std::atoi(argv[++i]);
    }
    else if (a == "--iterations" && hasValue)
    {
      options.iterations = std::atoi(argv[++i]);
    }
    else if (a == "--cell-size" && hasValue)
    {
      options.cellSize = std::atof(argv[++i]);
    }
    else if (a == "--original" && hasValue)
    {
      options.original = argv[++i];
    }
    else if (a == "--bent" && hasValue)
    {
      options.bent = argv[++i];
    }
    else if (a == "--spacing" && hasValue)
    {
      options.spacing = std::atof(argv[++i]);
    }
    else if (a == "--keep" && hasValue)
    {
      options.keep = argv[++i];
    }
    else
    {
      return Usage(("unknown or incomplete option " + a).c_str());
    }
  }
  if (options.processors < 1 || options.original.empty() != options.bent.empty())
  {
    return Usage("--processors must be >= 1; --original and --bent go together");
  }
  if (const std::string problem = bender::FindOpenFoamProblem(options.processors); !problem.empty())
  {
    std::fprintf(stderr, "bench_cfd: %s\n", problem.c_str());
    return 1;
  }

  std::printf("bench_cfd: the demo's original-vs-bent comparison, %s, %d processor%s per case\n",
    options.concurrent ? "both cases at once" : "one case after the other",
    options.processors,
    options.processors > 1 ? "s" : "");
  std::printf("%s\ndate: %s; load average (1 min) at the start: %.2f\n",
    bender_bench::MachineLine().c_str(),
    UtcNow().c_str(),
    LoadAverage());
  std::fflush(stdout);

  try
  {
    const fs::path folder = options.keep.empty()
      ? fs::temp_directory_path() / ("bench_cfd-" + std::to_string(::getpid()))
      : fs::path(options.keep);
    fs::create_directories(folder);
    Shape shapes[2];
    shapes[0].label = "original";
    shapes[1].label = "bent";

    // Prepare: not part of the target (the Flow panel starts from a bent, prepared vessel).
    const auto prepareStart = Clock::now();
    if (!options.original.empty())
    {
      shapes[0].surface = bender::ReadLabelledSurface(bender::ReadMesh(options.original));
      shapes[1].surface = bender::ReadLabelledSurface(bender::ReadMesh(options.bent));
    }
    else
    {
      bender::DemoOptions demo;
      demo.spacing = options.spacing;
      const bender::DemoVessel vessel = bender::SegmentDemoVessel(bender::DemoVesselPath(), demo);
      bender::ApplyPlanOptions apply;
      apply.planName = "demo plan";
      const vtkSmartPointer<vtkPolyData> bent =
        bender::ApplyPlan(vessel.surface, bender::ReadWarpPlan(bender::DemoPlanPath()), apply)
          .output;
      shapes[0].surface = Prepared(vessel.surface, "the demo vessel");
      shapes[1].surface = Prepared(bent, "the bent demo vessel");
    }
    std::printf("prepare (segment, bend, clip; not in the target): %.1f s; %lld and %lld "
                "triangles\n",
      Since(prepareStart),
      static_cast<long long>(shapes[0].surface.surface->GetNumberOfPolys()),
      static_cast<long long>(shapes[1].surface.surface->GetNumberOfPolys()));
    std::fflush(stdout);

    // The target: from the cases written to the comparison.
    const auto start = Clock::now();
    for (Shape& s : shapes)
    {
      s.caseDirectory = (folder / ("case-" + s.label)).string();
      WriteCase(s, options);
    }
    if (options.concurrent)
    {
      std::thread other([&] { RunCase(shapes[1]); });
      RunCase(shapes[0]);
      other.join();
    }
    else
    {
      for (Shape& s : shapes)
      {
        RunCase(s);
        if (!s.error.empty())
        {
          break;
        }
      }
    }
    for (const Shape& s : shapes)
    {
      if (!s.error.empty())
      {
        std::fprintf(stderr, "bench_cfd: %s: %s\n", s.label.c_str(), s.error.c_str());
        return 1;
      }
    }
    const auto compareStart = Clock::now();
    bender::CompareCfdCasesOptions compare;
    compare.caseA = shapes[0].caseDirectory;
    compare.caseB = shapes[1].caseDirectory;
    compare.plan = options.original.empty() ? bender::DemoPlanPath() : std::string();
    const bender::CfdCaseComparison comparison = bender::CompareCfdCases(compare);
    const double compareSeconds = Since(compareStart);
    const double total = Since(start);

    for (const Shape& s : shapes)
    {
      PrintShape(s, options.steps);
    }
    std::printf("compare (table and bend measures, %zu rows): %.1f s\n",
      comparison.table.rows.size(),
      compareSeconds);
    const double load = LoadAverage();
    std::printf("total, cases written to compared: %.1f s against the 4-minute target: %.2f x "
                "(%s); load average (1 min) at the end: %.2f\n",
      total,
      total / kTargetSeconds,
      total <= kTargetSeconds ? "met" : "missed",
      load);
    // On a machine shared with other work the wall clock says little: the same comparison on
    // an idle machine, from the CPU clocks (the map and the comparison at their wall times).
    const bender::CfdStageTimes cpuA = CpuStages(shapes[0]), cpuB = CpuStages(shapes[1]);
    const double written = shapes[0].write + shapes[1].write;
    std::printf("idle-machine estimate from the CPU clocks: one case after the other %.1f s",
      written + cpuA.Total() + cpuB.Total() + compareSeconds);
    if (options.processors == 1)
    {
      std::printf(", both at once on 2 cores %.1f s",
        written + std::max(cpuA.Total(), cpuB.Total()) + compareSeconds);
    }
    std::printf(" (against the 4-minute target)\n");
    if (options.keep.empty())
    {
      std::error_code ec;
      fs::remove_all(folder, ec);
    }
    else
    {
      std::printf("cases kept in %s\n", folder.string().c_str());
    }
  }
  catch (const std::exception& e) // the bench's one line for whatever stopped it
  {
    std::fprintf(stderr, "bench_cfd: %s\n", e.what());
    return 1;
  }
  return 0;
}
