#include "BenderSession.h"

#include "GeometryErrors.h"
#include "MeshIO.h"
#include "Ribbon.h"
#include "RibbonWarp.h"
#include "SessionAutosave.h"
#include "WarpPlanIO.h"
#include "vtkBenderAdaptiveSubdivisionFilter.h"

#include <vtkPolyData.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace bender
{

namespace
{

std::string FileName(const std::string& path)
{
  return std::filesystem::path(path).filename().string();
}

std::string AbsolutePath(const std::string& path)
{
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(path, ec);
  return ec ? path : absolute.lexically_normal().string();
}

bool SameRibbon(const RibbonSpec& a, const RibbonSpec& b)
{
  auto same = [](const RibbonEnd& x, const RibbonEnd& y) {
    auto eq = [](const Vec3& u, const Vec3& v) { return u.x == v.x && u.y == v.y && u.z == v.z; };
    return eq(x.position, y.position) && eq(x.tangent, y.tangent) && eq(x.normal, y.normal);
  };
  return same(a.start, b.start) && same(a.end, b.end) && a.extraTurns == b.extraTurns;
}

std::string Describe(const WarpParameters& p)
{
  std::ostringstream out;
  out << "R = " << p.radius << ", " << (p.decay.shape == DecayShape::Bell ? "bell" : "plateau");
  if (p.decay.shape == DecayShape::Plateau)
  {
    out << " " << p.decay.plateau;
  }
  return out.str();
}

}

BenderSession::BenderSession()
{
  this->LiveFilter->SetPrecision(WarpPrecision::Table);
}

BenderSession::~BenderSession() = default;

vtkPolyData* BenderSession::GetDisplaySurface() const
{
  return this->Display.GetPointer();
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

void BenderSession::ShowCommitted()
{
  vtkPolyData* current = this->History.Current();
  if (current)
  {
    this->Display->ShallowCopy(current);
  }
  else
  {
    this->Display->Initialize();
  }
  this->Display->Modified();
}

bool BenderSession::LoadSurface(const std::string& path)
{
  vtkSmartPointer<vtkPolyData> mesh;
  try
  {
    mesh = ReadMesh(path);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, e.what());
    return false;
  }
  return this->SetSurface(mesh, FileName(path), AbsolutePath(path));
}

bool BenderSession::SetSurface(
  vtkPolyData* surface, const std::string& name, const std::string& sourcePath)
{
  if (!surface || surface->GetNumberOfPoints() == 0 || surface->GetNumberOfPolys() +
      surface->GetNumberOfStrips() == 0)
  {
    this->Report(MessageSeverity::Error, name + ": the surface has no triangles");
    return false;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->CancelGrab("a new surface was loaded");
  }
  this->History.Reset(surface);
  this->State = GrabState::Idle;
  this->SourcePath = sourcePath;
  this->SurfaceName = name;
  this->AutosaveSourcePath.clear();
  this->LiveFilter->SetInputData(nullptr);
  this->ShowCommitted();
  std::ostringstream text;
  text << "Loaded " << name << ": " << surface->GetNumberOfPoints() << " points, "
       << surface->GetNumberOfPolys() + surface->GetNumberOfStrips() << " cells";
  this->Report(MessageSeverity::Info, text.str());
  this->Autosave();
  this->Changed();
  return true;
}

bool BenderSession::SetParameters(const WarpParameters& parameters)
{
  if (!(std::isfinite(parameters.radius) && parameters.radius > 0.0))
  {
    this->Report(MessageSeverity::Error, "radius: R must be a positive number");
    return false;
  }
  if (!(parameters.decay.plateau >= 0.0 && parameters.decay.plateau <= 0.95))
  {
    this->Report(MessageSeverity::Error, "plateau: the width must be in [0, 0.95]");
    return false;
  }
  if (!(std::isfinite(parameters.subdivisionTolerance) && parameters.subdivisionTolerance > 0.0) ||
    parameters.subdivisionMaxPasses < 0 || parameters.subdivisionMaxPasses > 64)
  {
    this->Report(MessageSeverity::Error,
      "subdivision: the tolerance must be positive and the passes in [0, 64]");
    return false;
  }
  const bool bindingChanged = parameters.radius != this->Parameters.radius ||
    parameters.decay.shape != this->Parameters.decay.shape ||
    parameters.decay.plateau != this->Parameters.decay.plateau ||
    parameters.reverseScrews != this->Parameters.reverseScrews;
  this->Parameters = parameters;
  if (this->State == GrabState::Grabbed && bindingChanged)
  {
    // The live warp takes the new region of influence at once (it rebinds).
    this->Live.radius = parameters.radius;
    this->Live.decay = parameters.decay;
    this->Live.reverseScrews = parameters.reverseScrews;
    this->LiveFilter->SetWarp(this->Live);
    this->LiveFilter->Update();
    if (this->LiveFilter->GetLastError().empty())
    {
      this->Display->ShallowCopy(this->LiveFilter->GetOutput());
      this->Display->Modified();
    }
    this->UpdateLiveInformation();
    this->Changed();
  }
  return true;
}

void BenderSession::UpdateLiveInformation()
{
  this->InitialMinimumRadius = this->LiveFilter->GetInitialMinimumRadius();
  this->SpaceInversionRisk = this->LiveFilter->GetSpaceInversionRisk();
  this->FlipOccurred = this->LiveFilter->GetFlipOccurred();
  this->InversionWarning = this->SpaceInversionRisk ? this->LiveFilter->GetLastWarning() : std::string();
  if (this->SpaceInversionRisk && !this->WarnedInversion)
  {
    this->WarnedInversion = true;
    this->Report(MessageSeverity::Warning, this->LiveFilter->GetLastWarning());
  }
}

long long BenderSession::GetNumberOfBoundPoints() const
{
  return this->State == GrabState::Grabbed
    ? static_cast<long long>(this->LiveFilter->GetNumberOfBoundPoints())
    : 0;
}

bool BenderSession::Grab(const RibbonSpec& initial)
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, "Grab: load or segment a surface first");
    return false;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Grab: already grabbed; release or cancel first");
    return false;
  }
  RibbonSpec start = initial;
  start.extraTurns = 0;
  WarpSpec warp;
  warp.initial = start;
  warp.final = start;
  warp.radius = this->Parameters.radius;
  warp.decay = this->Parameters.decay;
  warp.reverseScrews = this->Parameters.reverseScrews;
  try
  {
    RibbonWarp::Validate(warp);
    this->Unwrapper.Start(start);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, std::string("Grab refused: ") + e.what());
    return false;
  }
  this->Live = warp;
  this->LiveFilter->SetInputData(this->History.Current());
  this->LiveFilter->SetPrecision(WarpPrecision::Table);
  this->LiveFilter->SetWarp(warp);
  this->LiveFilter->Update();
  if (!this->LiveFilter->GetLastError().empty())
  {
    this->Report(MessageSeverity::Error, "Grab refused: " + this->LiveFilter->GetLastError());
    return false;
  }
  this->State = GrabState::Grabbed;
  this->LiveProblem.clear();
  this->WarnedInversion = false;
  this->UpdateLiveInformation();
  this->Display->ShallowCopy(this->LiveFilter->GetOutput());
  this->Display->Modified();
  std::ostringstream text;
  text << "Grabbed (" << Describe(this->Parameters) << "): "
       << this->LiveFilter->GetNumberOfBoundPoints() << " points inside the region of influence";
  this->Report(MessageSeverity::Info, text.str());
  this->Changed();
  return true;
}

