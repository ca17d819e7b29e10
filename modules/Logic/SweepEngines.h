#ifndef bender_SweepEngines_h
#define bender_SweepEngines_h

// The engines that solve a sweep's cases (issue 24): each case folder holds a complete
// OpenFOAM case written by WriteOpenFoamCase, run by its Allrun.
//  - local: a bounded pool on this machine (`jobs` cases at a time, each with the processors
//    its case was written for);
//  - slurm: one sbatch array job, one task per case, each running the case's Allrun inside its
//    allocation (mpirun -np P in the allocation when the case has P > 1 processors); followed
//    through squeue (and sacct where accounting is on); a failed task is submitted once more,
//    then reported with its log. The case folders must be on a filesystem every node shares.

#include "Progress.h"

#include <functional>
#include <string>
#include <vector>

namespace bender
{

/// One case to solve.
struct SweepJob
{
  std::string id;            ///< the candidate ("c03")
  std::string caseDirectory; ///< absolute
};

/// How a case's run ended.
struct SweepJobOutcome
{
  enum class State
  {
    Solved,   ///< Allrun succeeded
    Failed,   ///< Allrun (or the task) failed; message and log say why
    Cancelled ///< stopped by the caller (Ctrl+C) or a cancelled Slurm job
  };
  State state = State::Failed;
  std::string message; ///< one line
  std::string log;     ///< the log to read (log.Allrun, the Slurm task's output)
  int attempts = 0;
};

enum class SweepEngineKind
{
  Local,
  Slurm
};

/// Options of the engines.
struct SweepEngineOptions
{
  SweepEngineKind kind = SweepEngineKind::Local;
  int jobs = 1;       ///< local: cases at a time, [1, 256]
  int processors = 1; ///< per case (as written in the cases); Slurm: --ntasks of each task
  std::string partition, time, account; ///< sbatch's, passed through when set
  std::vector<std::string> sbatchArgs;  ///< more sbatch options, passed through as given
  double pollSeconds = 2.0;             ///< squeue polling interval
  int retries = 1;                      ///< Slurm: a failed task is submitted again this often
  /// Where the engine keeps its files (the Slurm script, task outputs): inside the sweep.
  std::string workFolder;
  /// Lines for the user ("slurm: job 42 submitted, 7 tasks").
  std::function<void(const std::string&)> onLine;
  /// Called as soon as job `index` is solved (from the engine's thread; Slurm: once its task
  /// ended well), so that the caller records it before the others end.
  std::function<void(std::size_t index, const SweepJobOutcome& outcome)> onSolved;
  /// "solve" with the fraction of cases ended; its cancel flag stops the runs (local: the
  /// Allruns; Slurm: scancel of the job).
  ProgressReporter progress;
};

/// Solves `jobs` (outcomes in the same order). Never throws for a case that fails (its outcome
/// says so); throws EnvironmentError when the engine cannot start at all (OpenFOAM or sbatch
/// missing, sbatch refusing the job), naming the program and its message.
std::vector<SweepJobOutcome> RunSweepJobs(const std::vector<SweepJob>& jobs,
  const SweepEngineOptions& options);

/// The engines' share: local and Slurm.
std::vector<SweepJobOutcome> RunLocalJobs(const std::vector<SweepJob>& jobs,
  const SweepEngineOptions& options);
std::vector<SweepJobOutcome> RunSlurmJobs(const std::vector<SweepJob>& jobs,
  const SweepEngineOptions& options);

/// The file system type of `folder` ("nfs", "lustre", "ext4", "tmpfs", ...; "unknown").
std::string FileSystemType(const std::string& folder);

} // namespace bender

#endif
