#include "RadiusSearch.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>

namespace bender
{

RadiusSearchResult FindPassingRadius(vtkPolyData* before,
  const WarpSpec& warp,
  const RadiusSearchOptions& options)
{
  if (!before)
  {
    throw InputError("Reduce R: no surface");
  }
  if (!(std::isfinite(options.lowest) && options.lowest > 0.0))
  {
    throw InputError("Reduce R: the vessel's radius must be a positive number");
  }
  RadiusSearchResult result;
  if (!(warp.radius > options.lowest))
  {
    return result;
  }
  const int count = std::clamp(options.candidates, 1, 20);
  std::shared_ptr<const CenterlineResult> lumenBefore = options.lumenBefore;
  CommitCheckOptions meshOnly = options.check;
  meshOnly.lumen.enabled = false;
  WarpSpec trial = warp;
  trial.subdivision.reset();
  ApplyPlanOptions apply;
  apply.planName = "Reduce R";
  apply.progress = options.progress;
  for (int k = 1; k <= count; ++k)
  {
    // Geometric steps; the last is the floor itself; rounded up to the step.
    double radius = k == count
      ? options.lowest
      : std::max(
          options.lowest, warp.radius * std::pow(options.lowest / warp.radius, double(k) / count));
    if (options.step > 0.0)
    {
      radius = std::ceil(radius / options.step - 1e-9) * options.step;
      radius = radius < options.lowest ? radius + options.step : radius;
    }
    if (radius >= warp.radius || (!result.tried.empty() && radius >= result.tried.back().first))
    {
      continue; // rounded onto R or onto the radius tried before
    }
    trial.radius = radius;
    options.progress.Report("trying R", double(k - 1) / count);
    options.progress.ThrowIfCancelled("Reduce R");
    vtkSmartPointer<vtkPolyData> after;
    try
    {
      after = ApplyWarp(before, trial, apply);
    }
    catch (const InputError& e)
    {
      result.tried.emplace_back(trial.radius, e.what()); // an invalid warp at this R
      continue;
    }
    // The cheap checks first; the lumen's centerlines only for a warp that passes them.
    result.check = CheckCommit(before, after, trial, meshOnly);
    if (result.check.Passed() && options.check.lumen.enabled)
    {
      if (!lumenBefore)
      {
        lumenBefore = std::make_shared<const CenterlineResult>(LumenCenterlines(before));
      }
      options.progress.ThrowIfCancelled("Reduce R");
      result.check = CheckCommit(before, after, trial, options.check, lumenBefore.get());
    }
    result.tried.emplace_back(trial.radius, result.check.Summary());
    if (result.check.Passed())
    {
      result.found = true;
      result.radius = trial.radius;
      return result;
    }
  }
  return result;
}

} // namespace bender
