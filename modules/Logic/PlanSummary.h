#ifndef PlanSummary_h
#define PlanSummary_h

#include "StringUtil.h"
#include "WarpPlan.h"

#include <string>

namespace bender
{
/// What a plan (or the history up to its current step) holds, for a status or panel line:
/// "2 warps committed", or "2 warps committed, prepared for CFD" when a Prepare for CFD step is
/// among its steps.
inline std::string PlanSummary(const WarpPlan& plan)
{
  std::string text = CountOf(plan.warps.size(), "warp") + " committed";
  if (!plan.cfdSteps.empty())
  {
    text += ", prepared for CFD";
  }
  return text;
}
}

#endif
