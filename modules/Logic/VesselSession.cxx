#include "VesselSession.h"

#include "BenderSession.h"
#include "GeometryErrors.h"
#include "PolyDataCopy.h"
#include "RibbonWarp.h"
#include "Vec3.h"
#include "VesselArrayNames.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>

namespace bender
{
namespace
{

/// The points of one polyline cell of `lines`.
std::vector<vtkIdType> CellIds(vtkPolyData* lines, vtkIdType cell)
{
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  lines->GetLines()->GetCellAtId(cell, n, ids);
  return std::vector<vtkIdType>(ids, ids + n);
}

Vec3 PointOf(vtkPolyData* data, vtkIdType id)
{
  double p[3];
  data->GetPoint(id, p);
  return { p[0], p[1], p[2] };
}

} // namespace

void CenterlineJob::Run(const ProgressReporter& progress)
{
  try
  {
    progress.Report("centerlines", 0.0);
    if (this->OriginalResult)
    {
      this->Before = *this->OriginalResult;
    }
    else
    {
      this->Before = ComputeCenterlines(this->Original);
    }
    if (!this->Before.ok)
    {
      this->Problem = "Centerlines: " + this->Before.message;
      return;
    }
    progress.ThrowIfCancelled("centerlines");
    if (this->Current)
    {
      progress.Report("centerlines of the bent vessel", 0.5);
      CenterlineOptions options;
      options.seeds = MatchedSeeds(this->Original, this->Current, this->Before.endpoints);
      this->After = ComputeCenterlines(this->Current, options);
      if (!this->After->ok)
      {
        this->Problem = "Centerlines of the bent vessel: " + this->After->message;
        return;
      }
      progress.ThrowIfCancelled("centerlines");
      this->Comparison = CompareVessels(this->Before.branches, this->After->branches);
    }
    progress.Report("centerlines", 1.0);
    this->Ok = true;
  }
  catch (const std::exception& e) // Cancelled, and ComputeCenterlines' std::invalid_argument
  {
    this->Problem = std::string("Centerlines: ") + e.what();
  }
}

bool VesselSession::IsUpToDate(const BenderSession& session) const
{
  vtkPolyData* surface = session.GetSurface();
  if (!surface)
  {
    return !this->Shown && !this->Pending;
  }
  return this->Key == surface && this->KeyTime == surface->GetMTime();
}

std::shared_ptr<CenterlineJob> VesselSession::BeginCenterlines(const BenderSession& session)
{
  vtkPolyData* surface = session.GetSurface();
  vtkPolyData* original = session.GetOriginalSurface();
  if (!surface || !original)
  {
    this->Clear();
    return nullptr;
  }
  if (this->IsUpToDate(session))
  {
    return nullptr;
  }
  auto job = std::make_shared<CenterlineJob>();
  job->Key = surface;
  job->KeyTime = surface->GetMTime();
  job->OriginalKey = original;
  job->OriginalTime = original->GetMTime();
  const bool sameOriginal =
    this->OriginalKey == original && this->OriginalTime == original->GetMTime();
  if (sameOriginal && this->OriginalResult)
  {
    job->OriginalResult = this->OriginalResult;
  }
  job->Original = DeepCopyOf(original);
  if (surface != original)
  {
    job->Current = DeepCopyOf(surface);
  }
  // A new surface (a load, a segmentation) drops what was shown for the previous one.
  if (!sameOriginal)
  {
    this->Shown.reset();
    this->OriginalResult.reset();
    this->Comparison.reset();
    this->Measures = {};
    this->DropBranch();
  }
  this->Key = job->Key;
  this->KeyTime = job->KeyTime;
  this->Pending = job;
  return job;
}

bool VesselSession::Finish(CenterlineJob& job, std::string& message)
{
  if (this->Pending.get() != &job)
  {
    message = "Centerlines of an older surface: ignored";
    return this->HasCenterlines();
  }
  this->Pending.reset();
  if (!job.Ok)
  {
    message = job.Problem;
    this->Shown.reset();
    this->Comparison.reset();
    this->Measures = {};
    this->DropBranch();
    return false;
  }
  this->OriginalKey = job.OriginalKey;
  this->OriginalTime = job.OriginalTime;
  this->OriginalResult = job.Before;
  this->Shown = job.After ? *job.After : job.Before;
  this->Comparison = job.Comparison;
  this->Measures = MeasureBranches(this->Shown->branches);
  std::ostringstream text;
  text << "Centerlines: " << this->Shown->paths->GetNumberOfCells() << " path(s), "
       << this->Measures.branches.size() << " branch(es)";
  if (!this->Shown->warnings.empty())
  {
    text << " (" << this->Shown->warnings.front() << ")";
  }
  message = text.str();
  return true;
}

vtkPolyData* VesselSession::GetPaths() const
{
  return this->Shown ? this->Shown->paths.GetPointer() : nullptr;
}

vtkPolyData* VesselSession::GetBranches() const
{
  return this->Shown ? this->Shown->branches.GetPointer() : nullptr;
}

void VesselSession::Clear()
{
  this->Shown.reset();
  this->OriginalResult.reset();
  this->Comparison.reset();
  this->Measures = {};
  this->Key = nullptr;
  this->KeyTime = 0;
  this->OriginalKey = nullptr;
  this->OriginalTime = 0;
  this->Pending.reset();
  this->DropBranch();
}

RibbonPlacement VesselSession::PlaceRibbon(const Vec3& first,
  const Vec3& second,
  const CenterlineRibbonOptions& options) const
{
  return PlaceRibbonOnCenterline(this->GetPaths(), first, second, options);
}

bool VesselSession::IsOnVessel(const Vec3& point, double factor) const
{
  vtkPolyData* paths = this->GetPaths();
  vtkDataArray* radius =
    paths ? paths->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius) : nullptr;
  if (!radius || !IsFinite(point))
  {
    return false;
  }
  double nearest = std::numeric_limits<double>::infinity();
  vtkIdType nearestId = -1;
  for (vtkIdType i = 0; i < paths->GetNumberOfPoints(); ++i)
  {
    const double d = Distance(PointOf(paths, i), point);
    if (d < nearest)
    {
      nearest = d;
      nearestId = i;
    }
  }
  return nearestId >= 0 && nearest <= factor * radius->GetComponent(nearestId, 0);
}