bool BenderSession::MoveFinal(const RibbonSpec& final)
{
  if (this->State != GrabState::Grabbed)
  {
    return false;
  }
  WarpSpec candidate = this->Live;
  try
  {
    candidate.final = this->Unwrapper.Unwrap(final);
    RibbonWarp::Validate(candidate);
  }
  catch (const std::exception& e)
  {
    this->LiveProblem = e.what();
    this->Changed();
    return false;
  }
  this->LiveFilter->SetFinalRibbon(candidate.final);
  this->LiveFilter->Update();
  if (!this->LiveFilter->GetLastError().empty())
  {
    this->LiveProblem = this->LiveFilter->GetLastError();
    // Put the filter back on the last valid ribbon so that the display stays consistent.
    this->LiveFilter->SetFinalRibbon(this->Live.final);
    this->LiveFilter->Update();
    this->Changed();
    return false;
  }
  this->Unwrapper.Accept(candidate.final);
  this->Live = candidate;
  this->LiveProblem.clear();
  this->UpdateLiveInformation();
  this->Display->ShallowCopy(this->LiveFilter->GetOutput());
  this->Display->Modified();
  this->Changed();
  return true;
}

bool BenderSession::ApplyExact(const WarpSpec& warp, vtkPolyData* input,
  vtkSmartPointer<vtkPolyData>& output, std::string& problem) const
{
  if (warp.subdivision && warp.subdivision->maxPasses > 0)
  {
    vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivision;
    subdivision->SetInputData(input);
    subdivision->SetWarp(warp);
    subdivision->SetPrecision(WarpPrecision::Exact);
    subdivision->Update();
    if (!subdivision->GetLastError().empty())
    {
      problem = subdivision->GetLastError();
      return false;
    }
    output = vtkSmartPointer<vtkPolyData>::New();
    output->DeepCopy(subdivision->GetOutput());
    return true;
  }
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(input);
  filter->SetWarp(warp);
  filter->SetPrecision(WarpPrecision::Exact);
  filter->Update();
  if (!filter->GetLastError().empty())
  {
    problem = filter->GetLastError();
    return false;
  }
  output = vtkSmartPointer<vtkPolyData>::New();
  output->DeepCopy(filter->GetOutput());
  return true;
}

