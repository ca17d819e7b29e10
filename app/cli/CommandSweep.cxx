// bender-cli sweep SURFACE PLAN -o SWEEP_DIR --vary fraction=0:1.5:7 [--engine slurm ...]: a
// what-if sweep of candidate bends, each solved by OpenFOAM (workflow in modules/Logic/Sweep).

#include "CliCommand.h"
#include "CliParsing.h"
#include "HeadlessDisplay.h"
#include "SignalGuard.h"

#include "BenderErrors.h"
#include "Sweep.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <unistd.h>

namespace
{
const char* const Details =
  "Makes candidate bends of a vessel from a plan, prepares each for CFD as the original (the "
  "same clipped ends, names and flow extensions, matched by name) and solves each with "
  "OpenFOAM with the same settings (the original's cell size and inlet flow rate), on this "
  "machine or on a Slurm cluster. A candidate that folds or self-intersects is reported and "
  "not solved.\n"
  "\n"
  "--vary fraction=FROM:TO:COUNT: the fraction of each warp's motion (the final ribbon's end "
  "frames moved along the screw motion from the initial ones: 0 the original, 1 the plan, 1.5 "
  "half as far again). --vary radius=FROM:TO:COUNT: every warp's radius of influence (mm). "
  "--plans A B ...: one candidate per plan, beside the original.\n"
  "\n"
  "SWEEP_DIR gets one folder per candidate (its state.json and OpenFOAM case), summary.csv, "
  "summary.json (one row per candidate: the varied value, bend angle, length change, minimal "
  "radius, pressure drop, split per outlet, wall shear stress, mesh size, iterations, state; "
  "the rows not solved and why) and summary.png. Running the same command again keeps what "
  "finished with the same inputs and runs only what is missing, failed or changed; Ctrl+C "
  "stops it with the folder consistent.\n"
  "\n"
  "--engine slurm submits one sbatch array job (one task per candidate, each case's Allrun "
  "inside its allocation, --processors P through mpirun); SWEEP_DIR must be on a filesystem "
  "every node shares. A failed task is submitted once more, then reported with its log.\n"
  "\n"
  "example: bender-cli sweep vessel.stl bend.bender.json -o sweep --vary fraction=0:1.5:7 "
  "--jobs 2\n"
  "\n"
  "exit status: 0 every candidate solved or rejected, 1 bad input, a failed candidate or a "
  "missing tool, 2 usage error, 130 interrupted";

struct SweepArguments
{
  std::string surface, vary, engine = "local";
  std::vector<std::string> plans, morePlans;
  bender::SweepOptions options;
};

// A progress bar on a terminal: "[#####.....] 3/7 solved".
void Bar(const std::string& stage, double fraction)
{
  if (!isatty(STDOUT_FILENO))
  {
    return;
  }
  const int width = 30;
  const int filled = static_cast<int>(std::lround(fraction * width));
  std::printf("\r[%s%s] %3.0f %% %s",
    std::string(filled, '#').c_str(),
    std::string(width - filled, '.').c_str(),
    100.0 * fraction,
    stage.c_str());
  if (fraction >= 1.0)
  {
    std::printf("\n");
  }
  std::fflush(stdout);
}

int RunSweepCommand(SweepArguments a)
{
  bender::SweepOptions& options = a.options;
  options.surface = a.surface;
  options.plans = a.plans;
  options.plans.insert(options.plans.end(), a.morePlans.begin(), a.morePlans.end());
  if (!a.vary.empty())
  {
    options.vary = bender::ParseSweepVary(a.vary);
  }
  else if (a.morePlans.empty())
  {
    return bender::CommandError("sweep", "give --vary NAME=FROM:TO:COUNT or --plans A B ...");
  }
  options.engine.kind =
    a.engine == "slurm" ? bender::SweepEngineKind::Slurm : bender::SweepEngineKind::Local;
  const bool terminal = isatty(STDOUT_FILENO);
  options.onLine = [terminal](const std::string& line)
  {
    std::printf("%s%s\n", terminal ? "\r\033[K" : "", line.c_str());
    std::fflush(stdout);
  };
  options.progress.onProgress = Bar;
  std::string plotProblem = bender::EnsureHeadlessDisplay();
  bender::SignalGuard signals;
  options.progress.cancel = signals.Flag();
  bender::SweepResult result;
  try
  {
    result = bender::RunSweep(options);
  }
  catch (const bender::Cancelled&)
  {
    std::printf("\nsweep: interrupted; %s is consistent: run the same command again to finish "
                "what is missing\n",
      options.output.c_str());
    return 130;
  }
  std::size_t failed = 0, solved = 0, rejected = 0;
  for (const bender::SweepRow& row : result.rows)
  {
    solved += row.state == "solved";
    rejected += row.state == "rejected";
    if (row.state == "failed")
    {
      ++failed;
      std::printf(
        "%s: failed: %s (log: %s)\n", row.id.c_str(), row.reason.c_str(), row.log.c_str());
    }
  }
  std::printf("sweep: %zu prepared now; %zu solved (%zu now, %zu kept), %zu rejected, %zu "
              "failed\n",
    result.prepared,
    solved,
    result.solved,
    result.kept,
    rejected,
    failed);
  std::printf("summary: %s, %s", result.summaryCsv.c_str(), result.summaryJson.c_str());
  if (!result.summaryPng.empty())
  {
    std::printf(", %s", result.summaryPng.c_str());
  }
  std::printf("\n");
  if (!result.plotProblem.empty() || !plotProblem.empty())
  {
    std::printf("summary.png not drawn: %s\n",
      (plotProblem.empty() ? result.plotProblem : plotProblem).c_str());
  }
  return failed > 0 ? 1 : 0;
}
} // namespace

