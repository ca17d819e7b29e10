#include "SweepStudy.h"

#include "BenderErrors.h"
#include "MeshIO.h"
#include "WarpPlanIO.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
std::string ReadText(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The row of a candidate whose state.json is missing or of other inputs.
SweepRow MissingRow(const nlohmann::json& candidate,
  const std::string& parameter,
  const std::string& reason)
{
  SweepRow row;
  row.id = candidate.at("id").get<std::string>();
  row.parameter = parameter;
  row.value = candidate.at("value").get<double>();
  row.planName = candidate.at("plan").get<std::string>();
  row.hash = candidate.at("hash").get<std::string>();
  row.original = row.id == "original" || (parameter == "fraction" && row.value == 0.0);
  row.state = "missing";
  row.reason = reason;
  return row;
}

SweepRow CandidateRow(const fs::path& dir,
  const nlohmann::json& candidate,
  const std::string& parameter)
{
  const fs::path state = dir / candidate.at("id").get<std::string>() / "state.json";
  std::error_code ec;
  if (!fs::exists(state, ec))
  {
    return MissingRow(candidate, parameter, "not prepared yet");
  }
  SweepRow row;
  try
  {
    row = SweepRowFromJson(ReadText(state), state.string());
  }
  catch (const InputError& e)
  {
    return MissingRow(candidate, parameter, e.what());
  }
  if (row.hash != candidate.at("hash").get<std::string>())
  {
    return MissingRow(
      candidate, parameter, "its results are of other inputs (run the sweep again)");
  }
  if (row.state == "ready" && row.reason.empty())
  {
    row.reason = "prepared, not solved yet";
  }
  return row;
}
} // namespace

SweepFolder ReadSweepFolder(const std::string& folder)
{
  SweepFolder sweep;
  const fs::path dir = fs::absolute(folder);
  sweep.folder = dir.string();
  const fs::path file = dir / "sweep.json";
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
  {
    throw InputError(folder + ": not a sweep folder (no sweep.json)");
  }
  const nlohmann::json j = nlohmann::json::parse(ReadText(file), nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("format", "") != "bender-sweep")
  {
    throw InputError(file.string() + ": not a Bender sweep (malformed JSON or another format)");
  }
  try
  {
    sweep.parameter = j.at("parameter").get<std::string>();
    for (const nlohmann::json& candidate : j.at("candidates"))
    {
      sweep.rows.push_back(CandidateRow(dir, candidate, sweep.parameter));
    }
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(file.string() + ": " + e.what());
  }
  return sweep;
}

std::string SweepCaseFolder(const SweepFolder& sweep, const SweepRow& row)
{
  return (fs::path(sweep.folder) / row.id / "case").string();
}

const SweepRow* SweepOriginalRow(const std::vector<SweepRow>& rows)
{
  for (const SweepRow& row : rows)
  {
    if (row.original)
    {
      return &row;
    }
  }
  return nullptr;
}

SweepResult RunSessionSweep(const SessionSweepInput& input, const SessionSweepOptions& options)
{
  if (!input.first || input.plan.warps.empty())
  {
    throw InputError(input.name + ": no bend to sweep (bend the vessel first)");
  }
  const fs::path dir = fs::absolute(options.folder);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec) && !fs::exists(dir / "sweep.json", ec))
  {
    throw InputError(options.folder + ": holds other files and no sweep (choose an empty folder)");
  }
  const fs::path inputs = dir / "input";
  fs::create_directories(inputs, ec);
  if (!fs::is_directory(inputs, ec))
  {
    throw InputError(options.folder + ": cannot create the sweep folder");
  }
  SweepOptions sweep;
  sweep.surface = (inputs / "surface.vtp").string();
  sweep.plans = { (inputs / "plan.bender.json").string() };
  WriteMesh(input.first, sweep.surface);
  WriteWarpPlan(input.plan, sweep.plans.front());
  sweep.vary = options.vary;
  sweep.vary->parameter = SweepParameter::Fraction;
  sweep.output = dir.string();
  sweep.caseOptions = options.caseOptions;
  sweep.engine.kind = SweepEngineKind::Local;
  sweep.engine.jobs = options.jobs;
  sweep.plot = false;
  sweep.onLine = options.onLine;
  sweep.progress = options.progress;
  return RunSweep(sweep);
}

} // namespace bender
