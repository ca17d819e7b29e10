#include "LumenGuard.h"

#include "BenderErrors.h"
#include "VesselMeasures.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticPointLocator.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace bender
{

namespace
{

std::string Percent(double fraction)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f %%", 100.0 * fraction);
  return text;
}

std::string Millimetres(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", value);
  return text;
}

std::string OutletsText(const std::set<int>& outlets)
{
  std::string text;
  for (int outlet : outlets)
  {
    text += (text.empty() ? "" : ", ") + std::to_string(outlet);
  }
  return text;
}

// The branch a name gives the user: its id after the bend and the ends it leads to.
std::string BranchName(const BranchLumenChange& change)
{
  std::string name = "branch";
  if (change.branchId >= 0)
  {
    name += " " + std::to_string(change.branchId);
  }
  if (!change.outlets.empty())
  {
    name += std::string(" (to end") + (change.outlets.size() > 1 ? "s " : " ") +
      OutletsText(change.outlets) + ")";
  }
  return name;
}

// The samples of each polyline of `branches` with at least two points, in the order
// MeasureBranches measures them (its index is the branch's index).
std::vector<std::vector<Point3>> BranchSamples(vtkPolyData* branches)
{
  std::vector<std::vector<Point3>> samples;
  vtkCellArray* lines = branches ? branches->GetLines() : nullptr;
  if (!lines)
  {
    return samples;
  }
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  for (lines->InitTraversal(); lines->GetNextCell(count, ids);)
  {
    if (count < 2)
    {
      continue;
    }
    std::vector<Point3> points(static_cast<std::size_t>(count));
    for (vtkIdType i = 0; i < count; ++i)
    {
      branches->GetPoint(ids[i], points[static_cast<std::size_t>(i)].data());
    }
    samples.push_back(std::move(points));
  }
  return samples;
}

// Which branches (indices of BranchSamples) are nearest to one of `moved`.
std::vector<bool> MovedBranches(vtkPolyData* branches, const std::vector<Point3>& moved)
{
  const std::vector<std::vector<Point3>> samples = BranchSamples(branches);
  std::vector<bool> touched(samples.size(), false);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  std::vector<std::size_t> owner;
  for (std::size_t b = 0; b < samples.size(); ++b)
  {
    for (const Point3& p : samples[b])
    {
      points->InsertNextPoint(p.data());
      owner.push_back(b);
    }
  }
  if (owner.empty() || moved.empty())
  {
    return touched;
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(cloud);
  locator->BuildLocator();
  for (const Point3& p : moved)
  {
    const vtkIdType nearest = locator->FindClosestPoint(p.data());
    if (nearest >= 0)
    {
      touched[owner[static_cast<std::size_t>(nearest)]] = true;
    }
  }
  return touched;
}

// The points of `before` that differ in `after` (same point count).
std::vector<Point3> MovedPoints(vtkPolyData* before, vtkPolyData* after)
{
  std::vector<Point3> moved;
  const vtkIdType n = before->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    Point3 a, b;
    before->GetPoint(i, a.data());
    after->GetPoint(i, b.data());
    if (a != b)
    {
      moved.push_back(a);
    }
  }
  return moved;
}

} // namespace

std::string LumenCheck::Summary() const
{
  if (!this->checked)
  {
    return "lumen not measured: " + this->notMeasured;
  }
  if (this->problems.empty())
  {
    return "no branch narrowed by more than " + Percent(this->maxNarrowing);
  }
  std::string text;
  for (const std::string& problem : this->problems)
  {
    text += (text.empty() ? "" : "; ") + problem;
  }
  return text;
}

CenterlineResult LumenCenterlines(vtkPolyData* surface, const std::vector<Point3>& seeds)
{
  CenterlineOptions options;
  options.seeds = seeds;
  return ComputeCenterlines(surface, options);
}

