#ifndef bender_SweepStudy_h
#define bender_SweepStudy_h

// A sweep in the application (issue 24, "In the application"): a sweep folder read back for
// the Flow panel's sweep view (its rows as the candidates left them, whatever engine ran them,
// finished or not), and a local sweep of the session's bend (the fraction of its warps' motion)
// run through RunSweep.

#include "CfdCase.h"
#include "Progress.h"
#include "Sweep.h"
#include "SweepCandidates.h"
#include "WarpPlan.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <string>
#include <vector>

namespace bender
{

/// A sweep folder as its candidates left it.
struct SweepFolder
{
  std::string folder;    ///< absolute
  std::string parameter; ///< "fraction", "radius", "plan"
  /// One per candidate of sweep.json, in its order: the candidate's state.json when it was
  /// written for the same inputs (the hash), else a row in state "missing" saying why.
  std::vector<SweepRow> rows;
};

/// Reads SWEEP_DIR/sweep.json and each candidate's state.json. Throws InputError, one line
/// naming the file: no sweep.json ("not a sweep folder"), a malformed one.
SweepFolder ReadSweepFolder(const std::string& folder);

/// The case folder of `row` (SWEEP_DIR/<id>/case).
std::string SweepCaseFolder(const SweepFolder& sweep, const SweepRow& row);

/// The original's row (the surface as it is), null when the sweep has none.
const SweepRow* SweepOriginalRow(const std::vector<SweepRow>& rows);

/// The session's bend, as FlowStudyInput takes it (deep copies: the sweep runs on a worker).
struct SessionSweepInput
{
  vtkSmartPointer<vtkPolyData> first; ///< the surface before any step of `plan`
  WarpPlan plan;                      ///< the committed warps and Prepare for CFD steps
  std::string name = "the surface";   ///< in messages
};

struct SessionSweepOptions
{
  /// SWEEP_DIR: an empty or missing folder, or a sweep folder (then resumed: what is finished
  /// with the same inputs is kept).
  std::string folder;
  SweepVary vary; ///< of the fraction
  CfdCaseOptions caseOptions;
  int jobs = 1; ///< cases solved at a time
  std::function<void(const std::string&)> onLine;
  /// RunSweep's stages and cancel flag.
  ProgressReporter progress;
};

/// Writes the session's surface and plan into SWEEP_DIR/input (surface.vtp, plan.bender.json)
/// and runs the local sweep of the fraction on them (RunSweep) without drawing summary.png: the
/// window draws it on its own thread (SweepOptions::plot). Throws InputError (a plan
/// without a warp, a folder that holds something else than a sweep, RunSweep's), RunSweep's
/// EnvironmentError and Cancelled (after the summary is written).
SweepResult RunSessionSweep(const SessionSweepInput& input, const SessionSweepOptions& options);

} // namespace bender

#endif