void VesselSession::DropBranch()
{
  this->Held.clear();
}

bool VesselSession::HoldBranch(const RibbonSpec& ribbon, vtkPolyData* surface)
{
  this->DropBranch();
  vtkPolyData* paths = this->GetPaths();
  if (!paths || !surface || surface->GetNumberOfPoints() == 0)
  {
    return false;
  }
  vtkDataArray* radius =
    paths->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius);
  if (!radius)
  {
    return false;
  }
  // The path nearest to both ends of the ribbon.
  double best = std::numeric_limits<double>::infinity();
  std::vector<vtkIdType> bestIds;
  std::size_t bestA = 0, bestB = 0;
  for (vtkIdType c = 0; c < paths->GetNumberOfCells(); ++c)
  {
    const std::vector<vtkIdType> ids = CellIds(paths, c);
    double da = std::numeric_limits<double>::infinity(), db = da;
    std::size_t ia = 0, ib = 0;
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      const Vec3 p = PointOf(paths, ids[i]);
      const double r = std::max(radius->GetComponent(ids[i], 0), 1e-9);
      const double a = Distance(p, ribbon.start.position) / r;
      const double b = Distance(p, ribbon.end.position) / r;
      if (a < da)
      {
        da = a;
        ia = i;
      }
      if (b < db)
      {
        db = b;
        ib = i;
      }
    }
    if (da <= 2 && db <= 2 && da + db < best && ia != ib)
    {
      best = da + db;
      bestIds = ids;
      bestA = ia;
      bestB = ib;
    }
  }
  if (bestIds.empty())
  {
    return false;
  }
  // Samples in the ribbon's order.
  const bool forward = bestA < bestB;
  const std::size_t lo = std::min(bestA, bestB), hi = std::max(bestA, bestB);
  std::vector<HeldSample> samples;
  for (std::size_t i = lo; i <= hi; ++i)
  {
    const vtkIdType id = bestIds[forward ? i : hi - (i - lo)];
    samples.push_back({ PointOf(paths, id), radius->GetComponent(id, 0), {} });
  }
  // Wall points: each surface point near the stretch goes to its nearest sample; each sample
  // keeps its 16 nearest (the smallest distance is the local radius, before and after a bend).
  double largest = 0;
  for (const auto& s : samples)
  {
    largest = std::max(largest, s.radius);
  }
  // Only the points in the stretch's box widened by 1.5 radii can be kept.
  Vec3 low = samples.front().position, high = low;
  for (const auto& s : samples)
  {
    low = {
      std::min(low.x, s.position.x), std::min(low.y, s.position.y), std::min(low.z, s.position.z)
    };
    high = {
      std::max(high.x, s.position.x), std::max(high.y, s.position.y), std::max(high.z, s.position.z)
    };
  }
  const Vec3 margin{ 1.5 * largest, 1.5 * largest, 1.5 * largest };
  low = low - margin;
  high = high + margin;
  std::vector<std::vector<std::pair<double, Vec3>>> near(samples.size());
  for (vtkIdType k = 0; k < surface->GetNumberOfPoints(); ++k)
  {
    const Vec3 q = PointOf(surface, k);
    if (q.x < low.x || q.y < low.y || q.z < low.z || q.x > high.x || q.y > high.y || q.z > high.z)
    {
      continue;
    }
    double d = std::numeric_limits<double>::infinity();
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < samples.size(); ++i)
    {
      const double di = Distance(q, samples[i].position);
      if (di < d)
      {
        d = di;
        nearest = i;
      }
    }
    if (d <= 1.5 * samples[nearest].radius && d <= 1.5 * largest)
    {
      near[nearest].emplace_back(d, q);
    }
  }
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    auto& list = near[i];
    std::sort(list.begin(),
      list.end(),
      [](const std::pair<double, Vec3>& a, const std::pair<double, Vec3>& b)
      { return a.first < b.first; });
    for (std::size_t j = 0; j < list.size() && j < 16; ++j)
    {
      samples[i].wall.push_back(list[j].second);
    }
  }
  this->Held = std::move(samples);
  return this->Held.size() >= 3;
}