LumenCheck CompareLumen(const CenterlineResult& before,
  const CenterlineResult& after,
  const std::vector<Point3>& moved,
  bool allMoved,
  double maxNarrowing)
{
  LumenCheck check;
  check.maxNarrowing = maxNarrowing;
  if (!before.ok)
  {
    check.notMeasured = "no centerline before the bend (" + before.message + ")";
    return check;
  }
  check.checked = true;
  const std::vector<bool> touched =
    allMoved ? std::vector<bool>() : MovedBranches(before.branches, moved);
  if (!after.ok)
  {
    check.problems.push_back(
      "the lumen's centerline is lost after the bend (" + after.message + "): is it closed?");
    return check;
  }
  const VesselComparison comparison = CompareVessels(before.branches, after.branches);
  double worst = -HUGE_VAL;
  for (const BranchChange& pair : comparison.pairs)
  {
    if (pair.beforeIndex < 0)
    {
      continue; // a branch only after the bend: nothing to compare with
    }
    const BranchMeasures& b = comparison.before.branches[pair.beforeIndex];
    BranchLumenChange change;
    change.outlets = b.outlets;
    change.beforeMinRadius = b.minRadius;
    change.moved = allMoved ||
      (static_cast<std::size_t>(pair.beforeIndex) < touched.size() &&
        touched[static_cast<std::size_t>(pair.beforeIndex)]);
    if (pair.afterIndex < 0)
    {
      if (change.moved)
      {
        change.tooNarrow = true;
        check.problems.push_back(
          BranchName(change) + " has no centerline after the bend: is its lumen closed?");
      }
      check.branches.push_back(change);
      continue;
    }
    const BranchMeasures& a = comparison.after.branches[pair.afterIndex];
    change.branchId = a.branchId;
    change.afterMinRadius = a.minRadius;
    change.narrowest = a.minRadiusPosition;
    change.narrowing = b.minRadius > 0.0 ? 1.0 - a.minRadius / b.minRadius : 0.0;
    change.tooNarrow = change.moved && change.narrowing > maxNarrowing;
    if (change.moved && change.narrowing > worst)
    {
      worst = change.narrowing;
      check.worst = static_cast<int>(check.branches.size());
    }
    if (change.tooNarrow)
    {
      check.problems.push_back(BranchName(change) + " narrowed by " + Percent(change.narrowing) +
        " (minimal radius " + Millimetres(change.beforeMinRadius) + " -> " +
        Millimetres(change.afterMinRadius) + " mm; at most " + Percent(maxNarrowing) + ")");
    }
    check.branches.push_back(change);
  }
  return check;
}

LumenCheck CheckLumen(vtkPolyData* before,
  vtkPolyData* after,
  const LumenGuardOptions& options,
  const CenterlineResult* beforeCenterlines)
{
  if (!before || !after)
  {
    throw InputError("lumen guard: a surface is missing");
  }
  if (!(options.maxNarrowing >= 0.0 && options.maxNarrowing < 1.0))
  {
    throw InputError("lumen guard: the largest narrowing must be in [0, 1), a fraction (" +
      std::to_string(options.maxNarrowing) + ")");
  }
  const auto start = std::chrono::steady_clock::now();
  CenterlineResult computed;
  if (!beforeCenterlines)
  {
    computed = LumenCenterlines(before);
    beforeCenterlines = &computed;
  }
  auto afterCenterlines = std::make_shared<CenterlineResult>();
  if (beforeCenterlines->ok)
  {
    *afterCenterlines =
      LumenCenterlines(after, MatchedSeeds(before, after, beforeCenterlines->endpoints));
  }
  const bool samePoints = before->GetNumberOfPoints() == after->GetNumberOfPoints();
  LumenCheck check = CompareLumen(*beforeCenterlines,
    *afterCenterlines,
    samePoints ? MovedPoints(before, after) : std::vector<Point3>(),
    !samePoints,
    options.maxNarrowing);
  check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (beforeCenterlines->ok)
  {
    check.after = std::move(afterCenterlines);
  }
  return check;
}

std::string LumenCheckText(const LumenCheck& check)
{
  std::ostringstream out;
  if (!check.checked)
  {
    out << "lumen: not measured (" << check.notMeasured << ")\n";
    return out.str();
  }
  out << "lumen (minimal inscribed radius per branch, before -> after, mm):\n";
  for (const BranchLumenChange& change : check.branches)
  {
    out << "  " << BranchName(change) << ": " << Millimetres(change.beforeMinRadius) << " -> "
        << (change.branchId >= 0 ? Millimetres(change.afterMinRadius) : std::string("none")) << " ("
        << (change.narrowing > 0.0 ? "-" : "+") << Percent(std::fabs(change.narrowing)) << ")"
        << (change.moved ? "" : ", not moved by the bend") << (change.tooNarrow ? ", NARROWED" : "")
        << "\n";
  }
  out << "lumen: " << check.Summary() << "\n";
  return out.str();
}

nlohmann::ordered_json LumenCheckToJson(const LumenCheck& check)
{
  nlohmann::ordered_json json;
  json["checked"] = check.checked;
  if (!check.checked)
  {
    json["notMeasured"] = check.notMeasured;
  }
  json["maxNarrowing"] = check.maxNarrowing;
  json["passed"] = check.Passed();
  nlohmann::ordered_json branches = nlohmann::ordered_json::array();
  for (const BranchLumenChange& change : check.branches)
  {
    nlohmann::ordered_json b = { { "branchId", change.branchId },
      { "outlets", change.outlets },
      { "beforeMinRadius", change.beforeMinRadius } };
    if (change.branchId >= 0)
    {
      b["afterMinRadius"] = change.afterMinRadius;
      b["narrowing"] = change.narrowing;
      b["narrowest"] = change.narrowest;
    }
    b.update({ { "moved", change.moved }, { "tooNarrow", change.tooNarrow } });
    branches.push_back(b);
  }
  json["branches"] = branches;
  json["problems"] = check.problems;
  json["seconds"] = check.seconds;
  return json;
}

} // namespace bender
