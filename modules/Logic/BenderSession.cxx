#include "BenderSession.h"

#include "BenderErrors.h"
#include "GeometryErrors.h"
#include "MeshIO.h"
#include "Ribbon.h"
#include "RibbonWarp.h"
#include "SessionAutosave.h"
#include "WarpPlanIO.h"
#include <vtkAlgorithmOutput.h>
#include <vtkCellArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkQuadricClustering.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <limits>
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
  auto same = [](const RibbonEnd& x, const RibbonEnd& y)
  {
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

namespace
{
// The live filter's input: the committed surface, or an empty one before any is loaded (a view
// connected to the output port may render first; without an input VTK reports an error).
vtkSmartPointer<vtkPolyData> InputOrEmpty(vtkPolyData* surface)
{
  return surface ? vtkSmartPointer<vtkPolyData>(surface) : vtkSmartPointer<vtkPolyData>::New();
}

}

vtkSmartPointer<vtkPolyData> MakeLevelOfDetail(vtkPolyData* surface)
{
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  // Clustering bins a NaN or infinite coordinate nowhere sensible: such a surface is not
  // decimated (the warp then refuses it with its own message, as without a copy).
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      auto same = vtkSmartPointer<vtkPolyData>::New();
      same->ShallowCopy(surface);
      return same;
    }
  }
  vtkNew<vtkQuadricClustering> decimate;
  decimate->SetInputData(surface);
  decimate->SetNumberOfDivisions(100, 100, 100);
  decimate->AutoAdjustNumberOfDivisionsOn();
  decimate->UseInputPointsOff();
  decimate->CopyCellDataOff();
  decimate->Update();
  vtkSmartPointer<vtkPolyData> copy = decimate->GetOutput();
  return copy;
}

namespace
{
// The level of detail of the committed surface (its input): the decimated copy, made when
// the output is pulled and the input changed, or the copy a release job made for this input.
class vtkBenderLevelOfDetailSource : public vtkPolyDataAlgorithm
{
public:
  static vtkBenderLevelOfDetailSource* New();
  vtkTypeMacro(vtkBenderLevelOfDetailSource, vtkPolyDataAlgorithm);
  /// `copy` is the decimated copy of `input` (in its present state): used instead of
  /// decimating again.
  void SetPrepared(vtkPolyData* input, vtkPolyData* copy)
  {
    this->PreparedFor = input;
    this->PreparedTime = input ? input->GetMTime() : 0;
    this->Prepared = copy;
    this->Modified();
  }
  long long GetBuildCount() const { return this->Builds; }

protected:
  vtkBenderLevelOfDetailSource() = default;
  int RequestData(vtkInformation*,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override
  {
    vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
    vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
    if (!input || !output)
    {
      return 0;
    }
    if (this->Prepared && input == this->PreparedFor && input->GetMTime() == this->PreparedTime)
    {
      output->ShallowCopy(this->Prepared);
    }
    else
    {
      output->ShallowCopy(MakeLevelOfDetail(input));
      if (input->GetNumberOfPoints() > 0)
      {
        ++this->Builds;
      }
    }
    return 1;
  }

private:
  vtkBenderLevelOfDetailSource(const vtkBenderLevelOfDetailSource&) = delete;
  void operator=(const vtkBenderLevelOfDetailSource&) = delete;
  vtkPolyData* PreparedFor = nullptr; // identity only
  vtkMTimeType PreparedTime = 0;
  vtkSmartPointer<vtkPolyData> Prepared;
  long long Builds = 0;
};
vtkStandardNewMacro(vtkBenderLevelOfDetailSource);

vtkBenderLevelOfDetailSource* LevelOfDetail(vtkPolyDataAlgorithm* source)
{
  return static_cast<vtkBenderLevelOfDetailSource*>(source);
}
}

BenderSession::BenderSession()
  : ProxySource(vtkSmartPointer<vtkBenderLevelOfDetailSource>::New())
{
  this->LiveFilter->SetPrecision(WarpPrecision::Table);
  this->LiveFilter->PassThroughOn();
  this->LiveFilter->SetInputData(InputOrEmpty(nullptr));
  this->ProxySource->SetInputData(InputOrEmpty(nullptr));
  this->ProxyFilter->SetPrecision(WarpPrecision::Table);
  this->ProxyFilter->PassThroughOn();
  this->ProxyFilter->SetInputConnection(this->ProxySource->GetOutputPort());
}

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
  return LevelOfDetail(this->ProxySource)->GetBuildCount() + this->ProxyJobBuilds;
}