void bender::AddSweepCommand(CLI::App& cli)
{
  auto a = std::make_shared<SweepArguments>();
  CLI::App* sweep = AddCommand(cli,
    "sweep",
    "what-if sweep: candidate bends solved by OpenFOAM, locally or on Slurm",
    Details,
    [a] { return RunSweepCommand(*a); });
  SweepOptions& options = a->options;
  CfdCaseOptions& cfd = options.caseOptions;
  sweep->add_option("SURFACE", a->surface, "the vessel surface (LPS mm)")->required();
  sweep->add_option("PLAN", a->plans, "the plan to vary (.bender.json)")->expected(0, 1);
  sweep->add_option("-o,--output", options.output, "the sweep folder (created; reused to resume)")
    ->required()
    ->type_name("SWEEP_DIR");
  sweep->add_option("--vary", a->vary, "fraction=FROM:TO:COUNT or radius=FROM:TO:COUNT")
    ->type_name("NAME=FROM:TO:COUNT");
  sweep->add_option("--plans", a->morePlans, "one candidate per plan, beside the original")
    ->type_name("PLAN ...");
  OneOf(sweep->add_option("--engine", a->engine, "where the cases run"), { "local", "slurm" })
    ->capture_default_str();
  sweep->add_option("--jobs", options.engine.jobs, "local: cases solved at a time")
    ->type_name("N")
    ->check(IntegerIn(1, 256))
    ->capture_default_str();
  sweep->add_option("--processors", cfd.processors, "processors of each case (mpirun -np P)")
    ->type_name("P")
    ->check(IntegerIn(1, 4096))
    ->capture_default_str();
  sweep->add_option("--partition", options.engine.partition, "slurm: sbatch --partition")
    ->type_name("NAME");
  sweep->add_option("--time", options.engine.time, "slurm: sbatch --time of each task")
    ->type_name("LIMIT");
  sweep->add_option("--account", options.engine.account, "slurm: sbatch --account")
    ->type_name("NAME");
  sweep
    ->add_option("--sbatch-arg",
      options.engine.sbatchArgs,
      "slurm: one more sbatch option, passed through (repeat it)")
    ->type_name("ARG")
    ->allow_extra_args(false);
  sweep->add_option("--poll", options.engine.pollSeconds, "slurm: seconds between squeue polls")
    ->type_name("S")
    ->check(NumberIn(0.05, 600))
    ->capture_default_str();
  sweep
    ->add_option("--cell-size",
      cfd.cellSize,
      "cell size at the wall, m, for every candidate (default: the original's)")
    ->type_name("H")
    ->check(NumberIn(0, 1));
  CLI::Option* flowRate =
    sweep->add_option("--flow-rate", cfd.flowRate, "inlet flow rate, m^3/s, of every candidate")
      ->type_name("Q")
      ->check(NumberAbove(0, 1))
      ->capture_default_str();
  sweep
    ->add_option("--velocity",
      cfd.velocity,
      "the original's mean inlet velocity, m/s, instead (its flow is that of every candidate)")
    ->type_name("V")
    ->check(NumberAbove(0))
    ->excludes(flowRate);
  sweep->add_option("--layers", cfd.layers, "prism layers on the wall of each case (0: none)")
    ->type_name("N")
    ->check(IntegerIn(0, 20))
    ->capture_default_str();
  sweep->add_option("--iterations", cfd.iterations, "simpleFoam iteration limit of each case")
    ->type_name("N")
    ->check(IntegerIn(1, 1000000))
    ->capture_default_str();
  sweep->add_flag("--prepare-only", options.prepareOnly, "prepare the cases, solve nothing");
}
