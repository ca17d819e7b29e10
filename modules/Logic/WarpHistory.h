#ifndef bender_WarpHistory_h
#define bender_WarpHistory_h

#include "WarpPlan.h"

#include <vtkSmartPointer.h>

#include <cstddef>
#include <variant>
#include <vector>

class vtkPolyData;

namespace bender
{

/// The undo history of a session: the surface before any step and after each committed step,
/// kept as deep copies, so that undo and redo restore the exact coordinates (and topology,
/// after adaptive subdivision or a Prepare for CFD) rather than inverting a step. A step is a
/// warp or a Prepare for CFD step (WarpPlan.h); the committed plan is the list of steps up to
/// the current position.
///
/// Memory: one copy of the surface per step, within a limit (MemoryLimit, 1 GiB by default:
/// about 200 steps of the 110,000-triangle demo vessel). Past it, the surfaces of the oldest
/// steps are let go, and undo stops at the oldest step whose surface before is kept; the plan
/// keeps every step. Never let go: the first surface, the current one and the one before it,
/// and the surfaces before and after each Prepare for CFD step (Original(), Previous()). So the
/// history holds at most MemoryLimit bytes plus those. Surfaces handed out are owned by the
/// history and must not be modified.
class WarpHistory
{
public:
  static constexpr std::size_t DefaultMemoryLimit = std::size_t(1) << 30;

  /// Forgets everything; `first` (deep-copied) becomes step 0. nullptr clears.
  void Reset(vtkPolyData* first);
  bool Empty() const { return this->Surfaces.empty(); }

  /// Adds a step after the current one, dropping the redo steps. `result` is deep-copied.
  void Commit(const WarpSpec& warp, vtkPolyData* result);
  /// The same for a Prepare for CFD step (its afterWarps is set from the history).
  void Commit(const CfdStep& step, vtkPolyData* result);

  bool CanUndo() const { return this->Index > 0 && this->Surfaces[this->Index - 1]; }
  bool CanRedo() const { return this->Index + 1 < this->Surfaces.size(); }
  /// Steps back or forward; false (nothing changes) when there is no such step.
  bool Undo();
  bool Redo();

  /// The surface at the current step; nullptr when empty.
  vtkPolyData* Current() const;
  /// The surface the current one is compared with (flips, the ghost, the vessels before and
  /// after): after the last Prepare for CFD step up to the current step (which changed the
  /// topology: a new start), else the first surface; nullptr when empty.
  vtkPolyData* Original() const;
  /// The surface before any step (what the plan applies to); nullptr when empty.
  vtkPolyData* First() const;
  /// The surface before the current step; nullptr at step 0.
  vtkPolyData* Previous() const;
  /// Number of steps up to the current one, and in all (redo steps included).
  std::size_t Position() const { return this->Index; }
  std::size_t Size() const { return this->Steps.size(); }
  /// The warp of step `step` (1-based, as Position()); nullptr for a Prepare for CFD step or
  /// no such step.
  const WarpSpec* WarpOf(std::size_t step) const;
  /// The Prepare for CFD step `step` (1-based); nullptr for a warp or no such step.
  const CfdStep* CfdStepOf(std::size_t step) const;

  /// The bytes the kept surfaces take (vtkPolyData::GetActualMemorySize, each surface once).
  std::size_t MemoryBytes() const;
  /// Sets the limit and lets go of the oldest surfaces beyond it (see the class comment).
  void SetMemoryLimit(std::size_t bytes);
  std::size_t MemoryLimit() const { return this->Limit; }
  /// The steps that can be undone from the current one (Position() when none was let go).
  std::size_t UndoableSteps() const;

  /// The warps up to the current step, in order.
  std::vector<WarpSpec> CommittedWarps() const;
  /// The steps from step `from` (0: all) up to the current one as a plan (warps and CFD steps,
  /// in order; the CFD steps' afterWarps count the warps from there).
  WarpPlan CommittedPlan(std::size_t from = 0) const;

private:
  using Step = std::variant<WarpSpec, CfdStep>;
  void Add(Step step, vtkPolyData* result);
  /// Whether Surfaces[i] is kept whatever the limit.
  bool Pinned(std::size_t i) const;
  void KeepWithinLimit();

  std::vector<vtkSmartPointer<vtkPolyData>> Surfaces; // Surfaces[i]: after i steps (or let go)
  std::vector<Step> Steps;                            // Steps[i]: from Surfaces[i] to [i + 1]
  std::size_t Index = 0;
  std::size_t Limit = DefaultMemoryLimit;
};

} // namespace bender

#endif
