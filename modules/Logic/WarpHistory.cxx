#include "WarpHistory.h"

#include "PolyDataCopy.h"

#include <vtkPolyData.h>

namespace bender
{

void WarpHistory::Reset(vtkPolyData* original)
{
  this->Surfaces.clear();
  this->Warps.clear();
  this->Index = 0;
  if (original)
  {
    this->Surfaces.push_back(DeepCopyOf(original));
  }
}

void WarpHistory::Commit(const WarpSpec& warp, vtkPolyData* result)
{
  if (this->Surfaces.empty() || !result)
  {
    return;
  }
  this->Surfaces.resize(this->Index + 1);
  this->Warps.resize(this->Index);
  this->Surfaces.push_back(DeepCopyOf(result));
  this->Warps.push_back(warp);
  ++this->Index;
}

bool WarpHistory::Undo()
{
  if (!this->CanUndo())
  {
    return false;
  }
  --this->Index;
  return true;
}

bool WarpHistory::Redo()
{
  if (!this->CanRedo())
  {
    return false;
  }
  ++this->Index;
  return true;
}

vtkPolyData* WarpHistory::Current() const
{
  return this->Surfaces.empty() ? nullptr : this->Surfaces[this->Index].GetPointer();
}

vtkPolyData* WarpHistory::Original() const
{
  return this->Surfaces.empty() ? nullptr : this->Surfaces.front().GetPointer();
}

std::vector<WarpSpec> WarpHistory::CommittedWarps() const
{
  return std::vector<WarpSpec>(this->Warps.begin(), this->Warps.begin() + this->Index);
}

} // namespace bender
