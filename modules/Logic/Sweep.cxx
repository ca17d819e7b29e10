#include "Sweep.h"

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "CfdBoundaryConditions.h"
#include "ContentHash.h"
#include "StringUtil.h"
#include "SweepRowResults.h"
#include "WarpPlanIO.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
// Bumped when what a candidate's folder holds changes meaning (old folders are then redone).
constexpr const char* HashVersion = "bender-sweep-candidate 1";

std::string ReadBytes(const std::string& path, const std::string& what)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw InputError(path + ": cannot read the " + what);
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::ordered_json CaseSettings(const CfdCaseOptions& o)
{
  nlohmann::ordered_json outlets = nlohmann::ordered_json::array();
  for (const CfdOutletValue& v : o.outletValues)
  {
    outlets.push_back({ { "name", v.name }, { "value", v.value } });
  }
  return { { "inlet", o.inlet },
    { "flowRate", o.flowRate },
    { "velocity", o.velocity },
    { "inletProfile", CfdInletProfileName(o.inletProfile) },
    { "outlets", CfdOutletConditionName(o.outlets) },
    { "outletValues", outlets },
    { "layers", o.layers },
    { "cellSize", o.cellSize },
    { "viscosity", o.viscosity },
    { "density", o.density },
    { "iterations", o.iterations },
    { "processors", o.processors },
    { "decomposition", o.decomposition },
    { "surfaceName", o.surfaceName } };
}

std::string StepJson(const CfdStep& step)
{
  WarpPlan holder;
  holder.cfdSteps.push_back(step);
  return WarpPlanToJson(holder).dump();
}

void Say(const SweepOptions& options, const std::string& line)
{
  if (options.onLine)
  {
    options.onLine(line);
  }
}

void WriteOrThrow(const std::string& path, const std::string& text)
{
  std::string problem;
  if (!AtomicWriteText(path, text, problem))
  {
    throw InputError(path + ": " + problem);
  }
}

// The plan's Prepare for CFD step (its last), or the default one.
CfdStep PlanStep(const WarpPlan& plan)
{
  return plan.cfdSteps.empty() ? CfdStep{} : plan.cfdSteps.back();
}

Vec3 WireMiddle(const WarpPlan& plan)
{
  if (plan.warps.empty())
  {
    return {};
  }
  const RibbonSpec& r = plan.warps.front().initial;
  return (r.start.position + r.end.position) * 0.5;
}

struct Candidates
{
  std::vector<SweepCandidate> list;
  CfdStep step;
  Vec3 bendPoint;
  std::string parameter;
};

Candidates MakeCandidates(const SweepOptions& options)
{
  Candidates c;
  if (options.plans.empty())
  {
    throw InputError("sweep: no plan (a plan with --vary, or --plans)");
  }
  std::vector<WarpPlan> plans;
  std::vector<std::string> names;
  for (const std::string& path : options.plans)
  {
    plans.push_back(ReadWarpPlan(path));
    names.push_back(fs::path(path).filename().string());
  }
  c.step = PlanStep(plans.front());
  c.bendPoint = WireMiddle(plans.front());
  if (options.vary)
  {
    if (plans.size() != 1)
    {
      throw InputError("sweep: --vary varies one plan, not " + std::to_string(plans.size()));
    }
    c.list = MakeSweepCandidates(plans.front(), names.front(), *options.vary);
    c.parameter = SweepParameterName(options.vary->parameter);
  }
  else
  {
    c.list = MakePlanCandidates(plans, names);
    c.parameter = SweepParameterName(SweepParameter::Plan);
  }
  return c;
}

SweepRow NewRow(const SweepCandidate& candidate, const std::string& hash)
{
  SweepRow row;
  row.id = candidate.id;
  row.parameter = SweepParameterName(candidate.parameter);
  row.value = candidate.value;
  row.planName = candidate.planName;
  row.original = candidate.original;
  row.hash = hash;
  return row;
}