bool BenderSession::WantsProxy() const
{
  vtkPolyData* surface = this->History.Current();
  return surface &&
    static_cast<long long>(surface->GetNumberOfPolys() + surface->GetNumberOfStrips()) >
    this->LodThreshold;
}

BenderSession::~BenderSession() = default;

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
    LevelOfDetail(this->ProxySource)->SetPrepared(this->History.Current(), proxy);
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

bool BenderSession::SetLiveWarp(const WarpSpec& warp, std::string& problem)
{
  // The one build per move: validates (convention 11) and is shared with the filter.
  std::shared_ptr<const RibbonWarp> built;
  try
  {
    ++this->WarpBuildCount;
    built = std::make_shared<const RibbonWarp>(warp);
  }
  catch (const std::exception& e)
  {
    problem = e.what();
    return false;
  }
  // Dragging a big surface, the decimated copy is warped (and validated) now; the full
  // surface's filter holds the warp and computes only when its output is asked for.
  vtkBenderWarpFilter* shown =
    this->ProxyDrag ? this->ProxyFilter.GetPointer() : this->LiveFilter.GetPointer();
  this->LiveFilter->SetPreparedWarp(built);
  if (this->ProxyDrag)
  {
    this->ProxyFilter->SetPreparedWarp(built);
  }
  shown->Update();
  if (!shown->GetLastError().empty())
  {
    problem = shown->GetLastError();
    // Back to the last valid warp so that the display stays consistent.
    this->LiveFilter->SetPreparedWarp(this->LiveWarp);
    if (this->ProxyDrag)
    {
      this->ProxyFilter->SetPreparedWarp(this->LiveWarp);
    }
    return false;
  }
  this->LiveWarp = built;
  return true;
}

bool BenderSession::LoadSurface(const std::string& path)
{
  if (this->RefuseWhenBusy(FileName(path)))
  {
    return false;
  }
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
    this->DropHeld();
    std::string problem;
    if (!this->SetLiveWarp(this->Live, problem))
    {
      this->LiveProblem = problem;
    }
    this->UpdateLiveInformation();
    this->Changed();
  }
  else if (this->State != GrabState::Grabbed && bindingChanged)
  {
    this->SetRibbonInformation(this->CurrentRibbon);
  }
  return true;
}

namespace
{
// The one sentence about the space-inversion rule, quoting the one r_min shown everywhere.
std::string InversionSentence(double radius, double minimumRadius)
{
  std::ostringstream out;
  out.precision(3);
  out << "space inversion possible: R = " << radius
      << " mm is not smaller than r_min = " << minimumRadius
      << " mm, the ribbon's smallest arc radius; reduce R or straighten the "
      << "ribbon";
  return out.str();
}
}

void BenderSession::SetRibbonInformation(const std::optional<RibbonSpec>& ribbon)
{
  this->CurrentRibbon = ribbon;
  this->WarnedInversion = false;
  this->FlipOccurred = false;
  this->MinimumRadius = std::numeric_limits<double>::infinity();
  this->InitialMinimumRadius = this->MinimumRadius;
  if (ribbon)
  {
    try
    {
      this->MinimumRadius = Ribbon(*ribbon).Wire().MinimumRadius();
      this->InitialMinimumRadius = this->MinimumRadius;
    }
    catch (const std::exception&)
    {
      // An invalid ribbon has no r_min; PlaceRibbon refuses it before.
    }
  }
  this->SpaceInversionRisk = this->Parameters.radius >= this->MinimumRadius;
  this->InversionWarning = this->SpaceInversionRisk
    ? InversionSentence(this->Parameters.radius, this->MinimumRadius)
    : std::string();
}

bool BenderSession::PlaceRibbon(const RibbonSpec& ribbon)
{
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Place ribbon: release or cancel the grab first");
    return false;
  }
  try
  {
    Ribbon check(ribbon);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, std::string("Place ribbon: ") + e.what());
    return false;
  }
  this->SetRibbonInformation(ribbon);
  this->Changed();
  return true;
}

const CommitCheck& BenderSession::GetHeldCheck() const
{
  static const CommitCheck none;
  return this->Held ? this->Held->check : none;
}

void BenderSession::DropHeld()
{
  this->Held.reset();
}

