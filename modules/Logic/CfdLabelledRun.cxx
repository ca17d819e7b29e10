#include "CfdLabelledRun.h"

#include "BenderErrors.h"
#include "CfdCase.h"

namespace bender
{

CfdFlowResults RunLabelledCase(const std::string& caseDirectory,
  const std::string& label,
  const std::function<void(const std::string&)>& onLine,
  const ProgressReporter& progress)
{
  progress.Report(label, 0.0);
  CfdRunOptions runOptions;
  runOptions.progress = progress;
  if (onLine)
  {
    runOptions.onLine = [&onLine, &label](const std::string& line) { onLine(label + ": " + line); };
  }
  const CfdRunResult run = RunOpenFoamCase(caseDirectory, runOptions);
  if (!run.flow)
  {
    throw Error(caseDirectory + ": the run mapped no results");
  }
  progress.Report(label, 1.0);
  return *run.flow;
}

} // namespace bender
