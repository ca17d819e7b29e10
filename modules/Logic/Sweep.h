#ifndef bender_Sweep_h
#define bender_Sweep_h

// What-if sweeps (issue 24): many candidate bends of one surface, each warped exactly, checked,
// prepared for CFD as the original and solved by OpenFOAM with the original's settings, on
// this machine or a Slurm cluster; one table (summary.csv, summary.json) and one plot
// (summary.png) of the results against the varied parameter.
//
// The sweep folder SWEEP_DIR:
//   sweep.json              the sweep: surface, plans, what varies, the case settings, candidates
//   <id>/state.json         one candidate's state and row (written last, atomically)
//   <id>/case/              its OpenFOAM case (bender-cli cfd-case's layout)
//   slurm/                  the Slurm engine's script and task outputs
//   summary.csv, summary.json, summary.png
// Resumable: each candidate carries a content hash of its inputs (the surface's bytes, its
// warps, the Prepare for CFD step, the case settings); running the same sweep again keeps the
// candidates solved (or rejected) with the same hash, solves those prepared but not solved,
// and prepares again the failed, cancelled, missing and changed ones (their folder replaced
// whole, so that results of different inputs never mix).

#include "CfdCase.h"
#include "Progress.h"
#include "SweepCandidates.h"
#include "SweepEngines.h"
#include "SweepPrepare.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace bender
{

/// Options of RunSweep.
struct SweepOptions
{
  std::string surface; ///< the vessel surface (any mesh format Bender reads), LPS mm
  /// With `vary`: one plan; without: one candidate per plan (--plans).
  std::vector<std::string> plans;
  std::optional<SweepVary> vary;
  std::string output; ///< SWEEP_DIR; created when missing
  /// The case settings of every candidate (caseDirectory and force are set per candidate; a
  /// cell size and flow rate left at 0 are resolved once, on the original).
  CfdCaseOptions caseOptions;
  /// The engine (local or Slurm); its onLine and progress are RunSweep's.
  SweepEngineOptions engine;
  /// Only prepare the candidates (warp, check, clip, cases); solve nothing.
  bool prepareOnly = false;
  /// Draw summary.png. Off: the caller draws it (WriteSweepPlot) on its own thread, as a window
  /// must (VTK's text rendering is not safe on two threads at once).
  bool plot = true;
  /// Lines for the user ("c02: solved").
  std::function<void(const std::string&)> onLine;
  /// Stages "prepare" and "solve"; its cancel flag (Ctrl+C) stops the sweep with the folder
  /// consistent (RunSweep then throws Cancelled after writing the summary).
  ProgressReporter progress;
};

/// One outlet's flow in a row.
struct SweepOutlet
{
  std::string name;
  double splitPercent = 0.0; ///< of the inlet's flow
  double pressureDrop = 0.0; ///< inlet - this outlet, Pa
  double flowRate = 0.0;     ///< ml/min
};

/// One row of the summary: a candidate, its state and its numbers (NaN where not known).
struct SweepRow
{
  std::string id;
  std::string parameter; ///< "fraction", "radius", "plan"
  double value = 0.0;
  std::string planName;
  bool original = false;
  /// "solved", "rejected" (folds or self-intersects: not solved), "failed", "ready" (prepared,
  /// not solved), "cancelled", "missing" (never prepared).
  std::string state = "missing";
  std::string reason; ///< why not solved (one line)
  std::string log;    ///< the log to read when failed
  std::string hash;   ///< of its inputs
  SweepMeasures measures;
  double pressureDrop = 0.0; ///< inlet - the outlets' flow-weighted mean pressure, Pa
  std::vector<SweepOutlet> outlets;
  /// Wall shear stress (CfdFlowResults): area-weighted mean, max, 99th percentile (Pa), wall
  /// area below 0.4 Pa and above 15 Pa (mm^2).
  double wssMean = 0.0, wssMax = 0.0, wssP99 = 0.0, lowWssArea = 0.0, highWssArea = 0.0;
  bool wallShearStress = false; ///< the WSS numbers are there
  long long meshCells = 0;
  int iterations = 0;
  bool converged = false;
  double solveSeconds = 0.0; ///< wall time of its run (mesh and solve)
};

/// What RunSweep did.
struct SweepResult
{
  std::vector<SweepRow> rows; ///< every candidate, in the sweep's order
  std::size_t prepared = 0;   ///< candidates prepared in this run
  std::size_t solved = 0;     ///< solved in this run
  std::size_t kept = 0;       ///< finished before and unchanged: not run again
  std::string summaryCsv, summaryJson, summaryPng;
  std::string plotProblem; ///< why summary.png was not drawn (no display), empty when drawn
};

/// Runs the sweep. Throws InputError (unreadable surface or plan, a bad combination of plans
/// and vary, an unwritable SWEEP_DIR, an original that cannot be prepared), EnvironmentError
/// (OpenFOAM or Slurm missing), Cancelled (after writing the summary).
SweepResult RunSweep(const SweepOptions& options);

/// The content hash (ContentHash.h) of a candidate's inputs.
std::string SweepCandidateHash(const std::string& surfaceBytes,
  const SweepCandidate& candidate,
  const CfdStep& step,
  const CfdCaseOptions& caseOptions);

/// The summary of the rows: CSV (a header line, then one line per row) and JSON
/// ("bender-sweep-summary", version 1: parameter, rows, missing with their reasons).
std::string SweepSummaryCsv(const std::vector<SweepRow>& rows);
std::string SweepSummaryJson(const std::vector<SweepRow>& rows, const std::string& parameter);

/// The row as JSON (state.json) and back. Throws InputError naming `source` for a malformed one.
std::string SweepRowToJson(const SweepRow& row);
SweepRow SweepRowFromJson(const std::string& text, const std::string& source);

/// summary.png: the pressure drop, each outlet's split and the low-WSS area against the varied
/// value (VTK charts; the original drawn as a dashed line across). Needs a display (DISPLAY;
/// bender-cli starts a private Xvfb). Throws EnvironmentError without one, InputError when the
/// PNG cannot be written.
void WriteSweepPlot(const std::vector<SweepRow>& rows,
  const std::string& parameter,
  const std::string& path);

} // namespace bender

#endif
