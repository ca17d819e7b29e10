#ifndef bender_WarpHistory_h
#define bender_WarpHistory_h

#include "WarpPlan.h"

#include <vtkSmartPointer.h>

#include <cstddef>
#include <vector>

class vtkPolyData;

namespace bender
{

/// The undo history of a session: the surface before any warp and after each committed warp,
/// kept as deep copies, so that undo and redo restore the exact coordinates (and topology,
/// after adaptive subdivision) rather than inverting a warp. The committed plan is the list of
/// warps up to the current position.
///
/// Memory: one copy of the surface per step. Surfaces handed out are owned by the history and
/// must not be modified.
class WarpHistory
{
public:
  /// Forgets everything; `original` (deep-copied) becomes step 0. nullptr clears.
  void Reset(vtkPolyData* original);
  bool Empty() const { return this->Surfaces.empty(); }

  /// Adds a step after the current one, dropping the redo steps. `result` is deep-copied.
  void Commit(const WarpSpec& warp, vtkPolyData* result);

  bool CanUndo() const { return this->Index > 0; }
  bool CanRedo() const { return this->Index + 1 < this->Surfaces.size(); }
  /// Steps back or forward; false (nothing changes) when there is no such step.
  bool Undo();
  bool Redo();

  /// The surface at the current step; nullptr when empty.
  vtkPolyData* Current() const;
  /// The surface before any warp; nullptr when empty.
  vtkPolyData* Original() const;
  /// Number of warps committed up to the current step, and in all (redo steps included).
  std::size_t Position() const { return this->Index; }
  std::size_t Size() const { return this->Warps.size(); }

  /// The warps up to the current step, in order.
  std::vector<WarpSpec> CommittedWarps() const;

private:
  std::vector<vtkSmartPointer<vtkPolyData>> Surfaces; // Surfaces[i]: after i warps
  std::vector<WarpSpec> Warps;                        // Warps[i]: from Surfaces[i] to [i + 1]
  std::size_t Index = 0;
};

} // namespace bender

#endif