// The row a previous run left for this candidate, when its inputs are the same.
std::optional<SweepRow> PreviousRow(const fs::path& folder, const std::string& hash)
{
  std::error_code ec;
  const fs::path state = folder / "state.json";
  if (!fs::exists(state, ec))
  {
    return std::nullopt;
  }
  try
  {
    SweepRow row = SweepRowFromJson(ReadBytes(state.string(), "state"), state.string());
    if (row.hash == hash)
    {
      return row;
    }
  }
  catch (const InputError&)
  {
  }
  return std::nullopt;
}

void SaveRow(const fs::path& folder, const SweepRow& row)
{
  WriteOrThrow((folder / "state.json").string(), SweepRowToJson(row));
}

std::string SweepJson(const SweepOptions& options,
  const Candidates& candidates,
  const std::vector<SweepRow>& rows)
{
  nlohmann::ordered_json j;
  j["format"] = "bender-sweep";
  j["version"] = 1;
  j["surface"] = fs::absolute(options.surface).string();
  j["plans"] = options.plans;
  j["parameter"] = candidates.parameter;
  j["caseSettings"] = CaseSettings(options.caseOptions);
  j["candidates"] = nlohmann::ordered_json::array();
  for (const SweepRow& row : rows)
  {
    j["candidates"].push_back(
      { { "id", row.id }, { "value", row.value }, { "plan", row.planName }, { "hash", row.hash } });
  }
  return j.dump(2) + "\n";
}
} // namespace

std::string SweepCandidateHash(const std::string& surfaceBytes,
  const SweepCandidate& candidate,
  const CfdStep& step,
  const CfdCaseOptions& caseOptions)
{
  WarpPlan warps = candidate.plan;
  if (candidate.original)
  {
    warps.warps.clear();
  }
  const std::string text = std::string(HashVersion) + "\n" + WarpPlanToJson(warps).dump() + "\n" +
    StepJson(step) + "\n" + CaseSettings(caseOptions).dump() + "\n";
  ContentHash hash;
  hash.Add(surfaceBytes);
  hash.Add(text);
  return hash.Finish();
}