bool BenderSession::HasUnsavedChanges() const
{
  return this->State == GrabState::Grabbed || this->ChangeCount != this->SavedChangeCount;
}

bool BenderSession::KeepHeldCommit()
{
  if (!this->Held || this->State != GrabState::Grabbed || this->Busy)
  {
    this->Report(MessageSeverity::Error, "Keep: no commit is held");
    return false;
  }
  const HeldCommit held = *this->Held;
  this->Held.reset();
  this->History.Commit(held.warp, held.result);
  ++this->ChangeCount;
  this->State = GrabState::Released;
  this->ShowCommitted(held.proxy);
  this->SetRibbonInformation(held.warp.final);
  this->Report(MessageSeverity::Warning,
    "Warp " + std::to_string(this->History.Position()) +
      " committed although the check found: " + held.check.Summary());
  this->Autosave();
  this->Changed();
  return true;
}

void BenderSession::UpdateLiveInformation()
{
  if (!this->LiveWarp)
  {
    return;
  }
  this->InitialMinimumRadius = this->LiveWarp->InitialMinimumRadius();
  this->MinimumRadius =
    std::min(this->LiveWarp->InitialMinimumRadius(), this->LiveWarp->FinalMinimumRadius());
  this->SpaceInversionRisk = this->LiveWarp->SpaceInversionRisk();
  this->FlipOccurred = this->LiveWarp->FlipOccurred();
  this->InversionWarning = this->SpaceInversionRisk
    ? InversionSentence(this->LiveWarp->Spec().radius, this->MinimumRadius)
    : std::string();
  if (this->SpaceInversionRisk && !this->WarnedInversion)
  {
    this->WarnedInversion = true;
    this->Report(MessageSeverity::Warning, this->InversionWarning);
  }
}

vtkPolyData* BenderSession::GetOriginalInPlay()
{
  vtkPolyData* original = this->History.Original();
  vtkPolyData* current = this->History.Current();
  const bool grabbed = this->State == GrabState::Grabbed;
  if (!original || !current || (grabbed && this->ProxyDrag) ||
    original->GetNumberOfPoints() != current->GetNumberOfPoints() ||
    original->GetNumberOfPolys() != current->GetNumberOfPolys() ||
    original->GetNumberOfCells() != original->GetNumberOfPolys())
  {
    this->InPlay = nullptr;
    this->InPlayMadeFrom = InPlayKey{};
    return nullptr;
  }
  InPlayKey key;
  key.original = original;
  key.current = current;
  key.originalTime = original->GetMTime();
  key.currentTime = current->GetMTime();
  key.binding = grabbed ? this->LiveFilter->GetBindingCount() : -1;
  if (this->InPlay && key == this->InPlayMadeFrom)
  {
    return this->InPlay;
  }
  // Points in play: moved by the committed warps, or bound by the grab.
  const vtkIdType n = original->GetNumberOfPoints();
  std::vector<std::uint8_t> inPlay(static_cast<std::size_t>(n), 0);
  vtkPoints* a = original->GetPoints();
  vtkPoints* b = current->GetPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    inPlay[static_cast<std::size_t>(i)] = p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
  }
  if (grabbed)
  {
    for (const std::int64_t id : this->LiveFilter->GetBoundPointIds())
    {
      if (id >= 0 && id < n)
      {
        inPlay[static_cast<std::size_t>(id)] = 1;
      }
    }
  }
  vtkNew<vtkCellArray> cells;
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = original->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(count, ids);)
  {
    for (vtkIdType k = 0; k < count; ++k)
    {
      if (inPlay[static_cast<std::size_t>(ids[k])])
      {
        cells->InsertNextCell(count, ids);
        break;
      }
    }
  }
  this->InPlay = vtkSmartPointer<vtkPolyData>::New();
  this->InPlay->SetPoints(original->GetPoints());
  this->InPlay->SetPolys(cells);
  this->InPlayMadeFrom = key;
  return this->InPlay;
}

long long BenderSession::GetNumberOfBoundPoints() const
{
  if (this->State != GrabState::Grabbed)
  {
    return 0;
  }
  return static_cast<long long>(this->ProxyDrag ? this->ProxyFilter->GetNumberOfBoundPoints()
                                                : this->LiveFilter->GetNumberOfBoundPoints());
}

