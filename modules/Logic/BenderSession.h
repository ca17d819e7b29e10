#ifndef bender_BenderSession_h
#define bender_BenderSession_h

#include "ApplyPlan.h"
#include "BenderMeshCheck.h"
#include "CommitGuard.h"
#include "ExportSurface.h"
#include "LevelOfDetail.h"
#include "LogicMessage.h"
#include "Progress.h"
#include "SessionJob.h"
#include "TwistUnwrapper.h"
#include "WarpHistory.h"
#include "WarpPlan.h"

#include "vtkBenderWarpFilter.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

class vtkAlgorithmOutput;

namespace bender
{

struct SessionSnapshot;

/// Where the session is in the bend gesture.
enum class GrabState
{
  Idle,    ///< nothing held (no warp yet, or after undo/cancel)
  Grabbed, ///< the initial ribbon is captured and bound; the surface follows the final ribbon
  Released ///< the last gesture was committed as a warp; a new grab may start
};

/// The parameters of the next warp, set from the Bend panel.
struct WarpParameters
{
  double radius = 10.0; ///< R, model units, > 0
  DecaySpec decay;
  bool reverseScrews = false;
  /// Adaptive subdivision at release (spec 7); tolerance in model units, > 0.
  bool subdivide = false;
  double subdivisionTolerance = 0.05;
  int subdivisionMaxPasses = 8;
};

/// The application state of Bender without Qt: the loaded surface, the grab / release state
/// machine that drives vtkBenderWarpFilter (Precision Table while dragging, Exact at release),
/// the undo history of committed warps, the plan, autosave and recovery, checks and export.
///
/// Every public operation returns false (or nothing) on failure and never throws: the problem
/// is added to Messages() as one sentence naming the input, and the callback set with
/// SetMessageCallback is called. Coordinates are those of the surface (LPS mm for segmented
/// vessels). Not thread-safe: call from one thread. Long work (release, replay, recovery,
/// check, export) is also offered as a SessionJob whose Run goes on a worker thread; every
/// warp is applied through the ApplyPlan workflow (ApplyPlan.h).
///
/// The live warp is a VTK pipeline connected once: the committed surface (History.Current())
/// is the input of a vtkBenderWarpFilter (Table precision) whose output port GetOutputPort()
/// a mapper connects to. Idle, the filter passes the surface through (no copy); grabbed, each
/// move builds the RibbonWarp once (validation included) and hands it to the filter.
///
/// Level of detail: a second pipeline, GetProxyOutputPort(), gives a decimated copy of the
/// committed surface (vtkQuadricClustering, made when first asked for, once per surface
/// version; after a release the job makes it off the session's thread) through its own warp
/// filter. A grab on a surface of more than GetLevelOfDetailThreshold() triangles binds the
/// copy and every move warps the copy alone (IsDraggingProxy()); the full surface's filter
/// is handed the same warp but computes only when its output is asked for (GetDisplaySurface,
/// a visible mapper). The release commits the exact warp of the full surface as always.
class BenderSession
{
public:
  BenderSession();
  ~BenderSession();
  BenderSession(const BenderSession&) = delete;
  BenderSession& operator=(const BenderSession&) = delete;

