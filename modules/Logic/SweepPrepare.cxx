#include "SweepPrepare.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "MeshIO.h"
#include "PrepareForCfd.h"
#include "RibbonLengthChange.h"
#include "StringUtil.h"
#include "VesselMeasures.h"
#include "WarpedPoints.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
std::string BaseName(const std::string& path)
{
  return fs::path(path).filename().string();
}

// The measures of the centerline branch nearest `bendPoint`.
void MeasureBend(vtkPolyData* centerlines, const Vec3& bendPoint, SweepMeasures& measures)
{
  if (!centerlines || centerlines->GetNumberOfCells() == 0 ||
    !centerlines->GetPointData()->GetArray("MaximumInscribedSphereRadius"))
  {
    return;
  }
  const VesselMeasurements all = MeasureBranches(centerlines);
  double best = std::numeric_limits<double>::infinity();
  for (vtkIdType c = 0; c < centerlines->GetNumberOfCells(); ++c)
  {
    vtkIdType count = 0;
    const vtkIdType* ids = nullptr;
    centerlines->GetCellPoints(c, count, ids);
    for (vtkIdType k = 0; k < count; ++k)
    {
      double p[3];
      centerlines->GetPoint(ids[k], p);
      const double d = Distance(Vec3{ p[0], p[1], p[2] }, bendPoint);
      if (d < best && static_cast<std::size_t>(c) < all.branches.size())
      {
        best = d;
        measures.bendAngle = all.branches[static_cast<std::size_t>(c)].bendAngle;
        measures.minRadius = all.branches[static_cast<std::size_t>(c)].minRadius;
      }
    }
  }
}

// The largest change of a ribbon's wire length among the plan's warps, %.
double LengthChange(const WarpPlan& plan)
{
  double largest = 0.0;
  for (const WarpSpec& warp : plan.warps)
  {
    const double change = 100.0 * RibbonLengthChange(warp);
    largest = std::abs(change) > std::abs(largest) ? change : largest;
  }
  return largest;
}
} // namespace

SweepBase PrepareSweepBase(const SweepBaseOptions& options, const ProgressReporter& progress)
{
  SweepBase base;
  base.surfaceName = BaseName(options.surfacePath);
  progress.Report("original", 0.0);
  base.surface = ReadMesh(options.surfacePath);
  PrepareForCfdOptions prepare = CfdStepOptions(options.step);
  prepare.inputName = base.surfaceName;
  const PrepareForCfdResult original = PrepareForCfd(base.surface, prepare, progress);
  base.step = ResolvedCfdStep(options.step, original);
  for (const CfdEnd& end : original.ends)
  {
    base.endNames.push_back(end.name);
  }
  base.bendPoint = options.bendPoint;
  MeshCheckOptions check;
  check.maxExamples = 0;
  base.selfIntersections = CheckMesh(base.surface, nullptr, check).selfIntersections;

  // The original's case, thrown away: the cell size and flow rate its defaults resolve to are
  // those of every candidate (the same mesh resolution and the same flow through each shape).
  progress.ThrowIfCancelled("original");
  base.caseOptions = options.caseOptions;
  CfdCaseOptions scratch = options.caseOptions;
  scratch.caseDirectory = options.scratchFolder;
  scratch.force = true;
  scratch.sourceName = base.surfaceName;
  const CfdCaseResult written = WriteOpenFoamCase(original, scratch);
  std::error_code ec;
  fs::remove_all(options.scratchFolder, ec);
  base.caseOptions.cellSize = written.cellSize;
  base.caseOptions.cellsAcross = written.grading.cellsAcross;
  base.caseOptions.flowRate = written.inletFlowRate;
  base.caseOptions.velocity = 0.0;
  base.caseOptions.inlet = written.inlet;
  base.caseOptions.sourceName = base.surfaceName;
  return base;
}

PreparedCandidate PrepareCandidate(const SweepBase& base,
  const SweepCandidate& candidate,
  const std::string& caseDirectory,
  const ProgressReporter& progress)
{
  PreparedCandidate prepared;
  const std::string where = candidate.id;
  vtkSmartPointer<vtkPolyData> warped = base.surface;
  CfdStep step = base.step;
  Vec3 bendPoint = base.bendPoint;
  if (!candidate.original)
  {
    progress.Report("warp " + candidate.id, 0.0);
    ApplyPlanOptions apply;
    apply.planName = candidate.id;
    apply.progress.cancel = progress.cancel;
    warped = ApplyPlan(base.surface, candidate.plan, apply).output;
    progress.Report("check " + candidate.id, 0.0);
    MeshCheckOptions check;
    check.maxExamples = 1;
    const bool samePoints = warped->GetNumberOfPoints() == base.surface->GetNumberOfPoints() &&
      warped->GetNumberOfCells() == base.surface->GetNumberOfCells();
    const MeshCheckReport report =
      CheckMesh(warped, samePoints ? base.surface.GetPointer() : nullptr, check);
    if (report.flippedTriangles > 0)
    {
      prepared.rejected = true;
      prepared.reason = "the warp folds the surface (" +
        CountOf(static_cast<std::size_t>(report.flippedTriangles), "flipped triangle") + ")";
    }
    else if (report.selfIntersections > base.selfIntersections)
    {
      prepared.rejected = true;
      prepared.reason = "the warped surface intersects itself (" +
        CountOf(
          static_cast<std::size_t>(report.selfIntersections - base.selfIntersections), "new pair") +
        " of triangles)";
    }
    if (prepared.rejected)
    {
      return prepared;
    }
    std::vector<Vec3*> points = CfdStepPoints(step);
    points.push_back(&bendPoint);
    CarryForward(points, candidate.plan.warps, candidate.plan.warps.size());
    prepared.measures.lengthChange = LengthChange(candidate.plan);
  }
  else
  {
    prepared.measures.lengthChange = 0.0;
  }

  progress.ThrowIfCancelled("prepare " + candidate.id);
  PrepareForCfdOptions options = CfdStepOptions(step);
  options.inputName = base.surfaceName + " (" + where + ")";
  PrepareForCfdResult result;
  try
  {
    result = PrepareForCfd(warped, options, progress);
  }
  catch (const Cancelled&)
  {
    throw;
  }
  catch (const InputError& e)
  {
    prepared.rejected = true;
    prepared.reason = std::string("cannot be clipped as the original: ") + e.what();
    return prepared;
  }
  prepared.warnings = result.warnings;
  std::vector<std::string> names;
  for (const CfdEnd& end : result.ends)
  {
    names.push_back(end.name);
  }
  for (const std::string& name : base.endNames)
  {
    if (std::find(names.begin(), names.end(), name) == names.end())
    {
      prepared.rejected = true;
      prepared.reason = "the end " + name + " of the original is not found after the warp";
      return prepared;
    }
  }
  if (names.size() != base.endNames.size())
  {
    prepared.rejected = true;
    prepared.reason = "the warped surface has " + CountOf(names.size(), "end") + ", the original " +
      std::to_string(base.endNames.size());
    return prepared;
  }
  MeasureBend(result.centerlines, bendPoint, prepared.measures);

  progress.ThrowIfCancelled("case " + candidate.id);
  CfdCaseOptions caseOptions = base.caseOptions;
  caseOptions.caseDirectory = caseDirectory;
  caseOptions.force = true;
  caseOptions.sourceName = options.inputName;
  WriteOpenFoamCase(result, caseOptions);
  return prepared;
}

} // namespace bender