bool BenderSession::Grab(const RibbonSpec& initial)
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, "Grab: load or segment a surface first");
    return false;
  }
  if (this->RefuseWhenBusy("Grab"))
  {
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
    this->Unwrapper.Start(start);
  }
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, std::string("Grab refused: ") + e.what());
    return false;
  }
  this->LiveWarp.reset();
  this->LiveFilter->SetInputData(InputOrEmpty(this->History.Current()));
  this->LiveFilter->PassThroughOff();
  // A big surface is dragged as its decimated copy (made now unless it is ready).
  this->ProxyDrag = this->WantsProxy();
  this->ProxyFilter->SetPassThrough(!this->ProxyDrag);
  std::string problem;
  if (!this->SetLiveWarp(warp, problem))
  {
    this->ShowCommitted(nullptr);
    this->Report(MessageSeverity::Error, "Grab refused: " + problem);
    return false;
  }
  this->Live = warp;
  this->State = GrabState::Grabbed;
  this->Held.reset();
  this->CurrentRibbon = start;
  this->LiveProblem.clear();
  this->WarnedInversion = false;
  this->UpdateLiveInformation();
  std::ostringstream text;
  text << "Grabbed (" << Describe(this->Parameters) << "): ";
  if (this->ProxyDrag)
  {
    text << "dragging a copy of " << this->GetProxySurface()->GetNumberOfPolys() << " triangles, "
         << this->ProxyFilter->GetNumberOfBoundPoints()
         << " of its points inside the region of influence (the whole surface at release)";
  }
  else
  {
    text << this->LiveFilter->GetNumberOfBoundPoints() << " points inside the region of influence";
  }
  this->Report(MessageSeverity::Info, text.str());
  this->Changed();
  return true;
}

bool BenderSession::MoveFinal(const RibbonSpec& final)
{
  if (this->State != GrabState::Grabbed || this->Busy)
  {
    return false;
  }
  WarpSpec candidate = this->Live;
  std::string problem;
  try
  {
    candidate.final = this->Unwrapper.Unwrap(final);
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  if (!problem.empty() || !this->SetLiveWarp(candidate, problem))
  {
    this->LiveProblem = problem;
    this->Changed();
    return false;
  }
  this->Unwrapper.Accept(candidate.final);
  this->Live = candidate;
  this->DropHeld(); // the held result no longer matches what is shown
  this->LiveProblem.clear();
  this->UpdateLiveInformation();
  this->Changed();
  return true;
}

bool BenderSession::Release()
{
  return this->RunNow(this->BeginRelease());
}

void BenderSession::CancelGrab(const std::string& reason)
{
  if (this->State != GrabState::Grabbed || this->Busy)
  {
    return;
  }
  this->State = GrabState::Idle;
  this->Held.reset();
  this->ShowCommitted(nullptr);
  // The ribbon goes back onto the committed surface, where it was grabbed.
  this->SetRibbonInformation(this->Live.initial);
  this->Report(MessageSeverity::Warning,
    "The live warp was cancelled (" + reason + "); the last committed shape is kept");
  this->Changed();
}

bool BenderSession::Undo()
{
  if (this->RefuseWhenBusy("Undo"))
  {
    return false;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Undo: release or cancel the grab first");
    return false;
  }
  const std::vector<WarpSpec> warps = this->History.CommittedWarps();
  if (!this->History.Undo())
  {
    this->Report(MessageSeverity::Info, "Nothing to undo");
    return false;
  }
  ++this->ChangeCount;
  // The ribbon goes back to where the undone warp grabbed it.
  this->SetRibbonInformation(warps.back().initial);
  this->State = GrabState::Idle;
  this->ShowCommitted(nullptr);
  this->Report(MessageSeverity::Info, "Undid warp " + std::to_string(this->History.Position() + 1));
  this->Autosave();
  this->Changed();
  return true;
}

bool BenderSession::Redo()
{
  if (this->RefuseWhenBusy("Redo"))
  {
    return false;
  }
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
  ++this->ChangeCount;
  this->SetRibbonInformation(this->History.CommittedWarps().back().final);
  this->State = GrabState::Idle;
  this->ShowCommitted(nullptr);
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
  this->MarkSaved();
  this->Report(MessageSeverity::Info,
    "Saved the plan (" + std::to_string(this->History.Position()) + " warps) to " + FileName(path));
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
  const std::vector<WarpSpec> committed = this->History.CommittedWarps();
  if (plan.warps.empty() || committed.size() < plan.warps.size())
  {
    return false;
  }
  WarpPlan last;
  last.warps.assign(
    committed.end() - static_cast<std::ptrdiff_t>(plan.warps.size()), committed.end());
  return SerializeWarpPlan(last) == SerializeWarpPlan(plan);
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
        WriteMesh(this->History.Original(), sourceCopy);
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
  return this->RunNow(this->BeginRecover(sessionPath));
}

// ---- Jobs ----

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
  catch (const std::exception& e)
  {
    this->Report(MessageSeverity::Error, e.what());
    return nullptr;
  }
  return this->BeginReplay(plan, FileName(path));
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
  job->Name = FileName(sessionPath);
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
  bool proceedOnProblems)
{
  if (!this->HasSurface())
  {
    this->Report(MessageSeverity::Error, FileName(path) + ": there is no surface to export");
    return nullptr;
  }
  if (!this->SourcePath.empty() && SameFile(path, this->SourcePath))
  {
    this->Report(MessageSeverity::Error,
      FileName(path) + ": refusing to overwrite the input surface; choose another file");
    return nullptr;
  }
  auto job = this->BeginCheck();
  job->JobKind = SessionJob::Kind::Export;
  job->Title = "Checking and exporting";
  job->Name = FileName(path);
  job->Path = path;
  job->Options = options;
  job->Options.output = path;
  job->Options.protectedPath = this->SourcePath;
  job->Options.sourceName = this->SurfaceName;
  // Export writes only when the check is clean or the caller accepted its problems.
  job->ProceedOnProblems = proceedOnProblems;
  return job;
}