bool BenderSession::Release()
{
  if (this->State != GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Release: nothing is grabbed");
    return false;
  }
  WarpSpec warp = this->Live;
  if (SameRibbon(warp.initial, warp.final))
  {
    this->State = GrabState::Idle;
    this->ShowCommitted();
    this->Report(MessageSeverity::Info, "Released without moving: no warp recorded");
    this->Changed();
    return true;
  }
  if (this->Parameters.subdivide)
  {
    warp.subdivision = SubdivisionSpec{ this->Parameters.subdivisionTolerance,
      this->Parameters.subdivisionMaxPasses };
  }
  vtkSmartPointer<vtkPolyData> result;
  std::string problem;
  // The live preview used the interpolated table; the committed shape is the exact warp.
  if (!this->ApplyExact(warp, this->History.Current(), result, problem))
  {
    this->Report(MessageSeverity::Error, "Release failed, the warp was not applied: " + problem);
    this->State = GrabState::Idle;
    this->ShowCommitted();
    this->Changed();
    return false;
  }
  this->History.Commit(warp, result);
  this->State = GrabState::Released;
  this->LiveFilter->SetInputData(nullptr);
  this->ShowCommitted();
  std::ostringstream text;
  text << "Warp " << this->History.Position() << " committed";
  if (warp.subdivision)
  {
    text << " (subdivided to " << result->GetNumberOfPolys() << " triangles)";
  }
  this->Report(MessageSeverity::Info, text.str());
  this->Autosave();
  this->Changed();
  return true;
}

void BenderSession::CancelGrab(const std::string& reason)
{
  if (this->State != GrabState::Grabbed)
  {
    return;
  }
  this->State = GrabState::Idle;
  this->LiveFilter->SetInputData(nullptr);
  this->ShowCommitted();
  this->Report(MessageSeverity::Warning,
    "The live warp was cancelled (" + reason + "); the last committed shape is kept");
  this->Changed();
}

bool BenderSession::Undo()
{
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Undo: release or cancel the grab first");
    return false;
  }
  if (!this->History.Undo())
  {
    this->Report(MessageSeverity::Info, "Nothing to undo");
    return false;
  }
  this->State = GrabState::Idle;
  this->ShowCommitted();
  this->Report(MessageSeverity::Info, "Undid warp " + std::to_string(this->History.Position() + 1));
  this->Autosave();
  this->Changed();
  return true;
}

bool BenderSession::Redo()
{
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Redo: release or cancel the grab first");
    return false;
  }
  if (!this->History.Redo())
  {
    this->Report(MessageSeverity::Info, "Nothing to redo");
    return false;
  }
  this->State = GrabState::Idle;
  this->ShowCommitted();
  this->Report(MessageSeverity::Info, "Redid warp " + std::to_string(this->History.Position()));
  this->Autosave();
  this->Changed();
  return true;
}

WarpPlan BenderSession::GetPlan() const
{
  WarpPlan plan;
  plan.warps = this->History.CommittedWarps();
  return plan;
}

bool BenderSession::SavePlan(const std::string& path)
{
  try
  {
    WriteWarpPlan(this->GetPlan(), path);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, std::string("Saving the plan failed: ") + e.what());
    return false;
  }
  this->Report(MessageSeverity::Info, "Saved the plan (" +
      std::to_string(this->History.Position()) + " warps) to " + FileName(path));
  return true;
}

bool BenderSession::LoadPlan(const std::string& path)
{
  WarpPlan plan;
  try
  {
    plan = ReadWarpPlan(path);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, e.what());
    return false;
  }
  return this->ReplayPlan(plan, FileName(path));
}

