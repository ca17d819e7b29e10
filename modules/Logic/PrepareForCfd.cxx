#include "PrepareForCfd.h"

#include "BenderErrors.h"
#include "FlowExtensions.h"
#include "MeshTopology.h"
#include "VesselCenterlines.h"
#include "vtkBenderCapFilter.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
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
  std::vector<long long> Rim;
  std::array<double, 3> Centre, Normal;
  double Radius = 0, Area = 0;
  std::string Name;
  bool Inlet = false;
  double Factor = -1.0;
  std::array<double, 3> CenterlineEnd{ { 0, 0, 0 } };
  double ClipDistance = -1.0;
};

template<typename T>
std::size_t Nearest(const std::vector<End>& ends, const T& position)
{
  std::size_t best = 0;
  for (std::size_t k = 1; k < ends.size(); ++k)
  {
    if (Distance2(ends[k].Centre, position) < Distance2(ends[best].Centre, position))
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
  const std::string& input = options.InputName;
  auto error = [&input](const std::string& what) { return InputError(input + ": " + what); };
  if (!surface || surface->GetNumberOfPoints() == 0 || CollectTriangles(surface).empty())
  {
    throw error("the surface has no triangles");
  }
  for (const double f : { options.InletExtension, options.OutletExtension })
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
    if (options.Clip)
    {
      vtkSmartPointer<vtkPolyData> centerlines = options.Centerlines;
      if (!centerlines)
      {
        progress.Report("centerlines", 0.0);
        const CenterlineResult cl = ComputeCenterlines(surface);
        if (!cl.Ok)
        {
          throw InputError("no centerline to clip the ends by: " + cl.Message);
        }
        centerlines = cl.Paths;
      }
      progress.ThrowIfCancelled("centerlines");
      progress.Report("clip", 0.2);
      ClipOptions clip;
      clip.Ends = options.Ends;
      ClipResult clipped = ClipVesselEnds(surface, centerlines, clip);
      result.Warnings = clipped.Warnings;
      open = clipped.Surface;
      for (const ClippedEnd& c : clipped.Ends)
      {
        ends.push_back({ c.Rim,
          c.Centre,
          c.Normal,
          c.Radius,
          c.Area,
          "",
          false,
          -1.0,
          c.CenterlineEnd,
          c.Distance });
      }
    }
    else
    {
      open = surface;
      for (const FlowExtensionEnd& e : OpenEnds(surface))
      {
        ends.push_back({ e.Rim,
          e.Centre,
          e.Normal,
          e.Radius,
          M_PI * e.Radius * e.Radius,
          "",
          false,
          -1.0,
          e.Centre,
          -1.0 });
      }
      if (ends.empty())
      {
        throw InputError(options.Cap ? "the surface has no open end to cap (clip its ends instead)"
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
    [&ends](std::size_t a, std::size_t b) { return ends[a].Area > ends[b].Area; });
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
  for (const CfdEndName& entry : options.Names)
  {
    if (!IsValidPatchName(entry.Name) || entry.Name == "wall")
    {
      throw error("invalid end name '" + entry.Name +
        "': use letters, digits and '_', not starting with a digit, not 'wall'");
    }
    if (!taken.insert(entry.Name).second)
    {
      throw error("the end name '" + entry.Name + "' is given twice");
    }
    End& end = ends[Nearest(ends, entry.Position)];
    if (!end.Name.empty())
    {
      throw error("the names '" + end.Name + "' and '" + entry.Name + "' choose the same end");
    }
    end.Name = entry.Name;
    if (entry.Inlet || entry.Name == "inlet")
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
  ends[static_cast<std::size_t>(inlet)].Inlet = true;
  int next = 1;
  for (End& end : ends)
  {
    if (!end.Name.empty())
    {
      continue;
    }
    if (end.Inlet && !taken.count("inlet"))
    {
      end.Name = "inlet";
    }
    else
    {
      do
      {
        end.Name = "outlet_" + std::to_string(next++);
      } while (taken.count(end.Name));
    }
    taken.insert(end.Name);
  }
  for (const CfdEndFactor& f : options.ExtensionFactors)
  {
    if (!std::isfinite(f.Factor) || f.Factor < 0 || f.Factor > 100)
    {
      throw error("the flow-extension factor " + std::to_string(f.Factor) + " is not in [0, 100]");
    }
    ends[Nearest(ends, f.Position)].Factor = f.Factor;
  }

  // Flow extensions.
  progress.ThrowIfCancelled("clip");
  progress.Report("flow extensions", 0.5);
  std::vector<FlowExtensionEnd> request;
  for (const End& end : ends)
  {
    request.push_back({ end.Rim, end.Centre, end.Normal, end.Radius, end.Factor, end.Inlet });
  }
  FlowExtensionOptions extension;
  extension.InletFactor = options.InletExtension;
  extension.OutletFactor = options.OutletExtension;
  FlowExtensionResult extended;
  try
  {
    extended = AddFlowExtensions(open, request, extension);
  }
  catch (const InputError& e)
  {
    throw error(e.what());
  }
  result.Warnings.insert(result.Warnings.end(), extended.Warnings.begin(), extended.Warnings.end());

  for (std::size_t k = 0; k < ends.size(); ++k)
  {
    CfdEnd out;
    out.Name = ends[k].Name;
    out.Id = static_cast<int>(k) + 2;
    out.Type = ends[k].Inlet ? PatchType::Inlet : PatchType::Outlet;
    out.Centre = extended.Ends[k].FarCentre;
    out.Normal = extended.Ends[k].Normal;
    out.Radius = ends[k].Radius;
    out.Area = ends[k].Area;
    out.ExtensionLength = extended.Ends[k].Length;
    out.ClipCentre = ends[k].Centre;
    out.CenterlineEnd = ends[k].CenterlineEnd;
    out.ClipDistance = ends[k].ClipDistance;
    result.Ends.push_back(out);
  }
  if (!options.Cap)
  {
    result.Surface = extended.Surface;
    const std::vector<int> ids(
      static_cast<std::size_t>(result.Surface->GetNumberOfPolys()), kWallEntityId);
    WritePatchLabels(result.Surface, ids, { { kWallEntityId, "wall", PatchType::Wall } });
    return result;
  }
  progress.ThrowIfCancelled("flow extensions");
  progress.Report("caps", 0.7);
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(extended.Surface);
  for (const CfdEnd& end : result.Ends)
  {
    cap->AddCapName(end.Centre.data(), end.Name, end.Type == PatchType::Inlet);
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
  result.Surface = cap->GetOutput();
  // The cap filter numbers caps by area; take ids, centres and areas from its caps by name.
  for (CfdEnd& end : result.Ends)
  {
    for (const auto& info : cap->GetCaps())
    {
      if (info.Name == end.Name)
      {
        end.Id = info.Id;
        end.Centre = info.Centre;
        end.Normal = info.Normal;
        end.Area = info.Area;
        end.Radius = info.Radius;
      }
    }
  }
  std::sort(result.Ends.begin(),
    result.Ends.end(),
    [](const CfdEnd& a, const CfdEnd& b) { return a.Id < b.Id; });
  return result;
}

} // namespace bender
