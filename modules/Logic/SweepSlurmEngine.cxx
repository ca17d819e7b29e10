// The Slurm engine of a sweep: one sbatch array job (one task per case, each running the case's
// Allrun inside its allocation), followed through squeue; a task that fails is submitted once
// more (options.retries), then reported with its log. Every file a task needs or writes is in
// the sweep folder, which the nodes must share: each task first looks for a token the
// submitting process wrote there and says so when it does not see it.

#include "SweepEngines.h"

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "ProcessRunner.h"
#include "StringUtil.h"

#include <sys/vfs.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;

namespace bender
{

std::string FileSystemType(const std::string& folder)
{
  struct statfs info
  {
  };
  if (statfs(folder.c_str(), &info) != 0)
  {
    return "unknown";
  }
  static const std::map<long, const char*> names = { { 0x6969, "nfs" },
    { 0x0BD00BD0, "lustre" },
    { 0x47504653, "gpfs" },
    { 0x19830326, "beegfs" },
    { 0xFF534D42, "cifs" },
    { 0xFE534D42, "smb2" },
    { 0x65735546, "fuse" },
    { 0x01021994, "tmpfs" },
    { 0xEF53, "ext4" },
    { 0x58465342, "xfs" },
    { 0x9123683E, "btrfs" },
    { 0x794C7630, "overlay" },
    { 0x2FC12FC1, "zfs" },
    { 0x00C36400, "ceph" } };
  const auto it = names.find(static_cast<long>(info.f_type) & 0xFFFFFFFFL);
  return it == names.end() ? "unknown" : it->second;
}

namespace
{
std::string Trimmed(const std::string& text)
{
  return std::string(Trim(text));
}

std::string ReadText(const fs::path& path)
{
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs a Slurm client; its output lines. Throws EnvironmentError naming it when it cannot run
// or fails (with its last line) unless `mayFail`.
std::vector<std::string> Client(const std::vector<std::string>& argv,
  bool mayFail = false,
  bool* failed = nullptr)
{
  std::vector<std::string> lines;
  ProcessOptions run;
  run.argv = argv;
  run.timeoutSeconds = 120;
  run.onLine = [&lines](const std::string& line) { lines.push_back(line); };
  const ProcessResult result = RunProcess(run);
  if (failed)
  {
    *failed = !result.Succeeded();
  }
  if (!result.Succeeded() && !mayFail)
  {
    throw EnvironmentError(argv[0] + " failed: " +
      (result.lastLine.empty() ? std::string("exit status ") + std::to_string(result.exitCode)
                               : result.lastLine));
  }
  return lines;
}

std::string ArrayList(const std::vector<std::size_t>& indices)
{
  std::string list;
  for (std::size_t i : indices)
  {
    list += (list.empty() ? "" : ",") + std::to_string(i);
  }
  return list;
}

// The batch script: checks the shared folder, runs the case's Allrun (its output in the case's
// log.Allrun, as the local engine leaves it, and in the task's output), leaves its exit status.
std::string BatchScript(const fs::path& work)
{
  const std::string w = work.string();
  return "#!/bin/sh\n"
         "# Written by Bender (bender-cli sweep --engine slurm): one array task per case.\n"
         "work='" +
    w +
    "'\n"
    "if [ ! -f \"$work/shared-check\" ]; then\n"
    "    echo \"bender sweep: $work is not visible on $(hostname): the sweep folder must be on "
    "a filesystem every node shares\" >&2\n"
    "    exit 3\nfi\n"
    "case=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" \"$work/cases.txt\")\n"
    "echo \"bender sweep: task $SLURM_ARRAY_TASK_ID on $(hostname) (${SLURM_NTASKS:-1} tasks): "
    "$case\"\n"
    "sh \"$case/Allrun\" > \"$case/log.Allrun\" 2>&1\n"
    "status=$?\n"
    "cat \"$case/log.Allrun\"\n"
    "echo \"$status\" > \"$work/status/$SLURM_ARRAY_JOB_ID.$SLURM_ARRAY_TASK_ID\"\n"
    "exit $status\n";
}

struct Submission
{
  std::string jobId;
  std::vector<std::size_t> indices;
};

Submission Submit(const fs::path& work,
  const std::vector<std::size_t>& indices,
  const SweepEngineOptions& options)
{
  std::vector<std::string> argv = { "sbatch",
    "--parsable",
    "--job-name=bender-sweep",
    "--array=" + ArrayList(indices),
    "--output=" + (work / "task-%A.%a.out").string(),
    "--ntasks=" + std::to_string(std::max(1, options.processors)) };
  if (!options.partition.empty())
  {
    argv.push_back("--partition=" + options.partition);
  }
  if (!options.time.empty())
  {
    argv.push_back("--time=" + options.time);
  }
  if (!options.account.empty())
  {
    argv.push_back("--account=" + options.account);
  }
  argv.insert(argv.end(), options.sbatchArgs.begin(), options.sbatchArgs.end());
  argv.push_back((work / "sweep.sbatch").string());
  const std::vector<std::string> lines = Client(argv);
  Submission submission;
  submission.indices = indices;
  for (const std::string& line : lines)
  {
    const std::string id = Trimmed(line.substr(0, line.find(';')));
    if (!id.empty() && id.find_first_not_of("0123456789") == std::string::npos)
    {
      submission.jobId = id;
    }
  }
  if (submission.jobId.empty())
  {
    throw EnvironmentError(
      "sbatch gave no job id" + (lines.empty() ? std::string() : ": " + lines.back()));
  }
  return submission;
}

// The tasks of the job squeue still lists (pending or running), by index, with their state;
// nothing when squeue could not answer (the controller busy or restarting: ask again), with
// its last line in `problem`. A job squeue no longer knows has ended.
std::optional<std::map<std::size_t, std::string>> Queued(const std::string& jobId,
  std::string& problem)
{
  bool failed = false;
  const std::vector<std::string> lines =
    Client({ "squeue", "-h", "-r", "-j", jobId, "-o", "%i %T" }, true, &failed);
  std::map<std::size_t, std::string> queued;
  if (failed)
  {
    problem = lines.empty() ? std::string("squeue failed") : lines.back();
    if (problem.find("Invalid job id") == std::string::npos)
    {
      return std::nullopt;
    }
    return queued;
  }
  for (const std::string& line : lines)
  {
    const auto under = line.find('_');
    const auto space = line.find(' ');
    if (under == std::string::npos || space == std::string::npos || space < under)
    {
      continue;
    }
    const std::string index = line.substr(under + 1, space - under - 1);
    if (!index.empty() && index.find_first_not_of("0123456789") == std::string::npos)
    {
      queued[std::stoul(index)] = line.substr(space + 1);
    }
  }
  return queued;
}

// What sacct says of a task ("CANCELLED by 0", "TIMEOUT"); empty where accounting is off.
std::string AccountedState(const std::string& jobId, std::size_t index)
{
  if (FindExecutable("sacct").empty())
  {
    return {};
  }
  bool failed = false;
  const std::vector<std::string> lines =
    Client({ "sacct", "-n", "-P", "-X", "-j", jobId + "_" + std::to_string(index), "-o", "State" },
      true,
      &failed);
  return failed || lines.empty() ? std::string() : Trimmed(lines.front());
}

// How task `index` of `jobId` ended, from its status file, its output and sacct.
SweepJobOutcome Ended(const fs::path& work,
  const std::string& jobId,
  std::size_t index,
  const SweepJob& job)
{
  SweepJobOutcome outcome;
  const fs::path status = work / "status" / (jobId + "." + std::to_string(index));
  const fs::path output = work / ("task-" + jobId + "." + std::to_string(index) + ".out");
  outcome.log = output.string();
  std::error_code ec;
  if (fs::exists(status, ec))
  {
    const std::string code = Trimmed(ReadText(status));
    if (code == "0")
    {
      outcome.state = SweepJobOutcome::State::Solved;
      return outcome;
    }
    outcome.state = SweepJobOutcome::State::Failed;
    outcome.log = (fs::path(job.caseDirectory) / "log.Allrun").string();
    const std::string text = ReadText(outcome.log);
    const std::size_t failedAt = text.find(" failed, see ");
    const std::size_t at =
      failedAt == std::string::npos ? failedAt : text.rfind("bender Allrun: ", failedAt);
    outcome.message = "Allrun failed (exit " + code + ")" +
      (at == std::string::npos ? std::string()
                               : ": " + Trimmed(text.substr(at, text.find('\n', at) - at)));
    return outcome;
  }
  const std::string accounted = AccountedState(jobId, index);
  const std::string printed = ReadText(output);
  outcome.state = SweepJobOutcome::State::Failed;
  if (StartsWith(accounted, "CANCELLED") || printed.find("CANCELLED") != std::string::npos)
  {
    outcome.state = SweepJobOutcome::State::Cancelled;
    outcome.message = "the Slurm task was cancelled";
  }
  else if (!fs::exists(output, ec))
  {
    outcome.message = "the Slurm task left nothing in " + work.string() +
      ": the sweep folder must be on a filesystem every node shares" +
      (accounted.empty() ? std::string() : " (task " + accounted + ")");
  }
  else if (printed.find("is not visible on") != std::string::npos)
  {
    outcome.message = "the node does not see the sweep folder: it must be on a filesystem "
                      "every node shares";
  }
  else
  {
    outcome.message = "the Slurm task ended without finishing" +
      (accounted.empty() ? std::string() : " (" + accounted + ")");
  }
  return outcome;
}

// Waits one polling interval.
void Pause(const SweepEngineOptions& options)
{
  std::this_thread::sleep_for(
    std::chrono::milliseconds(static_cast<long>(std::max(0.05, options.pollSeconds) * 1000.0)));
}

// Follows one submission until none of its tasks is queued; the outcome of each.
std::map<std::size_t, SweepJobOutcome> Follow(const fs::path& work,
  const Submission& submission,
  const std::vector<SweepJob>& jobs,
  std::size_t& ended,
  const SweepEngineOptions& options)
{
  std::map<std::size_t, SweepJobOutcome> outcomes;
  std::string lastLine;
  while (true)
  {
    if (options.progress.Cancelled())
    {
      Client({ "scancel", submission.jobId }, true);
      for (std::size_t index : submission.indices)
      {
        if (!outcomes.count(index))
        {
          outcomes[index].state = SweepJobOutcome::State::Cancelled;
          outcomes[index].message = "cancelled (scancel " + submission.jobId + ")";
        }
      }
      return outcomes;
    }
    std::string problem;
    const auto answer = Queued(submission.jobId, problem);
    if (!answer)
    {
      const std::string line = "slurm: squeue did not answer (" + problem + "), asking again";
      if (options.onLine && line != lastLine)
      {
        options.onLine(line);
        lastLine = line;
      }
      Pause(options);
      continue;
    }
    const std::map<std::size_t, std::string>& queued = *answer;
    std::size_t running = 0;
    for (std::size_t index : submission.indices)
    {
      const auto it = queued.find(index);
      const bool done = it == queued.end() || it->second == "COMPLETED" || it->second == "FAILED" ||
        it->second == "CANCELLED" || it->second == "TIMEOUT";
      running += it != queued.end() && it->second == "RUNNING";
      if (done && !outcomes.count(index))
      {
        outcomes[index] = Ended(work, submission.jobId, index, jobs[index]);
        if (outcomes[index].state == SweepJobOutcome::State::Solved && options.onSolved)
        {
          options.onSolved(index, outcomes[index]);
        }
        ++ended;
        if (options.onLine)
        {
          const SweepJobOutcome& o = outcomes[index];
          options.onLine(jobs[index].id + ": " +
            (o.state == SweepJobOutcome::State::Solved ? std::string("solved") : o.message));
        }
        options.progress.Report("solve", static_cast<double>(ended) / jobs.size());
      }
    }
    const std::string line = "slurm: job " + submission.jobId + ": " + std::to_string(ended) +
      " of " + std::to_string(jobs.size()) + " ended, " + std::to_string(running) + " running, " +
      std::to_string(submission.indices.size() - outcomes.size() - running) + " pending";
    if (options.onLine && line != lastLine)
    {
      options.onLine(line);
      lastLine = line;
    }
    if (outcomes.size() == submission.indices.size())
    {
      return outcomes;
    }
    Pause(options);
  }
}
} // namespace

std::vector<SweepJobOutcome> RunSlurmJobs(const std::vector<SweepJob>& jobs,
  const SweepEngineOptions& options)
{
  for (const char* client : { "sbatch", "squeue", "scancel" })
  {
    if (FindExecutable(client).empty())
    {
      throw EnvironmentError(std::string("--engine slurm: ") + client +
        " is not on PATH (Slurm's client commands; Debian: apt-get install slurm-client)");
    }
  }
  const fs::path work = fs::absolute(options.workFolder);
  std::error_code ec;
  fs::create_directories(work / "status", ec);
  std::string problem;
  std::string cases;
  for (const SweepJob& job : jobs)
  {
    cases += fs::absolute(job.caseDirectory).string() + "\n";
  }
  std::random_device random;
  if (!AtomicWriteText((work / "cases.txt").string(), cases, problem) ||
    !AtomicWriteText((work / "sweep.sbatch").string(), BatchScript(work), problem) ||
    !AtomicWriteText((work / "shared-check").string(), std::to_string(random()) + "\n", problem))
  {
    throw EnvironmentError(work.string() + ": " + problem);
  }
  if (options.onLine)
  {
    options.onLine("slurm: the sweep folder " + work.parent_path().string() + " is on " +
      FileSystemType(work.string()) +
      ": every node must see it at the same path (a shared filesystem)");
  }

  std::vector<SweepJobOutcome> outcomes(jobs.size());
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < jobs.size(); ++i)
  {
    pending.push_back(i);
  }
  std::size_t ended = 0;
  for (int attempt = 1; !pending.empty() && attempt <= 1 + std::max(0, options.retries); ++attempt)
  {
    const Submission submission = Submit(work, pending, options);
    if (options.onLine)
    {
      options.onLine("slurm: job " + submission.jobId + " submitted, " +
        CountOf(pending.size(), "task") + (attempt > 1 ? " (second try)" : ""));
    }
    const auto followed = Follow(work, submission, jobs, ended, options);
    std::vector<std::size_t> failed;
    for (const auto& [index, outcome] : followed)
    {
      outcomes[index] = outcome;
      outcomes[index].attempts = attempt;
      if (outcome.state == SweepJobOutcome::State::Failed)
      {
        failed.push_back(index);
      }
    }
    if (options.progress.Cancelled())
    {
      break;
    }
    ended -= failed.size();
    pending = failed;
  }
  return outcomes;
}

} // namespace bender