bool BenderSession::ReplayPlan(const WarpPlan& plan, const std::string& name)
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, name + ": load or segment a surface before replaying");
    return false;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, name + ": release or cancel the grab first");
    return false;
  }
  // All or nothing: compute every step before committing any.
  std::vector<vtkSmartPointer<vtkPolyData>> results;
  vtkPolyData* input = this->History.Current();
  for (std::size_t i = 0; i < plan.warps.size(); ++i)
  {
    vtkSmartPointer<vtkPolyData> output;
    std::string problem;
    try
    {
      RibbonWarp::Validate(plan.warps[i]);
    }
    catch (const std::exception& e)
    {
      problem = e.what();
    }
    if (!problem.empty() || !this->ApplyExact(plan.warps[i], input, output, problem))
    {
      this->Report(MessageSeverity::Error,
        name + ": warps[" + std::to_string(i) + "]: " + problem + "; nothing was applied");
      return false;
    }
    results.push_back(output);
    input = output;
  }
  for (std::size_t i = 0; i < plan.warps.size(); ++i)
  {
    this->History.Commit(plan.warps[i], results[i]);
  }
  this->State = GrabState::Idle;
  this->ShowCommitted();
  this->Report(MessageSeverity::Info,
    "Replayed " + std::to_string(plan.warps.size()) + " warps of " + name);
  this->Autosave();
  this->Changed();
  return true;
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

bool BenderSession::Export(const std::string& path, const ExportOptions& options)
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, FileName(path) + ": there is no surface to export");
    return false;
  }
  if (!this->SourcePath.empty() && SameFile(path, this->SourcePath))
  {
    this->Report(MessageSeverity::Error,
      FileName(path) + ": refusing to overwrite the input surface; choose another file");
    return false;
  }
  ExportOptions guarded = options;
  guarded.protectedPath = this->SourcePath;
  std::vector<std::string> written;
  try
  {
    written = ExportSurface(this->History.Current(), path, guarded);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, std::string("Export failed: ") + e.what());
    return false;
  }
  std::string names;
  for (const std::string& file : written)
  {
    names += (names.empty() ? "" : ", ") + FileName(file);
  }
  this->Report(MessageSeverity::Info,
    "Exported " + names + " (frame " + options.frame + ", unit " + options.unit + ")");
  return true;
}

void BenderSession::SetAutosavePath(const std::string& path)
{
  this->AutosavePath = path;
  this->AutosaveSourcePath.clear();
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
    if (snapshot.sourcePath.empty())
    {
      // A surface made here (segmentation) has no file: keep one beside the autosave.
      if (this->AutosaveSourcePath.empty())
      {
        const std::string sourceCopy = this->AutosavePath + ".source.vtp";
        WriteMesh(this->History.Original(), sourceCopy);
        this->AutosaveSourcePath = AbsolutePath(sourceCopy);
      }
      snapshot.sourcePath = this->AutosaveSourcePath;
    }
    snapshot.plan = this->GetPlan();
    WriteSessionFile(snapshot, this->AutosavePath);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Warning, std::string("Autosave failed: ") + e.what());
    return false;
  }
  return true;
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
}

bool BenderSession::Recover(const std::string& sessionPath)
{
  SessionSnapshot snapshot;
  try
  {
    snapshot = ReadSessionFile(sessionPath);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, std::string("Recovery failed: ") + e.what());
    return false;
  }
  vtkSmartPointer<vtkPolyData> source;
  try
  {
    source = ReadMesh(snapshot.sourcePath);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error,
      std::string("Recovery failed: the session's source cannot be read: ") + e.what());
    return false;
  }
  // Recovering from our own autosave: keep the source copy, it is the only one.
  const bool ownCopy = snapshot.sourcePath == AbsolutePath(this->AutosavePath + ".source.vtp");
  // No autosave until the replay has succeeded: loading the surface would otherwise overwrite
  // the session being recovered with an empty plan, and a failed replay would lose it.
  const std::string autosavePath = this->AutosavePath;
  this->AutosavePath.clear();
  const bool recovered =
    this->SetSurface(source, FileName(snapshot.sourcePath), ownCopy ? std::string() : snapshot.sourcePath) &&
    this->ReplayPlan(snapshot.plan, FileName(sessionPath));
  this->AutosavePath = autosavePath;
  if (!recovered)
  {
    return false;
  }
  this->Autosave();
  this->Report(MessageSeverity::Info,
    "Recovered the session: " + std::to_string(snapshot.plan.warps.size()) + " warps");
  return true;
}

} // namespace bender