bool VesselSession::HeldSamples(const WarpSpec* warp,
  std::vector<Point3>& points,
  std::vector<double>& radii) const
{
  points.clear();
  radii.clear();
  if (this->Held.size() < 3)
  {
    return false;
  }
  try
  {
    std::unique_ptr<RibbonWarp> moved;
    if (warp)
    {
      moved = std::make_unique<RibbonWarp>(*warp);
    }
    const auto carry = [&](const Vec3& x) { return moved ? moved->Apply(x) : x; };
    for (const HeldSample& sample : this->Held)
    {
      const Vec3 centre = carry(sample.position);
      // The radius at a sample: its distance to the nearest of its (carried) wall points; the
      // centerline's own where it has none.
      double radius = std::numeric_limits<double>::infinity();
      for (const Vec3& w : sample.wall)
      {
        radius = std::min(radius, Distance(carry(w), centre));
      }
      points.push_back(ToArray(centre));
      radii.push_back(std::isfinite(radius) ? radius : sample.radius);
    }
    return true;
  }
  catch (const GeometryError&)
  {
    points.clear(); // an invalid live warp: the session does not apply it either
    radii.clear();
    return false;
  }
}

HeldBranchMeasures VesselSession::MeasureBy(const WarpSpec* warp) const
{
  HeldBranchMeasures m;
  std::vector<Point3> points;
  std::vector<double> radii;
  if (!this->HeldSamples(warp, points, radii))
  {
    return m;
  }
  static_cast<BranchMeasures&>(m) = MeasureStretch(points, radii);
  m.samples = static_cast<int>(points.size());
  m.valid = std::isfinite(m.length) && std::isfinite(m.bendAngle);
  return m;
}

HeldBranchMeasures VesselSession::MeasureHeld() const
{
  return this->MeasureBy(nullptr);
}

HeldBranchMeasures VesselSession::MeasureHeld(const WarpSpec& warp) const
{
  return this->MeasureBy(&warp);
}

vtkSmartPointer<vtkPolyData> VesselSession::StretchBy(const WarpSpec* warp) const
{
  std::vector<Point3> points;
  std::vector<double> radii;
  if (!this->HeldSamples(warp, points, radii))
  {
    return nullptr;
  }
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> radius;
  radius->SetName(VesselArrays::MaximumInscribedSphereRadius);
  vtkNew<vtkCellArray> line;
  line->InsertNextCell(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    line->InsertCellPoint(xyz->InsertNextPoint(points[i].data()));
    radius->InsertNextValue(radii[i]);
  }
  auto stretch = vtkSmartPointer<vtkPolyData>::New();
  stretch->SetPoints(xyz);
  stretch->SetLines(line);
  stretch->GetPointData()->AddArray(radius);
  return stretch;
}

vtkSmartPointer<vtkPolyData> VesselSession::HeldStretch() const
{
  return this->StretchBy(nullptr);
}

vtkSmartPointer<vtkPolyData> VesselSession::HeldStretch(const WarpSpec& warp) const
{
  return this->StretchBy(&warp);
}

vtkSmartPointer<vtkPolyData> VesselSession::WarpedPaths(const WarpSpec& warp) const
{
  vtkPolyData* paths = this->GetPaths();
  if (!paths)
  {
    return nullptr;
  }
  try
  {
    const RibbonWarp moved(warp);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(paths->GetNumberOfPoints());
    for (vtkIdType i = 0; i < paths->GetNumberOfPoints(); ++i)
    {
      const Vec3 p = moved.Apply(PointOf(paths, i));
      points->SetPoint(i, p.x, p.y, p.z);
    }
    auto warped = vtkSmartPointer<vtkPolyData>::New();
    warped->ShallowCopy(paths);
    warped->SetPoints(points);
    return warped;
  }
  catch (const GeometryError&) // an invalid live warp
  {
    return nullptr;
  }
}

WarpSpec LiveWarpOf(const BenderSession& session)
{
  WarpSpec warp;
  warp.initial = session.GetInitialRibbon();
  warp.final = session.GetFinalRibbon();
  warp.radius = session.GetParameters().radius;
  warp.decay = session.GetParameters().decay;
  warp.reverseScrews = session.GetParameters().reverseScrews;
  return warp;
}

} // namespace bender
