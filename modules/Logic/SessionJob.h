#ifndef bender_SessionJob_h
#define bender_SessionJob_h

#include "ApplyPlan.h"
#include "BenderMeshCheck.h"
#include "CommitGuard.h"
#include "ExportSurface.h"
#include "MeshUnit.h"
#include "Progress.h"
#include "WarpPlan.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <memory>
#include <string>
#include <vector>

namespace bender
{

class BenderSession;

/// Long work of a session (load, release, replay, recovery, check, export) as a job that runs off
/// the session's thread: BenderSession::Begin... makes it on the session's thread (inputs copied,
/// the session refuses other changes meanwhile), Run computes on any thread (only the job's own
/// data), BenderSession::Finish commits it on the session's thread. Synchronous callers use the
/// plain operations (Release, ReplayPlan, ...), which do the three steps at once.
class SessionJob
{
public:
  enum class Kind
  {
    Load,
    Release,
    Replay,
    Recover,
    Check,
    Export
  };
  enum class Outcome
  {
    Pending,
    Done,
    Failed,
    Cancelled
  };

  Kind GetKind() const { return this->JobKind; }
  /// What the job is doing, for a progress bar ("Committing the warp", ...).
  const std::string& GetTitle() const { return this->Title; }
  /// Computes; never throws: the outcome and the problem are kept for Finish. Cancellation is
  /// the typed bender::Cancelled of the workflows, seen here as Outcome::Cancelled.
  void Run(const ProgressReporter& progress);
  Outcome GetOutcome() const { return this->Result; }
  const std::string& GetProblem() const { return this->Problem; }
  /// The check's report (Check jobs, and Export jobs once run).
  const MeshCheckReport& GetReport() const { return this->Report; }
  /// Export jobs: the files written (none when the check found problems and the caller did
  /// not accept them).
  const std::vector<std::string>& GetWrittenFiles() const { return this->Written; }
  /// Release jobs with the commit guard on: the check of the changed region (CheckCommit).
  const CommitCheck& GetCommitCheck() const { return this->Check; }

private:
  friend class BenderSession;
  Kind JobKind = Kind::Release;
  std::string Title;
  std::string Name; // plan or file name for messages
  WarpPlan Plan;
  vtkSmartPointer<vtkPolyData> Input;  // a copy owned by the job
  vtkSmartPointer<vtkPolyData> Before; // the surface before the warps (check)
  std::string SessionPath;             // Recover
  std::string SourcePath;              // Recover: the source read by the job
  std::string SurfaceName;             // Recover: the surface's name in the session file
  std::string Path;                    // Load: the mesh read; Export: the file written
  StatedSpace Stated;                  // Load: the unit and frame the file states (ReadMesh)
  ExportSurfaceOptions Options;
  bool ProceedOnProblems = false;
  bool AskOnProblems = false; // Export: the caller asks the user when the check finds problems
  bool MakeProxy = false;     // Release: decimate the result for the level of detail
  bool Guard = false;         // Release: check the changed region before committing
  bool GuardRule = false;     // ... and hold on the space-inversion rule alone
  LumenGuardOptions Lumen{ false, 0.05 }; // ... and measure the lumen (LumenGuard.h)
  // The centerlines of Input for the lumen guard: given when known (computed once per grab),
  // else computed by the job and kept by the session for the next release of the grab.
  std::shared_ptr<const CenterlineResult> LumenBefore;
  CommitCheck Check;
  ApplyPlanResult Steps;
  vtkSmartPointer<vtkPolyData> Proxy; // Release of a big surface: the result's decimated copy
  MeshCheckReport Report;
  std::vector<std::string> Written;
  Outcome Result = Outcome::Pending;
  std::string Problem;
};

} // namespace bender

#endif
