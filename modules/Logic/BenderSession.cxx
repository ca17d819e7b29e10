#include "BenderSession.h"

#include "FileIdentity.h"
#include "MeshIO.h"
#include "SessionAutosave.h"
#include "StringUtil.h"
#include "WarpPlanIO.h"
#include <vtkAlgorithmOutput.h>
#include <vtkPolyData.h>

#include <exception>
#include <filesystem>
#include <sstream>
#include <system_error>

// The session's data, messages, plan and autosave. The gesture and the history are in
// BenderSessionGesture.cxx, the jobs in BenderSessionJobs.cxx.

namespace bender
{

vtkSmartPointer<vtkPolyData> BenderSession::InputOrEmpty(vtkPolyData* surface)
{
  return surface ? vtkSmartPointer<vtkPolyData>(surface) : vtkSmartPointer<vtkPolyData>::New();
}

BenderSession::BenderSession()
{
  this->LiveFilter->SetPrecision(WarpPrecision::Table);
  this->LiveFilter->PassThroughOn();
  this->LiveFilter->SetInputData(InputOrEmpty(nullptr));
  this->ProxySource->SetInputData(InputOrEmpty(nullptr));
  this->ProxyFilter->SetPrecision(WarpPrecision::Table);
  this->ProxyFilter->PassThroughOn();
  this->ProxyFilter->SetInputConnection(this->ProxySource->GetOutputPort());
}

BenderSession::~BenderSession() = default;

vtkAlgorithmOutput* BenderSession::GetProxyOutputPort() const
{
  return this->ProxyFilter->GetOutputPort();
}

vtkPolyData* BenderSession::GetProxySurface() const
{
  this->ProxyFilter->Update();
  return this->ProxyFilter->GetOutput();
}

long long BenderSession::GetProxyBuildCount() const
{
  return this->ProxySource->GetBuildCount() + this->ProxyJobBuilds;
}

bool BenderSession::WantsProxy() const
{
  vtkPolyData* surface = this->History.Current();
  return surface &&
    static_cast<long long>(surface->GetNumberOfPolys() + surface->GetNumberOfStrips()) >
    this->LodThreshold;
}

vtkAlgorithmOutput* BenderSession::GetOutputPort() const
{
  return this->LiveFilter->GetOutputPort();
}

vtkPolyData* BenderSession::GetDisplaySurface() const
{
  this->LiveFilter->Update();
  return this->LiveFilter->GetOutput();
}

void BenderSession::Report(MessageSeverity severity, const std::string& text)
{
  this->Messages.push_back({ severity, text });
  if (this->MessageCallback)
  {
    this->MessageCallback(this->Messages.back());
  }
}

void BenderSession::Changed()
{
  if (this->ChangeCallback)
  {
    this->ChangeCallback();
  }
}

void BenderSession::SetMessageCallback(std::function<void(const LogicMessage&)> callback)
{
  this->MessageCallback = std::move(callback);
}

void BenderSession::SetChangeCallback(std::function<void()> callback)
{
  this->ChangeCallback = std::move(callback);
}

void BenderSession::ShowCommitted(vtkPolyData* proxy)
{
  // The pipeline stays connected: the committed surface passes through the live filter.
  this->LiveFilter->PassThroughOn();
  this->LiveFilter->SetPreparedWarp(nullptr);
  this->LiveWarp.reset();
  this->LiveFilter->SetInputData(InputOrEmpty(this->History.Current()));
  // The level of detail follows (decimated when pulled, unless a job made the copy).
  this->ProxyDrag = false;
  this->ProxyFilter->PassThroughOn();
  this->ProxyFilter->SetPreparedWarp(nullptr);
  this->ProxySource->SetInputData(InputOrEmpty(this->History.Current()));
  if (proxy)
  {
    this->ProxySource->SetPrepared(this->History.Current(), proxy);
    ++this->ProxyJobBuilds;
  }
}

bool BenderSession::RefuseWhenBusy(const std::string& what)
{
  if (!this->Busy)
  {
    return false;
  }
  this->Report(MessageSeverity::Error, what + ": busy, wait for the current task or cancel it");
  return true;
}

bool BenderSession::LoadSurface(const std::string& path)
{
  return this->RunNow(this->BeginLoadSurface(path));
}

bool BenderSession::SetSurface(vtkPolyData* surface,
  const std::string& name,
  const std::string& sourcePath)
{
  if (!surface || surface->GetNumberOfPoints() == 0 ||
    surface->GetNumberOfPolys() + surface->GetNumberOfStrips() == 0)
  {
    this->Report(MessageSeverity::Error, name + ": the surface has no triangles");
    return false;
  }
  if (this->RefuseWhenBusy(name))
  {
    return false;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->CancelGrab("a new surface was loaded");
  }
  this->History.Reset(surface);
  this->State = GrabState::Idle;
  this->Held.reset();
  this->SetRibbonInformation(std::nullopt);
  this->ChangeCount = this->SavedChangeCount = 0;
  this->SourcePath = sourcePath;
  this->SurfaceName = name;
  this->AutosaveSourcePath.clear();
  this->ShowCommitted(nullptr);
  std::ostringstream text;
  text << "Loaded " << name << ": " << surface->GetNumberOfPoints() << " points, "
       << surface->GetNumberOfPolys() + surface->GetNumberOfStrips() << " cells";
  this->Report(MessageSeverity::Info, text.str());
  this->Autosave();
  this->Changed();
  return true;
}

bool BenderSession::Clear(const std::string& reason)
{
  if (!this->HasSurface())
  {
    return true;
  }
  if (this->RefuseWhenBusy(this->SurfaceName))
  {
    return false;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->CancelGrab(reason);
  }
  const std::string name = this->SurfaceName;
  this->History.Reset(nullptr);
  this->State = GrabState::Idle;
  this->Held.reset();
  this->SetRibbonInformation(std::nullopt);
  this->ChangeCount = this->SavedChangeCount = 0;
  this->SourcePath.clear();
  this->SurfaceName.clear();
  this->AutosaveSourcePath.clear();
  this->AutosavedRibbon.reset();
  this->ShowCommitted(nullptr);
  this->Report(MessageSeverity::Info, "Closed " + name + ": " + reason);
  this->Changed();
  return true;
}

bool BenderSession::HasUnsavedChanges() const
{
  return this->State == GrabState::Grabbed || this->ChangeCount != this->SavedChangeCount;
}

WarpPlan BenderSession::GetPlan() const
{
  return this->History.CommittedPlan();
}

bool BenderSession::SavePlan(const std::string& path)
{
  try
  {
    WriteWarpPlan(this->GetPlan(), path);
  }
  catch (const std::exception& e) // WarpPlanError, and std's (filesystem, bad_alloc): a message
  {
    this->Report(MessageSeverity::Error, std::string("Saving the plan failed: ") + e.what());
    return false;
  }
  this->MarkSaved();
  const WarpPlan plan = this->GetPlan();
  this->Report(MessageSeverity::Info,
    "Saved the plan (" + CountOf(plan.warps.size(), "warp") +
      (plan.cfdSteps.empty() ? std::string() : ", Prepare for CFD") + ") to " + DisplayName(path));
  return true;
}

bool BenderSession::LoadPlan(const std::string& path)
{
  return this->RunNow(this->BeginLoadPlan(path));
}

bool BenderSession::ReplayPlan(const WarpPlan& plan, const std::string& name)
{
  return this->RunNow(this->BeginReplay(plan, name));
}

bool BenderSession::IsPlanApplied(const WarpPlan& plan) const
{
  const std::size_t steps = plan.warps.size() + plan.cfdSteps.size();
  const std::size_t position = this->History.Position();
  return steps > 0 && position >= steps &&
    SerializeWarpPlan(this->History.CommittedPlan(position - steps)) == SerializeWarpPlan(plan);
}

bool BenderSession::ApplyWarp(const WarpSpec& warp)
{
  WarpPlan plan;
  plan.warps.push_back(warp);
  return this->ReplayPlan(plan, "warp");
}

MeshCheckReport BenderSession::CheckSurface() const
{
  return CheckForExport(this->History.Current(), this->History.Original());
}

bool BenderSession::Export(const std::string& path, const ExportSurfaceOptions& options)
{
  return this->RunNow(this->BeginExport(path, options, true));
}

void BenderSession::SetAutosavePath(const std::string& path)
{
  this->AutosavePath = path;
  this->AutosaveSourcePath.clear();
  this->AutosavedRibbon.reset();
}

bool BenderSession::Autosave()
{
  if (this->AutosavePath.empty() || !this->HasSurface())
  {
    return true;
  }
  try
  {
    SessionSnapshot snapshot;
    snapshot.sourcePath = this->SourcePath;
    snapshot.surfaceName = this->SurfaceName;
    if (snapshot.sourcePath.empty())
    {
      // A surface made here (segmentation) has no file: keep one beside the autosave.
      if (this->AutosaveSourcePath.empty())
      {
        const std::string sourceCopy = this->AutosavePath + ".source.vtp";
        WriteMesh(this->History.First(), sourceCopy);
        this->AutosaveSourcePath = AbsolutePath(sourceCopy);
      }
      snapshot.sourcePath = this->AutosaveSourcePath;
    }
    snapshot.plan = this->GetPlan();
    if (this->AutosaveDecorator)
    {
      this->AutosaveDecorator(snapshot);
    }
    WriteSessionFile(snapshot, this->AutosavePath);
    this->AutosavedRibbon = this->CurrentRibbon;
  }
  catch (const std::exception& e) // the writers, VTK, std and the window's decorator: a warning
  {
    this->Report(MessageSeverity::Warning, std::string("Autosave failed: ") + e.what());
    return false;
  }
  return true;
}

bool BenderSession::HasUnsavedRibbon() const
{
  const auto& ribbon = this->CurrentRibbon;
  return ribbon && !this->AutosavePath.empty() && !this->Busy &&
    this->State != GrabState::Grabbed && this->HasSurface() &&
    !(this->AutosavedRibbon && SameRibbon(*this->AutosavedRibbon, *ribbon));
}

bool BenderSession::AutosaveRibbon()
{
  return !this->HasUnsavedRibbon() || this->Autosave();
}

void BenderSession::DiscardAutosave()
{
  if (this->AutosavePath.empty())
  {
    return;
  }
  std::error_code ec;
  std::filesystem::remove(this->AutosavePath, ec);
  std::filesystem::remove(this->AutosavePath + ".source.vtp", ec);
  this->AutosaveSourcePath.clear();
  this->AutosavedRibbon.reset();
}

bool BenderSession::Recover(const std::string& sessionPath)
{
  return this->RunNow(this->BeginRecover(sessionPath));
}

} // namespace bender