  ///@{ Data
  /// Reads a mesh (stl, obj, ply, vtp, vtk, off) and makes it the session's surface, dropping
  /// the history. On failure the previous surface stays. The load job (BeginLoadSurface) at
  /// once.
  bool LoadSurface(const std::string& path);
  /// Makes `surface` (deep-copied) the session's surface. `name` is for messages;
  /// `sourcePath` is the file it came from, empty for a surface made here (segmentation).
  bool SetSurface(vtkPolyData* surface,
    const std::string& name,
    const std::string& sourcePath = {});
  /// Forgets the surface and all that belongs to it (the grab, a held commit, the history and
  /// its plan, the ribbon): another patient's data comes next. Says so in one message ending
  /// in `reason`; refused (false, with a message) while busy. The autosave file is the
  /// caller's (DiscardAutosave).
  bool Clear(const std::string& reason);
  bool HasSurface() const { return !this->History.Empty(); }
  /// The committed surface (after the current history step); owned by the session.
  vtkPolyData* GetSurface() const { return this->History.Current(); }
  /// The surface the committed one is compared with (flips, the ghost, the vessels before and
  /// after): the one before the warps, after the last Prepare for CFD step if any (a new start:
  /// other points and cells).
  vtkPolyData* GetOriginalSurface() const { return this->History.Original(); }
  /// The surface before any step of the plan (what GetPlan() applies to).
  vtkPolyData* GetFirstSurface() const { return this->History.First(); }
  /// The part of the original surface that the surface shown may differ from (what a ghost of
  /// the original needs to draw: elsewhere the two coincide): the original's triangles with a
  /// point that the committed surface moved, or that the current grab binds (a drag can move
  /// it). Shares the original's points; the same object while neither changes (no re-upload
  /// per frame). Null when the whole original is needed: no surface, a committed surface of
  /// other points or cells (subdivided), or a drag of the decimated copy.
  vtkPolyData* GetOriginalInPlay();
  /// The live pipeline's output for rendering, connected once: the committed surface
  /// (History.Current(), passed through without a copy) through vtkBenderWarpFilter, which
  /// warps it live while grabbed. Connect a mapper to it; no Modified() is needed.
  vtkAlgorithmOutput* GetOutputPort() const;
  /// The same output, brought up to date (for tests and headless use).
  vtkPolyData* GetDisplaySurface() const;
  /// The live warp filter (read-only use: counters for tests and benchmarks).
  vtkBenderWarpFilter* GetLiveFilter() const { return this->LiveFilter.GetPointer(); }
  /// How many RibbonWarp objects the session built for the live warp (one per grab, per
  /// accepted or refused move, per change of R while grabbed): for tests.
  long long GetWarpBuildCount() const { return this->WarpBuildCount; }
  const std::string& GetSourcePath() const { return this->SourcePath; }
  const std::string& GetSurfaceName() const { return this->SurfaceName; }
  ///@}

  ///@{ Warp parameters (take effect at the next grab; radius and decay also while grabbed)
  bool SetParameters(const WarpParameters& parameters);
  const WarpParameters& GetParameters() const { return this->Parameters; }
  ///@}

