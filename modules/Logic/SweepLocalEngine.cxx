// The local engine of a sweep: a bounded pool of `jobs` workers on this machine, each running
// one case's Allrun at a time (RunOpenFoamCase, which stops it on the cancel flag).

#include "SweepEngines.h"

#include "BenderErrors.h"
#include "CfdCase.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>
#include <thread>

namespace bender
{

std::vector<SweepJobOutcome> RunLocalJobs(const std::vector<SweepJob>& jobs,
  const SweepEngineOptions& options)
{
  if (const std::string problem = FindOpenFoamProblem(options.processors); !problem.empty())
  {
    throw EnvironmentError(problem);
  }
  std::vector<SweepJobOutcome> outcomes(jobs.size());
  std::atomic<std::size_t> next{ 0 };
  std::size_t ended = 0;
  std::mutex report;
  auto say = [&](const std::string& line)
  {
    if (options.onLine)
    {
      options.onLine(line);
    }
  };
  auto worker = [&]()
  {
    for (std::size_t i; (i = next++) < jobs.size();)
    {
      SweepJobOutcome& outcome = outcomes[i];
      outcome.log = (std::filesystem::path(jobs[i].caseDirectory) / "log.Allrun").string();
      outcome.attempts = 1;
      if (options.progress.Cancelled())
      {
        outcome.state = SweepJobOutcome::State::Cancelled;
        outcome.message = "cancelled before it started";
        continue;
      }
      {
        std::lock_guard<std::mutex> lock(report);
        say(jobs[i].id + ": solving");
      }
      CfdRunOptions run;
      run.progress.cancel = options.progress.cancel;
      try
      {
        RunOpenFoamCase(jobs[i].caseDirectory, run);
        outcome.state = SweepJobOutcome::State::Solved;
      }
      catch (const Cancelled& e)
      {
        outcome.state = SweepJobOutcome::State::Cancelled;
        outcome.message = e.what();
      }
      catch (const Error& e)
      {
        outcome.state = SweepJobOutcome::State::Failed;
        outcome.message = e.what();
      }
      if (outcome.state == SweepJobOutcome::State::Solved && options.onSolved)
      {
        options.onSolved(i, outcome);
      }
      std::lock_guard<std::mutex> lock(report);
      ++ended;
      say(jobs[i].id + ": " +
        (outcome.state == SweepJobOutcome::State::Solved ? std::string("solved")
                                                         : outcome.message));
      options.progress.Report("solve", static_cast<double>(ended) / jobs.size());
    }
  };
  const std::size_t workers =
    std::min<std::size_t>(jobs.size(), static_cast<std::size_t>(std::max(1, options.jobs)));
  std::vector<std::thread> pool;
  for (std::size_t w = 0; w < workers; ++w)
  {
    pool.emplace_back(worker);
  }
  for (std::thread& t : pool)
  {
    t.join();
  }
  return outcomes;
}

std::vector<SweepJobOutcome> RunSweepJobs(const std::vector<SweepJob>& jobs,
  const SweepEngineOptions& options)
{
  if (jobs.empty())
  {
    return {};
  }
  return options.kind == SweepEngineKind::Slurm ? RunSlurmJobs(jobs, options)
                                                : RunLocalJobs(jobs, options);
}

} // namespace bender
