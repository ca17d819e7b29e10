#include "SessionJob.h"

#include "BenderErrors.h"
#include "LevelOfDetail.h"
#include "MeshIO.h"
#include "SessionAutosave.h"

#include <exception>

namespace bender
{

void SessionJob::Run(const ProgressReporter& progress)
{
  try
  {
    switch (this->JobKind)
    {
      case Kind::Load:
        this->Input = ReadMesh(this->Path, this->Stated);
        break;
      case Kind::Recover:
      {
        const SessionSnapshot snapshot = ReadSessionFile(this->SessionPath);
        this->SourcePath = snapshot.sourcePath;
        this->SurfaceName = snapshot.surfaceName;
        this->Plan = snapshot.plan;
        try
        {
          this->Input = ReadMesh(snapshot.sourcePath);
        }
        catch (const MeshIOError& e)
        {
          throw InputError(std::string("the session's source cannot be read: ") + e.what());
        }
        progress.ThrowIfCancelled("recovery");
      }
        [[fallthrough]];
      case Kind::Release:
      case Kind::Replay:
        if (!this->Plan.warps.empty() || !this->Plan.cfdSteps.empty())
        {
          ApplyPlanOptions options;
          options.planName = this->Name;
          options.progress = progress;
          this->Steps = ApplyPlan(this->Input, this->Plan, options);
          if (this->JobKind == Kind::Release && this->Guard)
          {
            // The guard compares cell by cell: the warp without subdivision.
            const WarpSpec& warp = this->Plan.warps.front();
            vtkSmartPointer<vtkPolyData> same = this->Steps.output;
            if (warp.subdivision)
            {
              WarpSpec plain = warp;
              plain.subdivision.reset();
              same = ApplyWarp(this->Input, plain, options);
            }
            progress.ThrowIfCancelled("commit check");
            // The rule R < r_min alone does not hold a commit: it is sufficient for safety, not a
            // sign of damage; the surface itself is measured (flips, crossings). The risk stays
            // in the check and in the warning shown while bending.
            CommitCheckOptions options;
            options.spaceInversionRule = this->GuardRule;
            options.lumen = this->Lumen;
            if (this->Lumen.enabled && !this->LumenBefore)
            {
              progress.Report("centerlines before the bend", 0.0);
              this->LumenBefore =
                std::make_shared<const CenterlineResult>(LumenCenterlines(this->Input));
              progress.ThrowIfCancelled("commit check");
            }
            this->Check = CheckCommit(this->Input, same, warp, options, this->LumenBefore.get());
          }
          if (this->JobKind == Kind::Release && this->MakeProxy)
          {
            progress.ThrowIfCancelled("level of detail");
            this->Proxy = MakeLevelOfDetail(this->Steps.output);
          }
        }
        break;
      case Kind::Check:
        this->Report = CheckForExport(this->Input, this->Before);
        break;
      case Kind::Export:
        this->Report = CheckForExport(this->Input, this->Before);
        progress.ThrowIfCancelled("check");
        if (this->Report.Clean() || this->ProceedOnProblems)
        {
          this->Written = ExportSurface(this->Input, this->Options).written;
        }
        break;
    }
    this->Result = Outcome::Done;
  }
  catch (const Cancelled& e)
  {
    this->Result = Outcome::Cancelled;
    this->Problem = e.what();
  }
  catch (const std::exception& e) // the workflows' errors, VTK's and std's: Run never throws
  {
    this->Result = Outcome::Failed;
    this->Problem = e.what();
  }
}

} // namespace bender