  ///@{ The gesture
  GrabState GetState() const { return this->State; }
  /// Captures `initial` (extraTurns set to 0) and binds the surface. Refused for an invalid
  /// ribbon (spec convention 11), without a surface, or while already grabbed.
  bool Grab(const RibbonSpec& initial);
  /// Moves the final ribbon (twist unwrapped, convention 4) and warps the display surface live
  /// (Precision Table). An invalid ribbon or warp is not applied: the last valid one stays and
  /// GetLiveProblem() says why (no message per move). Returns whether it was applied.
  bool MoveFinal(const RibbonSpec& final);
  /// Commits the last valid final ribbon: exact warp (or adaptive subdivision when enabled),
  /// a new undo step, the plan grows, autosave. A release without motion records nothing.
  /// With the commit guard on (the default) the changed region is checked first (see
  /// CheckCommit); when it fails the commit is held: nothing is committed, the grab goes on
  /// (the live warp stays on screen), IsCommitHeld() is true and GetHeldCheck() says what
  /// failed and where, until KeepHeldCommit(), CancelGrab(), a move or a change of R.
  bool Release();
  ///@{ The commit guard
  void SetCommitGuard(bool on) { this->GuardCommits = on; }
  /// Also hold a commit on the space-inversion rule alone (R >= r_min, no flipped or crossing
  /// triangle measured). Off by default: the rule is sufficient for safety, not a sign of
  /// damage; its warning is shown while bending.
  void SetCommitGuardRule(bool on) { this->GuardSpaceInversionRule = on; }
  bool GetCommitGuard() const { return this->GuardCommits; }
  bool GetCommitGuardRule() const { return this->GuardSpaceInversionRule; }
  bool IsCommitHeld() const { return this->Held.has_value(); }
  /// The lumen guard of the commit guard (LumenGuard.h): a release whose warp narrows a branch
  /// it moved by more than options.maxNarrowing is held like a fold. Off by default (the
  /// window turns it on): it computes the centerlines after the bend at every release.
  void SetLumenGuard(const LumenGuardOptions& options) { this->LumenGuard = options; }
  const LumenGuardOptions& GetLumenGuard() const { return this->LumenGuard; }
  /// The centerlines of `surface` (the committed surface) for the lumen guard, when known
  /// elsewhere (the window's vessel job); else the first release of a grab computes them and
  /// later releases of the same surface reuse them. Null `centerlines` forgets them.
  void SetLumenBaseline(vtkPolyData* surface, std::shared_ptr<const CenterlineResult> centerlines);
  /// The centerlines kept for `surface`; null when none or kept for another surface.
  std::shared_ptr<const CenterlineResult> LumenBaselineOf(vtkPolyData* surface) const;
  /// The failed check of the held commit (an unchecked, empty one when none is held).
  const CommitCheck& GetHeldCheck() const;
  /// Commits the held warp as it is (the user chose to keep it).
  bool KeepHeldCommit();
  ///@}
  /// Abandons the live warp (device failure, Escape): the committed surface stays.
  void CancelGrab(const std::string& reason);
  /// The ribbon placed on the surface by the user (the window's ribbon widget, a tracker
  /// alignment), while not grabbed: it becomes the session's ribbon and its r_min and the
  /// space-inversion warning are recomputed for it (the previous warning is cleared). False,
  /// with a message, for an invalid ribbon or while grabbed.
  bool PlaceRibbon(const RibbonSpec& ribbon);
  /// The ribbon lying on the committed surface: the one placed, the final ribbon after a
  /// release or a redo, the initial one after a cancel or an undo; none after a new surface.
  const std::optional<RibbonSpec>& GetRibbon() const { return this->CurrentRibbon; }
  const RibbonSpec& GetInitialRibbon() const { return this->Live.initial; }
  const RibbonSpec& GetFinalRibbon() const { return this->Live.final; }
  /// Why the last MoveFinal was not applied; empty when it was.
  const std::string& GetLiveProblem() const { return this->LiveProblem; }
  /// Live information for the Bend panel: r_min of the initial wire, the space-inversion risk
  /// (R >= r_min of either wire) and whether the screws flipped (paper 3.8 toggle).
  double GetInitialMinimumRadius() const { return this->InitialMinimumRadius; }
  /// The one r_min shown to the user (panel, status bar, commit guard): the smaller of the
  /// initial and the final wire's while grabbed, the placed ribbon's otherwise; infinite for
  /// a straight wire or no ribbon. GetSpaceInversionWarning() quotes this value.
  double GetMinimumRadius() const { return this->MinimumRadius; }
  bool GetSpaceInversionRisk() const { return this->SpaceInversionRisk; }
  bool GetFlipOccurred() const { return this->FlipOccurred; }
  /// The sentence describing the space-inversion risk of the live warp; empty when none.
  const std::string& GetSpaceInversionWarning() const { return this->InversionWarning; }
  /// Points inside the region of influence of the current grab (of the decimated copy while
  /// IsDraggingProxy()).
  long long GetNumberOfBoundPoints() const;
  ///@}

  ///@{ Level of detail while dragging big surfaces
  /// Surfaces with more triangles than this are dragged as a decimated copy; default 500000
  /// (the view's rotation threshold). Takes effect at the next grab.
  void SetLevelOfDetailThreshold(long long triangles) { this->LodThreshold = triangles; }
  long long GetLevelOfDetailThreshold() const { return this->LodThreshold; }
  /// The decimated copy of the committed surface, warped live while IsDraggingProxy() and
  /// passed through otherwise. Connected once, like GetOutputPort(); computed only when pulled.
  vtkAlgorithmOutput* GetProxyOutputPort() const;
  /// The same output, brought up to date (tests).
  vtkPolyData* GetProxySurface() const;
  /// True while grabbed with the decimated copy (a big surface, no commit held): moves warp
  /// the copy, the full surface is warped at release (or when its output is pulled).
  bool IsDraggingProxy() const
  {
    return this->State == GrabState::Grabbed && this->ProxyDrag && !this->Held;
  }
  /// How many decimated copies were made (on this thread or in release jobs): for tests.
  long long GetProxyBuildCount() const;
  ///@}

