#include "BenderSession.h"

#include "FaultInjection.h"
#include "FileIdentity.h"
#include "RibbonLengthChange.h"
#include "StringUtil.h"
#include "WarpPlanIO.h"
#include <vtkPolyData.h>

#include <exception>
#include <sstream>

// The session's jobs (see SessionJob): Begin... on the session's thread, Finish... commits.

namespace bender
{

std::shared_ptr<SessionJob> BenderSession::NewJob(SessionJob::Kind kind, const std::string& title)
{
  auto job = std::make_shared<SessionJob>();
  job->JobKind = kind;
  job->Title = title;
  return job;
}

bool BenderSession::RunNow(const std::shared_ptr<SessionJob>& job)
{
  if (!job)
  {
    return false;
  }
  job->Run({});
  return this->Finish(*job);
}

std::shared_ptr<SessionJob> BenderSession::BeginLoadSurface(const std::string& path)
{
  if (this->RefuseWhenBusy(DisplayName(path)))
  {
    return nullptr;
  }
  auto job = this->NewJob(SessionJob::Kind::Load, "Reading " + DisplayName(path));
  job->Name = DisplayName(path);
  job->Path = path;
  this->Busy = true;
  return job;
}

std::shared_ptr<SessionJob> BenderSession::BeginRelease()
{
  if (this->State != GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Release: nothing is grabbed");
    return nullptr;
  }
  if (this->RefuseWhenBusy("Release"))
  {
    return nullptr;
  }
  auto job = this->NewJob(SessionJob::Kind::Release, "Committing the warp");
  WarpSpec warp = this->Live;
  if (!SameRibbon(warp.initial, warp.final))
  {
    // The single subdivision rule (ApplyWarp): subdivide iff the warp carries a subdivision.
    if (this->Parameters.subdivide)
    {
      warp.subdivision = SubdivisionSpec{ this->Parameters.subdivisionTolerance,
        this->Parameters.subdivisionMaxPasses };
    }
    job->Plan.warps.push_back(warp);
    // The live preview used the interpolated table; the committed shape is the exact warp,
    // computed on a copy so that the display keeps the live warp meanwhile.
    job->Input = vtkSmartPointer<vtkPolyData>::New();
    job->Input->DeepCopy(this->History.Current());
  }
  job->Name = "release";
  // The level of detail of the result is made in the job too (off the session's thread).
  job->MakeProxy = this->ProxyDrag;
  job->Guard = this->GuardCommits;
  job->GuardRule = this->GuardSpaceInversionRule;
  job->Lumen = this->LumenGuard;
  job->LumenBefore = this->LumenBaselineOf(this->History.Current());
  this->Busy = true;
  return job;
}

std::shared_ptr<SessionJob> BenderSession::BeginReplay(const WarpPlan& plan,
  const std::string& name)
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, name + ": load or segment a surface before replaying");
    return nullptr;
  }
  if (this->RefuseWhenBusy(name))
  {
    return nullptr;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, name + ": release or cancel the grab first");
    return nullptr;
  }
  auto job = this->NewJob(SessionJob::Kind::Replay, "Replaying " + name);
  job->Name = name;
  job->Plan = plan;
  job->Input = vtkSmartPointer<vtkPolyData>::New();
  job->Input->DeepCopy(this->History.Current());
  this->Busy = true;
  return job;
}

std::shared_ptr<SessionJob> BenderSession::BeginLoadPlan(const std::string& path)
{
  WarpPlan plan;
  try
  {
    plan = ReadWarpPlan(path);
  }
  catch (const std::exception& e) // WarpPlanError, and std's (filesystem, bad_alloc): a message
  {
    this->Report(MessageSeverity::Error, e.what());
    return nullptr;
  }
  return this->BeginReplay(plan, DisplayName(path));
}