SweepResult RunSweep(const SweepOptions& options)
{
  const Candidates candidates = MakeCandidates(options);
  const fs::path dir = fs::absolute(options.output);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
  {
    throw InputError(options.output + ": cannot create the sweep folder");
  }
  const std::string surfaceBytes = ReadBytes(options.surface, "surface");

  SweepResult result;
  std::vector<SweepRow>& rows = result.rows;
  std::vector<std::size_t> toPrepare;
  std::vector<std::size_t> toSolve;
  for (std::size_t i = 0; i < candidates.list.size(); ++i)
  {
    const SweepCandidate& candidate = candidates.list[i];
    const std::string hash =
      SweepCandidateHash(surfaceBytes, candidate, candidates.step, options.caseOptions);
    const std::optional<SweepRow> previous = PreviousRow(dir / candidate.id, hash);
    if (previous && (previous->state == "solved" || previous->state == "rejected"))
    {
      rows.push_back(*previous);
      ++result.kept;
      continue;
    }
    if (previous && previous->state == "ready" && !options.prepareOnly)
    {
      rows.push_back(*previous);
      toSolve.push_back(i);
      continue;
    }
    rows.push_back(NewRow(candidate, hash));
    toPrepare.push_back(i);
  }
  WriteOrThrow((dir / "sweep.json").string(), SweepJson(options, candidates, rows));
  if (result.kept > 0)
  {
    Say(options,
      "sweep: " + CountOf(result.kept, "candidate") + " finished before with the same inputs");
  }

  auto finish = [&]()
  {
    WriteSweepSummary(rows, candidates.parameter, dir.string(), result, options.plot);
    return result;
  };
  try
  {
    if (!toPrepare.empty())
    {
      SweepBaseOptions baseOptions;
      baseOptions.surfacePath = options.surface;
      baseOptions.step = candidates.step;
      baseOptions.caseOptions = options.caseOptions;
      baseOptions.bendPoint = candidates.bendPoint;
      baseOptions.scratchFolder = (dir / ".original-case").string();
      Say(options, "sweep: preparing the original");
      const SweepBase base = PrepareSweepBase(baseOptions, options.progress);
      for (std::size_t k = 0; k < toPrepare.size(); ++k)
      {
        const std::size_t i = toPrepare[k];
        options.progress.Report("prepare", static_cast<double>(k) / toPrepare.size());
        const fs::path folder = dir / candidates.list[i].id;
        fs::remove_all(folder, ec);
        fs::create_directories(folder, ec);
        SweepRow& row = rows[i];
        PreparedCandidate prepared;
        try
        {
          prepared = PrepareCandidate(
            base, candidates.list[i], (folder / "case").string(), options.progress);
        }
        catch (const InputError& e)
        {
          // A warp that cannot be applied (or a case that cannot be written) is this
          // candidate's problem, not the sweep's.
          prepared.rejected = true;
          prepared.reason = e.what();
        }
        row.measures = prepared.measures;
        row.state = prepared.rejected ? "rejected" : "ready";
        row.reason = prepared.reason;
        SaveRow(folder, row);
        ++result.prepared;
        Say(options,
          row.id + ": " + (prepared.rejected ? "rejected: " + prepared.reason : "prepared"));
        if (!prepared.rejected && !options.prepareOnly)
        {
          toSolve.push_back(i);
        }
      }
      options.progress.Report("prepare", 1.0);
    }
    if (options.prepareOnly || toSolve.empty())
    {
      return finish();
    }

    std::vector<SweepJob> jobs;
    for (std::size_t i : toSolve)
    {
      jobs.push_back({ rows[i].id, (dir / rows[i].id / "case").string() });
    }
    SweepEngineOptions engine = options.engine;
    engine.processors = options.caseOptions.processors;
    engine.workFolder = (dir / "slurm").string();
    engine.onLine = options.onLine;
    engine.progress = options.progress;
    // Each case is recorded as soon as it is solved (a sweep killed outright keeps what was
    // done), and every case once more when the engine returns.
    std::mutex recording;
    std::vector<bool> recorded(jobs.size(), false);
    auto record = [&](std::size_t k, const SweepJobOutcome& outcome)
    {
      std::lock_guard<std::mutex> lock(recording);
      if (recorded[k])
      {
        return;
      }
      SweepRow& row = rows[toSolve[k]];
      row.log = outcome.log;
      row.state = "failed";
      row.reason = outcome.message;
      if (outcome.state == SweepJobOutcome::State::Solved)
      {
        try
        {
          ReadSweepRowResults(jobs[k].caseDirectory, row);
          row.state = "solved";
          row.reason.clear();
          row.solveSeconds = SweepCaseSeconds(jobs[k].caseDirectory);
          ++result.solved;
        }
        catch (const Error& e)
        {
          // Results that cannot be mapped (a diverged field): this candidate failed.
          row.reason = e.what();
        }
      }
      else if (outcome.state == SweepJobOutcome::State::Cancelled)
      {
        // A cancelled case stays prepared: it is solved next time.
        row.state = "ready";
      }
      recorded[k] = true;
      SaveRow(dir / row.id, row);
    };
    engine.onSolved = [&record](std::size_t k, const SweepJobOutcome& outcome)
    {
      try
      {
        record(k, outcome);
      }
      catch (const Error&)
      {
        // Recorded again (or its error thrown) once the engine returns.
      }
    };
    const std::vector<SweepJobOutcome> outcomes = RunSweepJobs(jobs, engine);
    for (std::size_t k = 0; k < jobs.size(); ++k)
    {
      record(k, outcomes[k]);
    }
    options.progress.ThrowIfCancelled("solve");
  }
  catch (const Cancelled&)
  {
    for (SweepRow& row : rows)
    {
      if (row.state == "missing" || row.state == "ready")
      {
        row.reason =
          "cancelled before it was " + std::string(row.state == "ready" ? "solved" : "prepared");
      }
    }
    finish();
    throw;
  }
  return finish();
}

} // namespace bender