  ///@{ History (exact coordinates restored)
  bool CanUndo() const { return this->State != GrabState::Grabbed && this->History.CanUndo(); }
  bool CanRedo() const { return this->State != GrabState::Grabbed && this->History.CanRedo(); }
  bool Undo();
  bool Redo();
  /// Steps up to the current one (warps and Prepare for CFD steps).
  std::size_t GetHistoryPosition() const { return this->History.Position(); }
  /// Commits a Prepare for CFD step as one undo step: `result` (deep-copied) is what
  /// ApplyCfdStep made of GetSurface(), or, with `replacesCurrent`, of GetPreviousSurface()
  /// when the committed surface is itself prepared (Prepare pressed again: the new step takes
  /// the current one's place). The step is saved in the plan (GetPlan) and replayed by it.
  bool CommitCfdStep(const CfdStep& step, vtkPolyData* result, bool replacesCurrent);
  /// The Prepare for CFD step that made the committed surface; null when it is a warp's or
  /// the first surface.
  const CfdStep* GetCurrentCfdStep() const
  {
    return this->History.CfdStepOf(this->History.Position());
  }
  /// The surface before the current history step; null at the first (or let go, see below).
  vtkPolyData* GetPreviousSurface() const { return this->History.Previous(); }
  /// The bytes the history's surfaces take, and their limit: past it the oldest steps'
  /// surfaces are let go and cannot be undone (WarpHistory); the plan keeps every step.
  std::size_t GetHistoryBytes() const { return this->History.MemoryBytes(); }
  void SetHistoryMemoryLimit(std::size_t bytes) { this->History.SetMemoryLimit(bytes); }
  ///@}

  ///@{ Unsaved work
  /// True while a grab is under way or the committed warps changed (commit, undo, redo,
  /// replay) since the surface was loaded, the plan saved or MarkSaved() was called.
  bool HasUnsavedChanges() const;
  /// The work counts as saved (or explicitly discarded) from now on.
  void MarkSaved() { this->SavedChangeCount = this->ChangeCount; }
  ///@}

  ///@{ Plan
  /// The committed steps (up to the current history step): warps and Prepare for CFD steps.
  WarpPlan GetPlan() const;
  bool SavePlan(const std::string& path);
  /// Reads a plan and replays it onto the current surface (all warps or none).
  bool LoadPlan(const std::string& path);
  /// Applies every step of `plan` in order (warps and Prepare for CFD steps), each as one undo
  /// step; all or nothing.
  bool ReplayPlan(const WarpPlan& plan, const std::string& name);
  /// True when the last committed steps are exactly `plan`'s (the plan was applied already:
  /// loading it again would bend the bent surface once more).
  bool IsPlanApplied(const WarpPlan& plan) const;
  /// Applies one warp (exact, with its subdivision if any) as one undo step.
  bool ApplyWarp(const WarpSpec& warp);
  ///@}