std::shared_ptr<SessionJob> BenderSession::BeginRecover(const std::string& sessionPath)
{
  if (this->RefuseWhenBusy("Recovery"))
  {
    return nullptr;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->CancelGrab("a session is being recovered");
  }
  auto job = this->NewJob(SessionJob::Kind::Recover, "Recovering the session");
  job->SessionPath = sessionPath;
  job->Name = DisplayName(sessionPath);
  this->Busy = true;
  return job;
}

std::shared_ptr<SessionJob> BenderSession::BeginCheck()
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, "Check: there is no surface");
    return nullptr;
  }
  auto job = this->NewJob(SessionJob::Kind::Check, "Checking");
  job->Name = this->SurfaceName;
  // Copies: the check runs while the window keeps drawing the surface.
  job->Input = vtkSmartPointer<vtkPolyData>::New();
  job->Input->DeepCopy(this->History.Current());
  job->Before = vtkSmartPointer<vtkPolyData>::New();
  job->Before->DeepCopy(this->History.Original());
  return job;
}

std::shared_ptr<SessionJob> BenderSession::BeginExport(const std::string& path,
  const ExportSurfaceOptions& options,
  bool proceedOnProblems,
  bool askOnProblems)
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, DisplayName(path) + ": there is no surface to export");
    return nullptr;
  }
  if (!this->SourcePath.empty() && SameFile(path, this->SourcePath))
  {
    this->Report(MessageSeverity::Error,
      DisplayName(path) + ": refusing to overwrite the input surface; choose another file");
    return nullptr;
  }
  auto job = this->BeginCheck();
  job->JobKind = SessionJob::Kind::Export;
  job->Title = "Checking and exporting";
  job->Name = DisplayName(path);
  job->Path = path;
  job->Options = options;
  job->Options.output = path;
  job->Options.protectedPath = this->SourcePath;
  job->Options.sourceName = this->SurfaceName;
  // Export writes only when the check is clean or the caller accepted its problems.
  job->ProceedOnProblems = proceedOnProblems;
  job->AskOnProblems = askOnProblems;
  return job;
}

bool BenderSession::Finish(SessionJob& job)
{
  const bool changes = job.JobKind == SessionJob::Kind::Load ||
    job.JobKind == SessionJob::Kind::Release || job.JobKind == SessionJob::Kind::Replay ||
    job.JobKind == SessionJob::Kind::Recover;
  if (changes)
  {
    this->Busy = false;
  }
  switch (job.JobKind)
  {
    case SessionJob::Kind::Load:
      return this->FinishLoad(job);
    case SessionJob::Kind::Release:
      return this->FinishRelease(job);
    case SessionJob::Kind::Replay:
      return this->FinishReplay(job);
    case SessionJob::Kind::Recover:
      return this->FinishRecover(job);
    case SessionJob::Kind::Check:
      if (job.Result != SessionJob::Outcome::Done)
      {
        this->Report(job.Result == SessionJob::Outcome::Cancelled ? MessageSeverity::Warning
                                                                  : MessageSeverity::Error,
          "Check: " + job.Problem);
        return false;
      }
      this->Report(job.Report.Clean() ? MessageSeverity::Info : MessageSeverity::Warning,
        job.Report.Clean() ? "Check: no problems found"
                           : "Check: problems found, see the Export panel");
      return true;
    case SessionJob::Kind::Export:
      return this->FinishExport(job);
  }
  return false;
}

void BenderSession::Abandon(SessionJob& job, const std::string& reason)
{
  // The jobs that made the session busy (see Finish).
  if (job.JobKind != SessionJob::Kind::Check && job.JobKind != SessionJob::Kind::Export)
  {
    this->Busy = false;
  }
  this->Report(MessageSeverity::Info, job.Name + ": " + reason);
}

