#include "BenderSession.h"

#include "GeometryErrors.h"
#include "Ribbon.h"
#include "RibbonWarp.h"
#include "StringUtil.h"
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

// The bend gesture (grab, move, release, cancel, the held commit), the placed ribbon and its
// r_min, the warp parameters, and the undo history.

namespace bender
{

namespace
{

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

bool BenderSession::SetLiveWarp(const WarpSpec& warp, std::string& problem)
{
  // The one build per move: validates (convention 11) and is shared with the filter.
  std::shared_ptr<const RibbonWarp> built;
  try
  {
    ++this->WarpBuildCount;
    built = std::make_shared<const RibbonWarp>(warp);
  }
  catch (const GeometryError& e)
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
    catch (const GeometryError&)
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
  catch (const GeometryError& e)
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
  this->KeepLumenAfter(held.warp, held.check);
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
  catch (const GeometryError& e)
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
  catch (const GeometryError& e)
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
  const WarpSpec* undone = this->History.WarpOf(this->History.Position());
  const std::optional<RibbonSpec> grabbed =
    undone ? std::optional<RibbonSpec>(undone->initial) : std::nullopt;
  if (!this->History.Undo())
  {
    this->Report(MessageSeverity::Info,
      this->History.Position() == 0 ? std::string("Nothing to undo")
                                    : "Nothing more to undo: the surfaces of the " +
          CountOf(this->History.Position(), "older step") +
          " were let go to keep the history within " +
          std::to_string(this->History.MemoryLimit() >> 20) + " MiB (the plan keeps them)");
    return false;
  }
  ++this->ChangeCount;
  // The ribbon goes back to where the undone warp grabbed it (a Prepare for CFD moved none).
  if (grabbed)
  {
    this->SetRibbonInformation(*grabbed);
  }
  this->State = GrabState::Idle;
  this->ShowCommitted(nullptr);
  this->Report(MessageSeverity::Info,
    grabbed ? "Undid warp " + std::to_string(this->History.CommittedWarps().size() + 1)
            : std::string("Undid Prepare for CFD"));
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
  const WarpSpec* redone = this->History.WarpOf(this->History.Position());
  if (redone)
  {
    this->SetRibbonInformation(redone->final);
  }
  this->State = GrabState::Idle;
  this->ShowCommitted(nullptr);
  this->Report(MessageSeverity::Info,
    redone ? "Redid warp " + std::to_string(this->History.CommittedWarps().size())
           : std::string("Redid Prepare for CFD"));
  this->Autosave();
  this->Changed();
  return true;
}

bool BenderSession::CommitCfdStep(const CfdStep& step, vtkPolyData* result, bool replacesCurrent)
{
  if (this->RefuseWhenBusy("Prepare for CFD"))
  {
    return false;
  }
  if (this->State == GrabState::Grabbed)
  {
    this->Report(MessageSeverity::Error, "Prepare for CFD: release or cancel the grab first");
    return false;
  }
  if (!this->HasSurface() || !result || result->GetNumberOfPolys() == 0 ||
    (replacesCurrent && !this->GetCurrentCfdStep()))
  {
    this->Report(MessageSeverity::Error, "Prepare for CFD: nothing to commit");
    return false;
  }
  if (replacesCurrent)
  {
    this->History.Undo(); // prepared again: the new step takes the old one's place
  }
  this->History.Commit(step, result);
  ++this->ChangeCount;
  this->State = GrabState::Idle;
  this->Held.reset();
  this->ShowCommitted(nullptr);
  this->Autosave();
  this->Changed();
  return true;
}

} // namespace bender
