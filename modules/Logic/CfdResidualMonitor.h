#ifndef bender_CfdResidualMonitor_h
#define bender_CfdResidualMonitor_h

// The solver's iterations as they come: simpleFoam's solverInfo function object writes a line
// per iteration (postProcessing/solverInfo/<start time>/solverInfo.dat, flushed per line); a
// monitor follows that file on its own thread while the case runs and hands each new
// iteration's initial residuals to a callback (the Flow panel's live plot, the job's progress).

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace bender
{

/// One iteration of the solver.
struct CfdIteration
{
  int iteration = 0;
  /// Initial residuals by field ("Ux", "Uy", "Uz", "p"), as solverInfo's "<field>_initial"
  /// columns name them, in column order.
  std::vector<std::pair<std::string, double>> residuals;
};

/// The iterations of `solverInfoText` (the whole text of a solverInfo.dat, or what is written
/// of it so far): whole lines only; rows that are incomplete or not numbers are left out.
std::vector<CfdIteration> ParseSolverInfo(const std::string& solverInfoText);

/// Follows a case folder's solverInfo.dat (the latest start time's) while the case runs:
/// every `intervalMs` on its own thread, and once more at Stop(). The callback is called on the
/// monitor's thread, once per new iteration, in order. A file that appears later (the mesh is
/// made first) or is replaced (the case re-run) is followed from its start.
class CfdResidualMonitor
{
public:
  CfdResidualMonitor(std::string caseDirectory,
    std::function<void(const CfdIteration&)> onIteration,
    int intervalMs = 250);
  /// Stops (see Stop).
  ~CfdResidualMonitor();
  CfdResidualMonitor(const CfdResidualMonitor&) = delete;
  CfdResidualMonitor& operator=(const CfdResidualMonitor&) = delete;

  /// Reads what is new one last time and ends the thread; no callback after it returns.
  void Stop();
  /// Iterations reported so far.
  int Count() const { return this->Reported; }

private:
  void Loop();
  void Poll();

  std::string CaseDirectory;
  std::function<void(const CfdIteration&)> OnIteration;
  int IntervalMs;
  std::string File;       // the file followed
  int LastIteration = -1; // the last of its iterations reported
  std::atomic<int> Reported{ 0 };
  std::mutex Mutex;
  std::condition_variable Wake;
  bool Stopping = false;
  std::thread Thread;
};

} // namespace bender

#endif
