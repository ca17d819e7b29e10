#include "PrepareForCfd.h"

#include "BenderErrors.h"
#include "FlowExtensions.h"
#include "MeshTopology.h"
#include "StringUtil.h"
#include "VesselCenterlines.h"
#include "vtkBenderCapFilter.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

namespace bender
{
namespace
{
double Distance2(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
    (a[2] - b[2]) * (a[2] - b[2]);
}

struct End
{
  std::vector<long long> rim;
  std::array<double, 3> centre, normal;
  double radius = 0, area = 0;
  std::string name;
  bool inlet = false;
  double factor = -1.0;
  std::array<double, 3> centerlineEnd{ { 0, 0, 0 } };
  double clipDistance = -1.0;
};

/// "x,y,z" as --end takes it.
std::string CliPoint(const std::array<double, 3>& p)
{
  std::string text = FormatPoint(p);
  text.erase(std::remove_if(
               text.begin(), text.end(), [](char c) { return c == '(' || c == ')' || c == ' '; }),
    text.end());
  return text;
}

/// Whether `position` is on a vessel of `centerlines`: within kClipPointReach inscribed radii
/// of one of its points.
bool OnCenterlines(vtkPolyData* centerlines, const std::array<double, 3>& position)
{
  const double reach2 = kClipPointReach * kClipPointReach;
  for (const CenterlineEndPath& path : FindCenterlineEndPaths(centerlines))
  {
    for (std::size_t i = 0; i < path.points.size(); ++i)
    {
      if (Distance2(path.points[i], position) <= reach2 * path.radii[i] * path.radii[i])
      {
        return true;
      }
    }
  }
  return false;
}

/// The centerlines of `surface` through every vessel end, the ends of `requests` the automatic
/// endpoints miss included: those are seeds of a second computation (with the ends found),
/// and a request without a distance that only seeded its end is dropped from `requests` (the
/// end is cut at its default distance). Throws InputError (one line) when there is no
/// centerline, or when a vessel end is not reached by one (it would be left closed).
vtkSmartPointer<vtkPolyData> CenterlinesThroughEnds(vtkPolyData* surface,
  std::vector<ClipEndRequest>& requests,
  std::vector<std::string>& warnings)
{
  CenterlineResult cl = ComputeCenterlines(surface);
  if (!cl.ok)
  {
    throw InputError("no centerline to clip the ends by: " + cl.message);
  }
  std::vector<std::size_t> seeds;
  for (std::size_t k = 0; k < requests.size(); ++k)
  {
    if (!OnCenterlines(cl.paths, requests[k].position))
    {
      seeds.push_back(k);
    }
  }
  if (!seeds.empty())
  {
    CenterlineOptions seeded;
    for (const bool inlet : { true, false })
    {
      for (const CenterlineEndpoint& e : cl.endpoints)
      {
        if (e.inlet == inlet && e.reached)
        {
          seeded.seeds.push_back(e.position);
        }
      }
    }
    for (const std::size_t k : seeds)
    {
      seeded.seeds.push_back(requests[k].position);
    }
    // Used when a vessel now reaches every seed; else the points are on no vessel (the clip
    // says so).
    CenterlineResult through = ComputeCenterlines(surface, seeded);
    bool reached = through.ok;
    for (const std::size_t k : seeds)
    {
      reached = reached && OnCenterlines(through.paths, requests[k].position);
    }
    if (reached)
    {
      cl = std::move(through);
      // A seed's end lies a little inside its point (the inscribed sphere it snapped to): a
      // distance counts from the point, so that the cut does not move when the step is
      // replayed from the end it made.
      const std::vector<CenterlineEndPath> paths = FindCenterlineEndPaths(cl.paths);
      for (auto k = seeds.rbegin(); k != seeds.rend(); ++k)
      {
        ClipEndRequest& request = requests[*k];
        if (request.distance < 0)
        {
          requests.erase(requests.begin() + static_cast<std::ptrdiff_t>(*k));
          continue;
        }
        double inside = std::numeric_limits<double>::infinity();
        for (const CenterlineEndPath& path : paths)
        {
          inside = std::min(inside, std::sqrt(Distance2(path.position, request.position)));
        }
        request.distance = std::max(0.0, request.distance - inside);
      }
    }
  }
  for (const CenterlineEndpoint& e : cl.endpoints)
  {
    if (!e.reached)
    {
      throw InputError("the vessel end at " + FormatPoint(e.position) + " (" +
        FormatNumber(2.0 * e.radius) +
        " mm wide) would not be clipped: no centerline reaches it through the lumen (remesh the "
        "surface finer there, or cut its ends yourself and use --no-clip)");
    }
  }
  for (const std::string& w : cl.warnings)
  {
    warnings.push_back("centerlines: " + w);
  }
  return cl.paths;
}

template<typename T>
std::size_t Nearest(const std::vector<End>& ends, const T& position)
{
  std::size_t best = 0;
  for (std::size_t k = 1; k < ends.size(); ++k)
  {
    if (Distance2(ends[k].centre, position) < Distance2(ends[best].centre, position))
    {
      best = k;
    }
  }
  return best;
}
} // namespace

PrepareForCfdResult PrepareForCfd(vtkPolyData* surface,
  const PrepareForCfdOptions& options,
  const ProgressReporter& progress)
{
  const std::string& input = options.inputName;
  auto error = [&input](const std::string& what) { return InputError(input + ": " + what); };
  if (!surface || surface->GetNumberOfPoints() == 0 || CollectTriangles(surface).empty())
  {
    throw error("the surface has no triangles");
  }
  for (const double f : { options.inletExtension, options.outletExtension })
  {
    if (!std::isfinite(f) || f < 0 || f > 100)
    {
      throw error("the flow-extension factor " + std::to_string(f) + " is not in [0, 100]");
    }
  }
  PrepareForCfdResult result;
  std::vector<End> ends;
  vtkSmartPointer<vtkPolyData> open;
  try
  {
    if (options.clip)
    {
      vtkSmartPointer<vtkPolyData> centerlines = options.centerlines;
      ClipOptions clip;
      clip.ends = options.ends;
      if (!centerlines)
      {
        progress.Report("centerlines", 0.0);
        centerlines = CenterlinesThroughEnds(surface, clip.ends, result.warnings);
      }
      result.centerlines = centerlines;
      progress.ThrowIfCancelled("centerlines");
      progress.Report("clip", 0.2);
      ClipResult clipped = ClipVesselEnds(surface, centerlines, clip);
      if (!clipped.unclipped.empty())
      {
        const UnclippedEnd& missed = clipped.unclipped.front();
        const std::string at = FormatPoint(missed.centre);
        const std::string remedy = options.centerlines
          ? "give centerlines through it (or none: they are computed)"
          : "clip it with --end " + CliPoint(missed.centre);
        throw InputError("the open end at " + at + " (" + FormatNumber(2.0 * missed.radius) +
          " mm wide) would not be clipped: no centerline reaches it (" +
          CountOf(clipped.unclipped.size(), "such end") + "); " + remedy +
          ", or keep the ends as they are with --no-clip");
      }
      result.warnings.insert(
        result.warnings.end(), clipped.warnings.begin(), clipped.warnings.end());
      open = clipped.surface;
      for (const ClippedEnd& c : clipped.ends)
      {
        ends.push_back({ c.rim,
          c.centre,
          c.normal,
          c.radius,
          c.area,
          "",
          false,
          -1.0,
          c.centerlineEnd,
          c.distance });
      }
    }
    else
    {
      open = surface;
      for (const FlowExtensionEnd& e : OpenEnds(surface))
      {
        ends.push_back({ e.rim,
          e.centre,
          e.normal,
          e.radius,
          M_PI * e.radius * e.radius,
          "",
          false,
          -1.0,
          e.centre,
          -1.0 });
      }
      if (ends.empty())
      {
        throw InputError(options.cap ? "the surface has no open end to cap (clip its ends instead)"
                                     : "the surface has no open end");
      }
    }
  }
  catch (const InputError& e)
  {
    throw error(e.what());
  }
  if (ends.size() < 2)
  {
    throw error("the surface has " + std::to_string(ends.size()) +
      " vessel end; a CFD model needs at least two (an inlet and an outlet)");
  }
  // Ids by decreasing area (ties: the order found), names and roles.
  std::vector<std::size_t> order(ends.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(),
    order.end(),
    [&ends](std::size_t a, std::size_t b) { return ends[a].area > ends[b].area; });
  {
    std::vector<End> sorted;
    for (std::size_t k : order)
    {
      sorted.push_back(ends[k]);
    }
    ends = std::move(sorted);
  }
  std::set<std::string> taken;
  int inlet = -1;
  for (const CfdEndName& entry : options.names)
  {
    if (!IsValidPatchName(entry.name) || entry.name == "wall")
    {
      throw error("invalid end name '" + entry.name +
        "': use letters, digits and '_', not starting with a digit, not 'wall'");
    }
    if (!taken.insert(entry.name).second)
    {
      throw error("the end name '" + entry.name + "' is given twice");
    }
    End& end = ends[Nearest(ends, entry.position)];
    if (!end.name.empty())
    {
      throw error("the names '" + end.name + "' and '" + entry.name + "' choose the same end");
    }
    end.name = entry.name;
    if (entry.inlet || entry.name == "inlet")
    {
      if (inlet >= 0)
      {
        throw error("two ends are named as the inlet");
      }
      inlet = static_cast<int>(&end - ends.data());
    }
  }
  if (inlet < 0)
  {
    inlet = 0;
  }
  ends[static_cast<std::size_t>(inlet)].inlet = true;
  int next = 1;
  for (End& end : ends)
  {
    if (!end.name.empty())
    {
      continue;
    }
    if (end.inlet && !taken.count("inlet"))
    {
      end.name = "inlet";
    }
    else
    {
      do
      {
        end.name = "outlet_" + std::to_string(next++);
      } while (taken.count(end.name));
    }
    taken.insert(end.name);
  }
  for (const CfdEndFactor& f : options.extensionFactors)
  {
    if (!std::isfinite(f.factor) || f.factor < 0 || f.factor > 100)
    {
      throw error("the flow-extension factor " + std::to_string(f.factor) + " is not in [0, 100]");
    }
    ends[Nearest(ends, f.position)].factor = f.factor;
  }

  // Flow extensions.
  progress.ThrowIfCancelled("clip");
  progress.Report("flow extensions", 0.5);
  std::vector<FlowExtensionEnd> request;
  for (const End& end : ends)
  {
    request.push_back({ end.rim, end.centre, end.normal, end.radius, end.factor, end.inlet });
  }
  FlowExtensionOptions extension;
  extension.inletFactor = options.inletExtension;
  extension.outletFactor = options.outletExtension;
  FlowExtensionResult extended;
  try
  {
    extended = AddFlowExtensions(open, request, extension);
  }
  catch (const InputError& e)
  {
    throw error(e.what());
  }
  result.warnings.insert(result.warnings.end(), extended.warnings.begin(), extended.warnings.end());

  for (std::size_t k = 0; k < ends.size(); ++k)
  {
    CfdEnd out;
    out.name = ends[k].name;
    out.id = static_cast<int>(k) + 2;
    out.type = ends[k].inlet ? PatchType::Inlet : PatchType::Outlet;
    out.centre = extended.ends[k].farCentre;
    out.normal = extended.ends[k].normal;
    out.radius = ends[k].radius;
    out.area = ends[k].area;
    out.extensionLength = extended.ends[k].length;
    out.extensionFactor = ends[k].factor >= 0
      ? ends[k].factor
      : (ends[k].inlet ? options.inletExtension : options.outletExtension);
    out.clipCentre = ends[k].centre;
    out.centerlineEnd = ends[k].centerlineEnd;
    out.clipDistance = ends[k].clipDistance;
    result.ends.push_back(out);
  }
  if (!options.cap)
  {
    result.surface = extended.surface;
    const std::vector<int> ids(
      static_cast<std::size_t>(result.surface->GetNumberOfPolys()), kWallEntityId);
    result.patches = { { kWallEntityId, "wall", PatchType::Wall } };
    WritePatchLabels(result.surface, ids, result.patches);
    return result;
  }
  progress.ThrowIfCancelled("flow extensions");
  progress.Report("caps", 0.7);
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(extended.surface);
  for (const CfdEnd& end : result.ends)
  {
    cap->AddCapName(end.centre.data(), end.name, end.type == PatchType::Inlet);
  }
  cap->Update();
  if (!cap->GetLastError().empty())
  {
    throw error("capping failed: " + cap->GetLastError());
  }
  if (cap->GetNumberOfCaps() != static_cast<int>(ends.size()) ||
    cap->GetNumberOfSkippedLoops() != 0)
  {
    throw error("capping failed: " + std::to_string(cap->GetNumberOfCaps()) + " caps for " +
      std::to_string(ends.size()) + " ends (" + std::to_string(cap->GetNumberOfSkippedLoops()) +
      " open loops left)");
  }
  result.surface = cap->GetOutput();
  // The cap filter numbers caps by area; take ids, centres and areas from its caps by name.
  for (CfdEnd& end : result.ends)
  {
    for (const auto& info : cap->GetCaps())
    {
      if (info.name == end.name)
      {
        end.id = info.id;
        end.centre = info.centre;
        end.normal = info.normal;
        end.area = info.area;
        end.radius = info.radius;
      }
    }
  }
  std::sort(result.ends.begin(),
    result.ends.end(),
    [](const CfdEnd& a, const CfdEnd& b) { return a.id < b.id; });
  // The table the cap filter wrote: the wall (the flow extensions keep no labels of the input)
  // and the caps.
  result.patches = { { kWallEntityId, "wall", PatchType::Wall } };
  for (const CfdEnd& end : result.ends)
  {
    result.patches.push_back({ end.id, end.name, end.type });
  }
  return result;
}

namespace
{
std::array<double, 3> Array(const Vec3& v)
{
  return { { v.x, v.y, v.z } };
}

Vec3 Point(const std::array<double, 3>& p)
{
  return { p[0], p[1], p[2] };
}
} // namespace

PrepareForCfdOptions CfdStepOptions(const CfdStep& step)
{
  PrepareForCfdOptions options;
  options.clip = step.clip;
  options.cap = step.cap;
  options.inletExtension = step.inletExtension;
  options.outletExtension = step.outletExtension;
  for (const CfdStepEnd& end : step.ends)
  {
    options.ends.push_back({ Array(end.position), end.distance });
  }
  for (const CfdStepName& name : step.names)
  {
    options.names.push_back({ Array(name.position), name.name, name.inlet });
  }
  for (const CfdStepFactor& factor : step.extensionFactors)
  {
    options.extensionFactors.push_back({ Array(factor.position), factor.factor });
  }
  return options;
}

CfdStep ResolvedCfdStep(const CfdStep& given, const PrepareForCfdResult& result)
{
  CfdStep step = given;
  step.ends.clear();
  step.names.clear();
  step.extensionFactors.clear();
  for (const CfdEnd& end : result.ends)
  {
    if (end.clipDistance >= 0)
    {
      step.ends.push_back({ Point(end.centerlineEnd), end.clipDistance });
    }
    step.names.push_back({ Point(end.clipCentre), end.name, end.type == PatchType::Inlet });
    step.extensionFactors.push_back({ Point(end.clipCentre), end.extensionFactor });
  }
  return step;
}

CfdStep CfdStepOf(const PrepareForCfdOptions& options, std::size_t afterWarps)
{
  CfdStep step;
  step.afterWarps = afterWarps;
  step.clip = options.clip;
  step.cap = options.cap;
  step.inletExtension = options.inletExtension;
  step.outletExtension = options.outletExtension;
  for (const ClipEndRequest& end : options.ends)
  {
    step.ends.push_back({ Point(end.position), end.distance });
  }
  for (const CfdEndName& name : options.names)
  {
    step.names.push_back({ Point(name.position), name.name, name.inlet });
  }
  for (const CfdEndFactor& factor : options.extensionFactors)
  {
    step.extensionFactors.push_back({ Point(factor.position), factor.factor });
  }
  return step;
}

} // namespace bender