  ///@{ Jobs (see SessionJob): nullptr, with a message, when refused (busy, nothing grabbed,
  ///    no surface). While a job is begun and not finished, the session refuses other changes.
  /// Reads the mesh at `path` in the job; Finish makes it the surface (SetSurface, named after
  /// the file, its absolute path as the source).
  std::shared_ptr<SessionJob> BeginLoadSurface(const std::string& path);
  std::shared_ptr<SessionJob> BeginRelease();
  std::shared_ptr<SessionJob> BeginReplay(const WarpPlan& plan, const std::string& name);
  /// Reads the plan file in the job.
  std::shared_ptr<SessionJob> BeginLoadPlan(const std::string& path);
  std::shared_ptr<SessionJob> BeginRecover(const std::string& sessionPath);
  std::shared_ptr<SessionJob> BeginCheck();
  /// Checks, then writes when the check is clean or `proceedOnProblems`. `askOnProblems`: the
  /// caller asks the user whether to write anyway when the check finds problems, so Finish
  /// says the problems were found and claims no result (the caller reports the answer's).
  std::shared_ptr<SessionJob> BeginExport(const std::string& path,
    const ExportSurfaceOptions& options,
    bool proceedOnProblems,
    bool askOnProblems = false);
  /// Commits a job that ran (or reports why not); returns whether it succeeded.
  bool Finish(SessionJob& job);
  /// Drops a job that ran instead of finishing it (the user declined its result, e.g. a mesh
  /// read and then not opened): nothing changes, the session is no longer busy, and one
  /// message says "<the job's file or plan>: `reason`".
  void Abandon(SessionJob& job, const std::string& reason);
  bool IsBusy() const { return this->Busy; }
  ///@}

  ///@{ Check and export
  /// The report shown before writing (see CheckForExport).
  MeshCheckReport CheckSurface() const;
  /// Writes the committed surface (atomic). Refuses to overwrite the source file.
  /// Written through the export workflow (ExportSurface); `options.output` is set to `path`.
  bool Export(const std::string& path, const ExportSurfaceOptions& options = {});
  ///@}

  ///@{ Autosave and recovery
  /// Where to autosave (empty: off). Saved after each change of the surface or the history.
  void SetAutosavePath(const std::string& path);
  const std::string& GetAutosavePath() const { return this->AutosavePath; }
  bool Autosave();
  /// Adds what the session does not hold (the window: volume, segmentation parameters,
  /// ribbon, Bend parameters) to every autosave, just before it is written. Null (default):
  /// nothing added.
  void SetAutosaveDecorator(std::function<void(SessionSnapshot&)> decorator)
  {
    this->AutosaveDecorator = std::move(decorator);
  }
  /// True when the ribbon lying on the surface is not the one the last autosave kept (placed,
  /// or put back by undo, cancel or redo: no warp, so no autosave of its own) and an autosave
  /// would keep it now (an autosave path, a surface, not busy, not grabbed).
  bool HasUnsavedRibbon() const;
  /// Autosaves when HasUnsavedRibbon(); true when nothing was to be done. Not on every move of
  /// a handle (each autosave is flushed to disk): the window calls it once the ribbon rests.
  bool AutosaveRibbon();
  /// Removes the autosave files (a clean exit).
  void DiscardAutosave();
  /// Loads the source of a session file and replays its plan.
  bool Recover(const std::string& sessionPath);
  ///@}

  ///@{ Messages for the GUI
  const std::vector<LogicMessage>& GetMessages() const { return this->Messages; }
  void ClearMessages() { this->Messages.clear(); }
  void SetMessageCallback(std::function<void(const LogicMessage&)> callback);
  /// Called after the display surface, state or history changed.
  void SetChangeCallback(std::function<void()> callback);
  /// Adds a message from a collaborator (tracker session, GUI worker results).
  void AddMessage(MessageSeverity severity, const std::string& text)
  {
    this->Report(severity, text);
  }
  ///@}

private:
  void Report(MessageSeverity severity, const std::string& text);
  void Changed();
  bool RefuseWhenBusy(const std::string& what);
  std::shared_ptr<SessionJob> NewJob(SessionJob::Kind kind, const std::string& title);
  bool RunNow(const std::shared_ptr<SessionJob>& job);
  bool FinishLoad(SessionJob& job);
  bool FinishRelease(SessionJob& job);
  bool FinishReplay(SessionJob& job);
  /// Commits the steps a replay or recovery job computed, each as one undo step (with
  /// `faultPoints`, FaultPoint("commit") after each); false when the plan has none.
  bool CommitPlanSteps(const SessionJob& job, bool faultPoints);
  bool FinishRecover(SessionJob& job);
  bool FinishExport(SessionJob& job);
  bool SetLiveWarp(const WarpSpec& warp, std::string& problem);
  /// Whether the next grab of the committed surface drags the decimated copy.
  bool WantsProxy() const;
  void UpdateLiveInformation();
  /// The live filters' input: `surface`, or an empty one before any is loaded (a view
  /// connected to the output port may render first; without an input VTK reports an error).
  static vtkSmartPointer<vtkPolyData> InputOrEmpty(vtkPolyData* surface);
  void SetRibbonInformation(const std::optional<RibbonSpec>& ribbon);
  void DropHeld();
  /// After a commit: the lumen guard's centerlines after the bend are those of the committed
  /// surface (unless subdivided), the next bend's "before".
  void KeepLumenAfter(const WarpSpec& warp, const CommitCheck& check);

