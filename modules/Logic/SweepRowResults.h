#ifndef bender_SweepRowResults_h
#define bender_SweepRowResults_h

// A sweep row filled from its solved case, and the summary files written from the rows
// (Sweep.h).

#include "Sweep.h"

#include <string>
#include <vector>

namespace bender
{

/// Fills `row` from the solved case in `caseDirectory` (CfdFlowResults.h: CASE/results/flow.json,
/// mapped here by MapCfdResults when the run did not map it, as a Slurm task does not): each
/// outlet's split and pressure drop, iterations and convergence, mesh cells, the wall shear
/// stress statistics. Throws InputError / Error as MapCfdResults and ReadCfdFlowResults do.
void ReadSweepRowResults(const std::string& caseDirectory, SweepRow& row);

/// The wall-clock seconds OpenFOAM's programs report in the case's logs (mesh and solve), 0
/// when none is readable.
double SweepCaseSeconds(const std::string& caseDirectory);

/// Writes SWEEP_DIR/summary.csv, summary.json and (where a display is, and `plot`) summary.png;
/// sets the paths (and plotProblem) in `result`. Throws InputError when a summary cannot be
/// written.
void WriteSweepSummary(const std::vector<SweepRow>& rows,
  const std::string& parameter,
  const std::string& folder,
  SweepResult& result,
  bool plot = true);

} // namespace bender

#endif
