#ifndef bender_CfdLabelledRun_h
#define bender_CfdLabelledRun_h

// One of several cases of a study run in turn (the meshes of a convergence study, the
// verification tubes): RunOpenFoamCase with its progress lines prefixed by the case's label and
// the label reported as a stage, returning the mapped results.

#include "CfdFlowResults.h"
#include "Progress.h"

#include <functional>
#include <string>

namespace bender
{

/// Runs the written case in `caseDirectory` (RunOpenFoamCase, steps All); each Allrun line goes
/// to onLine (when set) as "label: line"; progress gets (label, 0) and (label, 1) and its cancel
/// flag stops the run. Throws what RunOpenFoamCase throws, Error when no results were mapped.
CfdFlowResults RunLabelledCase(const std::string& caseDirectory,
  const std::string& label,
  const std::function<void(const std::string&)>& onLine,
  const ProgressReporter& progress);

} // namespace bender

#endif
