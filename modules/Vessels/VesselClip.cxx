#include "VesselClip.h"

#include "BenderErrors.h"
#include "MeshTopology.h"
#include "StringUtil.h"
#include "VesselClipPasses.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace bender
{

ClipResult ClipVesselEnds(vtkPolyData* surface,
  vtkPolyData* centerlines,
  const ClipOptions& options)
{
  using namespace clip;
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    throw InputError("the surface is empty");
  }
  Mesh mesh;
  mesh.x.resize(static_cast<std::size_t>(surface->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    surface->GetPoint(i, mesh.x[i].data());
    if (!std::isfinite(mesh.x[i][0]) || !std::isfinite(mesh.x[i][1]) ||
      !std::isfinite(mesh.x[i][2]))
    {
      throw InputError("the surface has non-finite (NaN or infinite) point coordinates");
    }
  }
  {
    const std::vector<std::int64_t> flat = CollectTriangles(surface);
    for (std::size_t t = 0; t + 2 < flat.size(); t += 3)
    {
      if (flat[t] != flat[t + 1] && flat[t + 1] != flat[t + 2] && flat[t] != flat[t + 2])
      {
        mesh.t.push_back({ { flat[t], flat[t + 1], flat[t + 2] } });
      }
    }
  }
  if (mesh.t.empty())
  {
    throw InputError("the surface has no triangles");
  }
  const std::vector<EndGroup> groups = EndGroups(centerlines);

  // What to cut at each end: (end group, distance, user chosen).
  struct Plan
  {
    std::size_t group;
    const Profile* along;
    double distance;
    bool user;
  };
  std::vector<Plan> plans;
  for (std::size_t g = 0; g < groups.size(); ++g)
  {
    plans.push_back({ g, &groups[g].longest, SettledDistance(groups[g].longest), false });
  }
  for (const ClipEndRequest& request : options.ends)
  {
    const V3 q = request.position;
    if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2]))
    {
      throw InputError("a clip position is not finite");
    }
    // The centerline point nearest q on the ends [first, last)'s profiles (first halves).
    struct OnCenterline
    {
      std::size_t group = 0;
      const Profile* along = nullptr;
      double s = 0.0, distance = std::numeric_limits<double>::infinity(), radius = 0.0;
    };
    auto nearestOn = [&groups, &q](std::size_t first, std::size_t last)
    {
      OnCenterline n;
      for (std::size_t g = first; g < last; ++g)
      {
        for (const Profile& p : groups[g].profiles)
        {
          for (std::size_t i = 0; i < p.x.size() && p.s[i] <= 0.5 * p.Length(); ++i)
          {
            const double d = Distance(p.x[i], q);
            if (d < n.distance)
            {
              n = { g, &p, p.s[i], d, p.r[i] };
            }
          }
        }
      }
      return n;
    };
    std::size_t best = 0;
    double bestS = 0.0;
    const Profile* along = nullptr;
    if (request.distance >= 0)
    {
      for (std::size_t g = 1; g < groups.size(); ++g)
      {
        if (Distance(groups[g].position, q) < Distance(groups[best].position, q))
        {
          best = g;
        }
      }
      // The point must be on that end's vessel, not on another the centerlines miss.
      const OnCenterline on = nearestOn(best, best + 1);
      if (on.distance > kClipPointReach * on.radius)
      {
        throw InputError("the clip position " + FormatPoint(q) + " is " +
          FormatNumber(on.distance - on.radius) + " mm from the vessel of the nearest end " +
          FormatPoint(groups[best].position) + " (inscribed radius " + FormatNumber(on.radius) +
          "): not on a vessel whose end the centerlines found");
      }
      along = &groups[best].longest;
      bestS = request.distance;
      if (bestS > 0.5 * along->Length())
      {
        throw InputError("the clip distance " + std::to_string(request.distance) + " at the end " +
          FormatPoint(groups[best].position) + " is more than half the centerline's length (" +
          std::to_string(along->Length()) + ")");
      }
    }
    else
    {
      const OnCenterline on = nearestOn(0, groups.size());
      best = on.group;
      bestS = on.s;
      along = on.along;
      if (on.distance > 3.0 * on.radius)
      {
        throw InputError("the clip position " + FormatPoint(q) +
          " is not on a vessel: the nearest centerline point is " + std::to_string(on.distance) +
          " away (radius " + std::to_string(on.radius) + ")");
      }
    }
    if (plans[best].user)
    {
      throw InputError(
        "two clip positions choose the same vessel end " + FormatPoint(groups[best].position));
    }
    plans[best] = { best, along, bestS, true };
  }

  ClipResult result;
  for (const Plan& plan : plans)
  {
    const Profile& p = *plan.along;
    double s = plan.distance;
    bool done = false;
    std::vector<std::int64_t> rim;
    V3 c{}, n{};
    double r = 0;
    for (int attempt = 0; attempt < (plan.user ? 1 : 12) && !done; ++attempt)
    {
      c = p.At(s, &r);
      const V3 t = p.Tangent(s);
      n = { { -t[0], -t[1], -t[2] } };
      done = Cut(mesh, c, n, r, rim);
      if (!done)
      {
        s += 0.25 * r; // inwards, past an oblique old rim
        if (s > 0.5 * p.Length())
        {
          break;
        }
      }
    }
    if (!done)
    {
      throw InputError("the clip plane at " + FormatPoint(c) + " (" + std::to_string(s) +
        " from the vessel end " + FormatPoint(groups[plan.group].position) +
        ") cuts no vessel cleanly: the cut does not close around the vessel");
    }
    ClippedEnd end;
    end.normal = n;
    end.inscribedRadius = r;
    end.centerlineEnd = groups[plan.group].position;
    end.distance = s;
    end.userChosen = plan.user;
    end.rim.assign(rim.begin(), rim.end());
    result.ends.push_back(std::move(end));
  }
  Compact(mesh, result.ends, result.warnings);
  // Rim measures: area and centroid of the planar polygon (fan from the first vertex).
  for (ClippedEnd& end : result.ends)
  {
    V3 area{ { 0, 0, 0 } }, centroid{ { 0, 0, 0 } };
    double total = 0.0;
    for (std::size_t k = 1; k + 1 < end.rim.size(); ++k)
    {
      const V3& a = mesh.x[end.rim[0]];
      const V3& b = mesh.x[end.rim[k]];
      const V3& cc = mesh.x[end.rim[k + 1]];
      const V3 cr = Cross(Sub(b, a), Sub(cc, a));
      const double w = 0.5 * Dot(cr, end.normal);
      total += w;
      for (int e = 0; e < 3; ++e)
      {
        area[e] += 0.5 * cr[e];
        centroid[e] += w * (a[e] + b[e] + cc[e]) / 3.0;
      }
    }
    end.area = std::abs(total);
    end.radius = std::sqrt(end.area / M_PI);
    for (int e = 0; e < 3; ++e)
    {
      end.centre[e] = total != 0.0 ? centroid[e] / total : mesh.x[end.rim[0]][e];
    }
  }
  // The open loops that are no rim: ends of the input that no centerline end reached.
  {
    std::vector<std::int64_t> flat;
    for (const Tri& t : mesh.t)
    {
      flat.insert(flat.end(), t.begin(), t.end());
    }
    std::vector<char> onRim(mesh.x.size(), 0);
    for (const ClippedEnd& end : result.ends)
    {
      for (long long v : end.rim)
      {
        onRim[static_cast<std::size_t>(v)] = 1;
      }
    }
    for (const BoundaryChain& chain : BoundaryLoops(flat, static_cast<std::int64_t>(mesh.x.size())))
    {
      if (chain.vertices.empty() || onRim[static_cast<std::size_t>(chain.vertices.front())])
      {
        continue;
      }
      UnclippedEnd open;
      const double share = 1.0 / static_cast<double>(chain.vertices.size());
      for (std::int64_t v : chain.vertices)
      {
        for (int e = 0; e < 3; ++e)
        {
          open.centre[e] += share * mesh.x[v][e];
        }
      }
      for (std::int64_t v : chain.vertices)
      {
        open.radius += share * Distance(mesh.x[v], open.centre);
      }
      result.unclipped.push_back(open);
    }
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const V3& x : mesh.x)
  {
    points->InsertNextPoint(x.data());
  }
  vtkNew<vtkCellArray> polys;
  for (const Tri& t : mesh.t)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    polys->InsertNextCell(3, ids);
  }
  result.surface = vtkSmartPointer<vtkPolyData>::New();
  result.surface->SetPoints(points);
  result.surface->SetPolys(polys);
  return result;
}

} // namespace bender
