#include "BenderSession.h"

// The lumen guard's centerlines before the bend, kept for the committed surface they measure.

namespace bender
{

void BenderSession::SetLumenBaseline(vtkPolyData* surface,
  std::shared_ptr<const CenterlineResult> centerlines)
{
  this->LumenBaseline = surface ? std::move(centerlines) : nullptr;
  this->LumenBaselineSurface = this->LumenBaseline ? surface : nullptr;
  this->LumenBaselineTime = this->LumenBaseline ? surface->GetMTime() : 0;
}

std::shared_ptr<const CenterlineResult> BenderSession::LumenBaselineOf(vtkPolyData* surface) const
{
  if (!surface || surface != this->LumenBaselineSurface ||
    surface->GetMTime() != this->LumenBaselineTime)
  {
    return nullptr;
  }
  return this->LumenBaseline;
}

void BenderSession::KeepLumenAfter(const WarpSpec& warp, const CommitCheck& check)
{
  this->SetLumenBaseline(this->History.Current(), warp.subdivision ? nullptr : check.lumen.after);
}

} // namespace bender
