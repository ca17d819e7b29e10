#include "WarpHistory.h"

#include "PolyDataCopy.h"

#include <vtkPolyData.h>

namespace bender
{

void WarpHistory::Reset(vtkPolyData* first)
{
  this->Surfaces.clear();
  this->Steps.clear();
  this->Index = 0;
  if (first)
  {
    this->Surfaces.push_back(DeepCopyOf(first));
  }
}

void WarpHistory::Add(Step step, vtkPolyData* result)
{
  if (this->Surfaces.empty() || !result)
  {
    return;
  }
  this->Surfaces.resize(this->Index + 1);
  this->Steps.resize(this->Index);
  this->Surfaces.push_back(DeepCopyOf(result));
  this->Steps.push_back(std::move(step));
  ++this->Index;
  this->KeepWithinLimit();
}

bool WarpHistory::Pinned(std::size_t i) const
{
  const auto isCfdStep = [this](std::size_t step)
  { return step < this->Steps.size() && std::holds_alternative<CfdStep>(this->Steps[step]); };
  // Surfaces[i] comes before step i and after step i - 1.
  return i == 0 || i + 1 >= this->Index || isCfdStep(i) || (i > 0 && isCfdStep(i - 1));
}

std::size_t WarpHistory::MemoryBytes() const
{
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < this->Surfaces.size(); ++i)
  {
    if (this->Surfaces[i])
    {
      bytes += std::size_t(this->Surfaces[i]->GetActualMemorySize()) * 1024;
    }
  }
  return bytes;
}

void WarpHistory::SetMemoryLimit(std::size_t bytes)
{
  this->Limit = bytes;
  this->KeepWithinLimit();
}

void WarpHistory::KeepWithinLimit()
{
  std::size_t bytes = this->MemoryBytes();
  for (std::size_t i = 0; i < this->Surfaces.size() && bytes > this->Limit; ++i)
  {
    if (this->Surfaces[i] && !this->Pinned(i))
    {
      bytes -= std::size_t(this->Surfaces[i]->GetActualMemorySize()) * 1024;
      this->Surfaces[i] = nullptr;
    }
  }
}

std::size_t WarpHistory::UndoableSteps() const
{
  std::size_t steps = 0;
  while (steps < this->Index && this->Surfaces[this->Index - steps - 1])
  {
    ++steps;
  }
  return steps;
}

void WarpHistory::Commit(const WarpSpec& warp, vtkPolyData* result)
{
  this->Add(warp, result);
}

void WarpHistory::Commit(const CfdStep& step, vtkPolyData* result)
{
  CfdStep placed = step;
  placed.afterWarps = this->CommittedWarps().size();
  this->Add(placed, result);
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
  for (std::size_t step = this->Index; step > 0; --step)
  {
    if (std::holds_alternative<CfdStep>(this->Steps[step - 1]))
    {
      return this->Surfaces[step].GetPointer();
    }
  }
  return this->First();
}

vtkPolyData* WarpHistory::First() const
{
  return this->Surfaces.empty() ? nullptr : this->Surfaces.front().GetPointer();
}

vtkPolyData* WarpHistory::Previous() const
{
  return this->Index == 0 ? nullptr : this->Surfaces[this->Index - 1].GetPointer();
}

const WarpSpec* WarpHistory::WarpOf(std::size_t step) const
{
  return step == 0 || step > this->Steps.size() ? nullptr
                                                : std::get_if<WarpSpec>(&this->Steps[step - 1]);
}

const CfdStep* WarpHistory::CfdStepOf(std::size_t step) const
{
  return step == 0 || step > this->Steps.size() ? nullptr
                                                : std::get_if<CfdStep>(&this->Steps[step - 1]);
}

std::vector<WarpSpec> WarpHistory::CommittedWarps() const
{
  std::vector<WarpSpec> warps;
  for (std::size_t i = 0; i < this->Index; ++i)
  {
    if (const WarpSpec* warp = std::get_if<WarpSpec>(&this->Steps[i]))
    {
      warps.push_back(*warp);
    }
  }
  return warps;
}

WarpPlan WarpHistory::CommittedPlan(std::size_t from) const
{
  WarpPlan plan;
  for (std::size_t i = from; i < this->Index; ++i)
  {
    if (const WarpSpec* warp = std::get_if<WarpSpec>(&this->Steps[i]))
    {
      plan.warps.push_back(*warp);
    }
    else
    {
      CfdStep step = std::get<CfdStep>(this->Steps[i]);
      step.afterWarps = plan.warps.size();
      plan.cfdSteps.push_back(step);
    }
  }
  return plan;
}

} // namespace bender