  struct HeldCommit
  {
    WarpSpec warp;
    vtkSmartPointer<vtkPolyData> result;
    CommitCheck check;
    vtkSmartPointer<vtkPolyData> proxy; // the result's decimated copy (big surfaces)
  };
  /// The committed surface is shown (the live warps pass it through); `proxy`, when given, is
  /// its decimated copy made by a job.
  void ShowCommitted(vtkPolyData* proxy);

  WarpHistory History;
  WarpParameters Parameters;
  GrabState State = GrabState::Idle;
  WarpSpec Live;
  TwistUnwrapper Unwrapper;
  std::string LiveProblem;
  double InitialMinimumRadius = 0.0;
  bool SpaceInversionRisk = false;
  bool FlipOccurred = false;
  bool WarnedInversion = false;
  std::string InversionWarning;
  double MinimumRadius = std::numeric_limits<double>::infinity();
  std::optional<RibbonSpec> CurrentRibbon;
  bool GuardCommits = true;
  bool GuardSpaceInversionRule = false;
  std::optional<HeldCommit> Held;
  LumenGuardOptions LumenGuard{ false, 0.05 };
  std::shared_ptr<const CenterlineResult> LumenBaseline;
  vtkPolyData* LumenBaselineSurface = nullptr; // the surface it was computed for, and when
  vtkMTimeType LumenBaselineTime = 0;
  unsigned long long ChangeCount = 0;
  unsigned long long SavedChangeCount = 0;

  vtkNew<vtkBenderWarpFilter> LiveFilter;
  // GetOriginalInPlay's result and what it was made from.
  struct InPlayKey
  {
    vtkPolyData* original = nullptr;
    vtkPolyData* current = nullptr;
    vtkMTimeType originalTime = 0;
    vtkMTimeType currentTime = 0;
    vtkIdType binding = -1; // LiveFilter's binding count while grabbed, -1 otherwise
    bool operator==(const InPlayKey& o) const
    {
      return original == o.original && current == o.current && originalTime == o.originalTime &&
        currentTime == o.currentTime && binding == o.binding;
    }
  };
  InPlayKey InPlayMadeFrom;
  vtkSmartPointer<vtkPolyData> InPlay;
  std::shared_ptr<const RibbonWarp> LiveWarp;
  // The level of detail: committed surface -> decimated copy (made once per version) -> warp.
  vtkNew<vtkBenderLevelOfDetailSource> ProxySource;
  vtkNew<vtkBenderWarpFilter> ProxyFilter;
  long long LodThreshold = 500000;
  bool ProxyDrag = false;
  long long ProxyJobBuilds = 0;
  long long WarpBuildCount = 0;
  bool Busy = false;

  std::string SourcePath;
  std::string SurfaceName;
  std::string AutosavePath;
  std::string AutosaveSourcePath;
  std::optional<RibbonSpec> AutosavedRibbon; // the ribbon when the last autosave was written
  std::function<void(SessionSnapshot&)> AutosaveDecorator;

  std::vector<LogicMessage> Messages;
  std::function<void(const LogicMessage&)> MessageCallback;
  std::function<void()> ChangeCallback;
};

} // namespace bender

#endif
