#include "ApplyPlan.h"

#include "GeometryErrors.h"
#include "RibbonWarp.h"
#include "vtkBenderAdaptiveSubdivisionFilter.h"
#include "vtkBenderWarpFilter.h"

#include <vtkNew.h>
#include <vtkPoints.h>

#include <exception>

namespace bender
{

namespace
{
// A shallow copy of `input` whose points are double: every warp then computes and stores in
// double, with or without subdivision (the subdivision filter always writes double).
vtkSmartPointer<vtkPolyData> WithDoublePoints(vtkPolyData* input)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(input);
  vtkPoints* points = input->GetPoints();
  if (points && points->GetDataType() != VTK_DOUBLE)
  {
    vtkNew<vtkPoints> converted;
    converted->SetDataTypeToDouble();
    converted->DeepCopy(points);
    copy->SetPoints(converted);
  }
  return copy;
}

std::string PlanName(const ApplyPlanOptions& options)
{
  return options.planName.empty() ? std::string("plan") : options.planName;
}

std::string Where(const ApplyPlanOptions& options, std::size_t index)
{
  return PlanName(options) + ": warps[" + std::to_string(index) + "]";
}

PrepareForCfdResult PrepareStep(vtkPolyData* input,
  const CfdStep& step,
  const ApplyPlanOptions& options,
  const std::string& where,
  vtkPolyData* centerlines)
{
  if (!input)
  {
    throw InputError(where + ": no input surface");
  }
  PrepareForCfdOptions prepare = CfdStepOptions(step);
  prepare.centerlines = centerlines;
  prepare.inputName = where;
  return PrepareForCfd(input, prepare, options.progress);
}

vtkSmartPointer<vtkPolyData> ApplyOne(vtkPolyData* input,
  const WarpSpec& warp,
  const ApplyPlanOptions& options,
  const std::string& where,
  WarpStepInfo& info)
{
  if (!input)
  {
    throw InputError(where + ": no input surface");
  }
  info = WarpStepInfo{};
  info.inputPoints = static_cast<long long>(input->GetNumberOfPoints());
  info.trianglesBefore =
    static_cast<long long>(input->GetNumberOfPolys() + input->GetNumberOfStrips());
  const vtkSmartPointer<vtkPolyData> source = WithDoublePoints(input);
  auto output = vtkSmartPointer<vtkPolyData>::New();
  if (warp.subdivision)
  {
    // The subdivision filter performs the exact warp itself: the warp is evaluated once.
    try
    {
      const RibbonWarp validated(warp);
      info.flipOccurred = validated.FlipOccurred();
      info.warning = validated.SpaceInversionWarning();
    }
    catch (const GeometryError& e)
    {
      throw InputError(where + ": " + e.what());
    }
    vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivide;
    subdivide->SetInputData(source);
    subdivide->SetWarp(warp);
    subdivide->SetPrecision(options.precision);
    subdivide->SetBlendMode(options.blend);
    subdivide->Update();
    if (!subdivide->GetLastError().empty())
    {
      throw InputError(where + ": subdivision: " + subdivide->GetLastError());
    }
    output->ShallowCopy(subdivide->GetOutput());
    info.subdivided = true;
    info.tolerance = subdivide->GetTolerance();
    info.passesRun = subdivide->GetNumberOfPassesRun();
    info.converged = subdivide->GetConverged();
  }
  else
  {
    vtkNew<vtkBenderWarpFilter> filter;
    filter->SetInputData(source);
    filter->SetWarp(warp);
    filter->SetPrecision(options.precision);
    filter->SetBlendMode(options.blend);
    filter->Update();
    if (!filter->GetLastError().empty())
    {
      throw InputError(where + ": " + filter->GetLastError());
    }
    output->ShallowCopy(filter->GetOutput());
    info.boundPoints = static_cast<long long>(filter->GetNumberOfBoundPoints());
    info.flipOccurred = filter->GetFlipOccurred();
    info.warning = filter->GetLastWarning();
  }
  info.trianglesAfter =
    static_cast<long long>(output->GetNumberOfPolys() + output->GetNumberOfStrips());
  return output;
}
} // namespace

vtkSmartPointer<vtkPolyData> ApplyWarp(vtkPolyData* input,
  const WarpSpec& warp,
  const ApplyPlanOptions& options,
  WarpStepInfo* info)
{
  options.progress.ThrowIfCancelled("warp");
  WarpStepInfo local;
  const std::string where = options.planName.empty() ? std::string("warp") : options.planName;
  auto output = ApplyOne(input, warp, options, where, local);
  if (info)
  {
    *info = local;
  }
  return output;
}

PrepareForCfdResult ApplyCfdStep(vtkPolyData* input,
  const CfdStep& step,
  const ApplyPlanOptions& options,
  vtkPolyData* centerlines)
{
  options.progress.ThrowIfCancelled("Prepare for CFD");
  const std::string where =
    options.planName.empty() ? std::string("prepareForCfd") : options.planName;
  return PrepareStep(input, step, options, where, centerlines);
}

ApplyPlanResult ApplyPlan(vtkPolyData* input, const WarpPlan& plan, const ApplyPlanOptions& options)
{
  ApplyPlanResult result;
  vtkSmartPointer<vtkPolyData> current = input;
  for (const PlanStepRef& ref : PlanOrder(plan))
  {
    const std::size_t i = ref.index;
    if (ref.cfd)
    {
      options.progress.ThrowIfCancelled("Prepare for CFD");
      const std::string where = PlanName(options) + ": prepareForCfd[" + std::to_string(i) + "]";
      result.prepared.push_back(PrepareStep(current, plan.cfdSteps[i], options, where, nullptr));
      current = result.prepared.back().surface;
      continue;
    }
    const std::string stage =
      "warp " + std::to_string(i + 1) + " of " + std::to_string(plan.warps.size());
    options.progress.ThrowIfCancelled(stage);
    options.progress.Report(stage, 0.0);
    WarpStepInfo info;
    current = ApplyOne(current, plan.warps[i], options, Where(options, i), info);
    result.steps.push_back(current);
    result.info.push_back(info);
    options.progress.Report(stage, 1.0);
  }
  if (result.steps.empty() && result.prepared.empty())
  {
    result.output = vtkSmartPointer<vtkPolyData>::New();
    if (input)
    {
      result.output->DeepCopy(WithDoublePoints(input));
    }
  }
  else
  {
    result.output = current;
  }
  return result;
}

} // namespace bender