bool BenderSession::FinishLoad(SessionJob& job)
{
  if (job.Result != SessionJob::Outcome::Done)
  {
    const bool cancelled = job.Result == SessionJob::Outcome::Cancelled;
    this->Report(cancelled ? MessageSeverity::Warning : MessageSeverity::Error,
      cancelled ? job.Name + ": reading cancelled, the surface is unchanged" : job.Problem);
    return false;
  }
  if (!this->SetSurface(job.Input, job.Name, AbsolutePath(job.Path)))
  {
    return false;
  }
  // The status line's last word: the numbers in the file are not those shown.
  std::string says, in, read;
  if (job.Stated.frame == "RAS")
  {
    says = "frame RAS";
    in = "RAS ";
    read = "LPS ";
  }
  if (job.Stated.unit == "m")
  {
    says += std::string(says.empty() ? "" : ", ") + "unit m";
    in += "metres";
    read += "millimetres";
  }
  if (!says.empty())
  {
    this->Report(MessageSeverity::Info,
      job.Name + ": the file is in " + std::string(Trim(in)) + " (it says " + says + "); read in " +
        std::string(Trim(read)) + ", as everything in Bender");
  }
  return true;
}

bool BenderSession::FinishRelease(SessionJob& job)
{
  if (job.Result != SessionJob::Outcome::Done)
  {
    const bool cancelled = job.Result == SessionJob::Outcome::Cancelled;
    this->State = GrabState::Idle;
    this->ShowCommitted(nullptr);
    this->SetRibbonInformation(this->Live.initial);
    this->Report(cancelled ? MessageSeverity::Warning : MessageSeverity::Error,
      std::string(cancelled ? "Release cancelled" : "Release failed") +
        ", the warp was not applied: " + job.Problem);
    this->Changed();
    return false;
  }
  if (job.Plan.warps.empty())
  {
    this->State = GrabState::Idle;
    this->ShowCommitted(nullptr);
    this->SetRibbonInformation(this->Live.initial);
    this->Report(MessageSeverity::Info, "Released without moving: no warp recorded");
    this->Changed();
    return true;
  }
  const WarpSpec& warp = job.Plan.warps.front();
  vtkPolyData* result = job.Steps.output;
  // The centerlines before the bend serve every release of the surface (once per grab).
  this->SetLumenBaseline(this->History.Current(), job.LumenBefore);
  if (job.Guard && job.Check.checked && !job.Check.Passed())
  {
    // Held: the grab goes on with the live warp on screen until the user chooses.
    this->Held = HeldCommit{ warp, job.Steps.output, job.Check, job.Proxy };
    this->Report(MessageSeverity::Warning,
      "Commit held: " + job.Check.Summary() + ". Reduce R, cancel (Esc) or keep the warp");
    this->Changed();
    return false;
  }
  this->History.Commit(warp, result);
  FaultPoint("commit");
  this->KeepLumenAfter(warp, job.Check);
  ++this->ChangeCount;
  this->State = GrabState::Released;
  this->ShowCommitted(job.Proxy);
  this->SetRibbonInformation(warp.final);
  std::ostringstream text;
  text << "Warp " << this->History.Position() << " committed";
  if (warp.subdivision)
  {
    text << " (subdivided to " << result->GetNumberOfPolys() << " triangles)";
  }
  // A clean surface may still be a much shorter or longer vessel: said, never silent.
  const std::string lengthNote = RibbonLengthNote(warp);
  if (!lengthNote.empty())
  {
    text << "; " << lengthNote;
  }
  this->Report(lengthNote.empty() ? MessageSeverity::Info : MessageSeverity::Warning, text.str());
  this->Autosave();
  this->Changed();
  return true;
}

bool BenderSession::FinishReplay(SessionJob& job)
{
  if (job.Result != SessionJob::Outcome::Done)
  {
    const bool cancelled = job.Result == SessionJob::Outcome::Cancelled;
    this->Report(cancelled ? MessageSeverity::Warning : MessageSeverity::Error,
      (cancelled ? job.Name + ": replay cancelled (" + job.Problem + ")" : job.Problem) +
        "; nothing was applied");
    return false;
  }
  // All or nothing: every step was computed before any is committed.
  if (this->CommitPlanSteps(job, true))
  {
    ++this->ChangeCount;
  }
  this->State = GrabState::Idle;
  this->ShowCommitted(nullptr);
  this->Report(MessageSeverity::Info,
    "Replayed " + CountOf(job.Plan.warps.size(), "warp") +
      (job.Plan.cfdSteps.empty() ? std::string() : " and Prepare for CFD") + " of " + job.Name);
  this->Autosave();
  this->Changed();
  return true;
}