void SessionJob::Run(const ProgressReporter& progress)
{
  try
  {
    switch (this->JobKind)
    {
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
        catch (const std::exception& e)
        {
          throw InputError(std::string("the session's source cannot be read: ") + e.what());
        }
        progress.ThrowIfCancelled("recovery");
      }
        [[fallthrough]];
      case Kind::Release:
      case Kind::Replay:
        if (!this->Plan.warps.empty())
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
            this->Check = CheckCommit(this->Input, same, warp, options);
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
  catch (const std::exception& e)
  {
    this->Result = Outcome::Failed;
    this->Problem = e.what();
  }
}

bool BenderSession::Finish(SessionJob& job)
{
  const bool warps = job.JobKind == SessionJob::Kind::Release ||
    job.JobKind == SessionJob::Kind::Replay || job.JobKind == SessionJob::Kind::Recover;
  if (warps)
  {
    this->Busy = false;
  }
  switch (job.JobKind)
  {
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
  this->Report(MessageSeverity::Info, text.str());
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
  for (std::size_t i = 0; i < job.Plan.warps.size(); ++i)
  {
    this->History.Commit(job.Plan.warps[i], job.Steps.steps[i]);
  }
  if (!job.Plan.warps.empty())
  {
    ++this->ChangeCount;
    this->SetRibbonInformation(job.Plan.warps.back().final);
  }
  this->State = GrabState::Idle;
  this->ShowCommitted(nullptr);
  this->Report(MessageSeverity::Info,
    "Replayed " + std::to_string(job.Plan.warps.size()) + " warps of " + job.Name);
  this->Autosave();
  this->Changed();
  return true;
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
  const std::string name = job.SurfaceName.empty() ? FileName(job.SourcePath) : job.SurfaceName;
  bool recovered = this->SetSurface(job.Input, name, ownCopy ? std::string() : job.SourcePath);
  if (recovered)
  {
    for (std::size_t i = 0; i < job.Plan.warps.size(); ++i)
    {
      this->History.Commit(job.Plan.warps[i], job.Steps.steps[i]);
    }
    if (!job.Plan.warps.empty())
    {
      ++this->ChangeCount; // recovered warps are in no saved plan
      this->SetRibbonInformation(job.Plan.warps.back().final);
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
  this->Report(MessageSeverity::Info,
    "Recovered the session: " + std::to_string(job.Plan.warps.size()) + " warps");
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
    this->Report(MessageSeverity::Warning, "Export not written: the check found problems");
    return false;
  }
  std::string names;
  for (const std::string& file : job.Written)
  {
    names += (names.empty() ? "" : ", ") + FileName(file);
  }
  this->Report(MessageSeverity::Info,
    "Exported " + names + " (frame " + (job.Options.frame == StlFrame::RAS ? "RAS" : "LPS") +
      ", unit " + job.Options.unit + ")");
  return true;
}

} // namespace bender