bool BenderSession::CommitPlanSteps(const SessionJob& job, bool faultPoints)
{
  const std::vector<PlanStepRef> order = PlanOrder(job.Plan);
  for (const PlanStepRef& ref : order)
  {
    if (ref.cfd)
    {
      this->History.Commit(job.Plan.cfdSteps[ref.index], job.Steps.prepared[ref.index].surface);
    }
    else
    {
      this->History.Commit(job.Plan.warps[ref.index], job.Steps.steps[ref.index]);
    }
    if (faultPoints)
    {
      FaultPoint("commit");
    }
  }
  if (!job.Plan.warps.empty())
  {
    this->SetRibbonInformation(job.Plan.warps.back().final);
  }
  return !order.empty();
}

bool BenderSession::FinishRecover(SessionJob& job)
{
  if (job.Result != SessionJob::Outcome::Done)
  {
    this->Report(job.Result == SessionJob::Outcome::Cancelled ? MessageSeverity::Warning
                                                              : MessageSeverity::Error,
      std::string(job.Result == SessionJob::Outcome::Cancelled ? "Recovery cancelled: "
                                                               : "Recovery failed: ") +
        job.Problem);
    return false;
  }
  // Recovering from our own autosave: keep the source copy, it is the only one.
  const bool ownCopy = job.SourcePath == AbsolutePath(this->AutosavePath + ".source.vtp");
  // No autosave until the plan is in: loading the surface would otherwise overwrite the
  // session being recovered with an empty plan.
  const std::string autosavePath = this->AutosavePath;
  this->AutosavePath.clear();
  // The surface keeps the name it had (not the name of the autosave's copy of it).
  const std::string name = job.SurfaceName.empty() ? DisplayName(job.SourcePath) : job.SurfaceName;
  bool recovered = this->SetSurface(job.Input, name, ownCopy ? std::string() : job.SourcePath);
  if (recovered)
  {
    if (this->CommitPlanSteps(job, false))
    {
      ++this->ChangeCount; // recovered steps are in no saved plan
    }
    this->ShowCommitted(nullptr);
  }
  this->AutosavePath = autosavePath;
  if (!recovered)
  {
    return false;
  }
  if (ownCopy)
  {
    this->AutosaveSourcePath = job.SourcePath;
  }
  this->Autosave();
  this->Report(
    MessageSeverity::Info, "Recovered the session: " + CountOf(job.Plan.warps.size(), "warp"));
  this->Changed();
  return true;
}

bool BenderSession::FinishExport(SessionJob& job)
{
  if (job.Result != SessionJob::Outcome::Done)
  {
    const bool cancelled = job.Result == SessionJob::Outcome::Cancelled;
    this->Report(cancelled ? MessageSeverity::Warning : MessageSeverity::Error,
      cancelled ? "Export cancelled, nothing was written" : "Export failed: " + job.Problem);
    return false;
  }
  if (job.Written.empty())
  {
    this->Report(MessageSeverity::Warning,
      job.AskOnProblems ? "Export: the check found problems; write anyway?"
                        : "Export not written: the check found problems");
    return false;
  }
  std::string names;
  for (const std::string& file : job.Written)
  {
    names += (names.empty() ? "" : ", ") + DisplayName(file);
  }
  this->Report(MessageSeverity::Info,
    "Exported " + names + " (frame " + (job.Options.frame == StlFrame::RAS ? "RAS" : "LPS") +
      ", unit " + job.Options.unit + ")");
  return true;
}

} // namespace bender
