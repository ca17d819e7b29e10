#include "FlowExtensions.h"

#include "BenderErrors.h"
#include "MeshTopology.h"
#include "Vec3.h"

#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>

namespace bender
{
namespace
{
using V3 = std::array<double, 3>;

/// True when extension `b` (its axis and rings of radius reachB, sampled) enters the cylinder
/// of extension `a` (beyond a's rim plane, within 1.1 reachA of its axis).
bool Sweeps(const FlowExtensionEnd& a,
  const V3& axisA,
  double lengthA,
  double reachA,
  const FlowExtensionEnd& b,
  const V3& axisB,
  double lengthB,
  double reachB)
{
  if (lengthA <= 0)
  {
    return false;
  }
  V3 e1 = Cross(axisB, std::abs(axisB[0]) < 0.9 ? V3{ { 1, 0, 0 } } : V3{ { 0, 1, 0 } });
  e1 = Normalized(e1);
  const V3 e2 = Cross(axisB, e1);
  const int rings = std::max(1, static_cast<int>(std::ceil(2.0 * lengthB / reachB)));
  for (int k = 0; k <= rings; ++k)
  {
    const double d = lengthB * k / rings;
    for (int j = -1; j < 16; ++j)
    {
      const double angle = 2.0 * M_PI * j / 16.0;
      const double r = j < 0 ? 0.0 : reachB;
      V3 p;
      for (int e = 0; e < 3; ++e)
      {
        p[e] = b.centre[e] + d * axisB[e] + r * (std::cos(angle) * e1[e] + std::sin(angle) * e2[e]);
      }
      const V3 q = Sub(p, a.centre);
      const double along = Dot(q, axisA);
      if (along <= 0 || along > lengthA)
      {
        continue;
      }
      const V3 radial{
        { q[0] - along * axisA[0], q[1] - along * axisA[1], q[2] - along * axisA[2] }
      };
      if (Norm(radial) < 1.1 * reachA)
      {
        return true;
      }
    }
  }
  return false;
}

/// The length of each extension: Factor x radius, reduced where it would run into the
/// surface (a point of the surface within 1.2 radii of the axis, beyond the rim's plane) or
/// into another extension (sampled rings of one inside the other's cylinder, 1.1 radii),
/// never below zero.
std::vector<double> ClearLengths(vtkPolyData* surface,
  const std::vector<FlowExtensionEnd>& ends,
  const FlowExtensionOptions& options,
  std::vector<std::string>& warnings)
{
  std::vector<double> length(ends.size(), 0.0), requested(ends.size(), 0.0);
  std::vector<V3> axis(ends.size());
  std::vector<double> reach(ends.size(), 0.0); // largest rim radius
  for (std::size_t k = 0; k < ends.size(); ++k)
  {
    const FlowExtensionEnd& end = ends[k];
    const double factor =
      end.factor >= 0 ? end.factor : (end.inlet ? options.inletFactor : options.outletFactor);
    if (!std::isfinite(factor) || factor > 100)
    {
      throw InputError(
        "flow extensions: the length factor " + std::to_string(factor) + " is not in [0, 100]");
    }
    if (end.rim.size() < 3)
    {
      throw InputError("flow extensions: an end's rim has fewer than 3 points");
    }
    for (long long v : end.rim)
    {
      if (v < 0 || v >= surface->GetNumberOfPoints())
      {
        throw InputError("flow extensions: an end's rim has a point id out of range");
      }
      V3 p;
      surface->GetPoint(v, p.data());
      reach[k] = std::max(reach[k], Norm(Sub(p, end.centre)));
    }
    axis[k] = Normalized(end.normal);
    if (Norm(axis[k]) == 0.0 || !(end.radius > 0) || !std::isfinite(end.radius))
    {
      throw InputError("flow extensions: an end has no normal or no radius");
    }
    requested[k] = length[k] = factor * end.radius;
  }
  // The surface.
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    V3 p;
    surface->GetPoint(i, p.data());
    for (std::size_t k = 0; k < ends.size(); ++k)
    {
      const V3 d = Sub(p, ends[k].centre);
      const double along = Dot(d, axis[k]);
      if (along <= 1e-9 * ends[k].radius || along > length[k] + reach[k])
      {
        continue;
      }
      const V3 radial{
        { d[0] - along * axis[k][0], d[1] - along * axis[k][1], d[2] - along * axis[k][2] }
      };
      if (Norm(radial) < 1.2 * std::max(reach[k], ends[k].radius))
      {
        length[k] = std::max(0.0, std::min(length[k], along - reach[k]));
      }
    }
  }
  // Pairs of extensions: shorten the longer by a tenth until they clear.
  for (int pass = 0; pass < 200; ++pass)
  {
    bool clear = true;
    for (std::size_t a = 0; a < ends.size(); ++a)
    {
      for (std::size_t b = a + 1; b < ends.size(); ++b)
      {
        if (length[a] <= 0 && length[b] <= 0)
        {
          continue;
        }
        const bool collide =
          Sweeps(ends[a], axis[a], length[a], reach[a], ends[b], axis[b], length[b], reach[b]) ||
          Sweeps(ends[b], axis[b], length[b], reach[b], ends[a], axis[a], length[a], reach[a]);
        if (collide)
        {
          clear = false;
          std::size_t& longer = length[a] >= length[b] ? a : b;
          length[longer] = length[longer] < 0.5 * ends[longer].radius ? 0.0 : 0.9 * length[longer];
        }
      }
    }
    if (clear)
    {
      break;
    }
  }
  for (std::size_t k = 0; k < ends.size(); ++k)
  {
    if (length[k] < requested[k])
    {
      std::ostringstream s;
      s.precision(3);
      s << "the flow extension at (" << ends[k].centre[0] << ", " << ends[k].centre[1] << ", "
        << ends[k].centre[2] << ") is " << length[k] << " long instead of " << requested[k]
        << ": a longer one would run into the vessel or another extension";
      warnings.push_back(s.str());
    }
  }
  return length;
}
} // namespace

std::vector<FlowExtensionEnd> OpenEnds(vtkPolyData* surface)
{
  std::vector<FlowExtensionEnd> ends;
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    return ends;
  }
  V3 mean{ { 0, 0, 0 } };
  const vtkIdType np = surface->GetNumberOfPoints();
  for (vtkIdType i = 0; i < np; ++i)
  {
    V3 p;
    surface->GetPoint(i, p.data());
    for (int e = 0; e < 3; ++e)
    {
      mean[e] += p[e] / static_cast<double>(np);
    }
  }
  double largest = -1;
  for (const BoundaryChain& chain : BoundaryLoops(CollectTriangles(surface), np))
  {
    if (!chain.closed || chain.vertices.size() < 3)
    {
      continue;
    }
    FlowExtensionEnd end;
    end.rim.assign(chain.vertices.begin(), chain.vertices.end());
    V3 area{ { 0, 0, 0 } }, c{ { 0, 0, 0 } };
    std::vector<V3> x;
    for (long long v : end.rim)
    {
      V3 p;
      surface->GetPoint(v, p.data());
      x.push_back(p);
      for (int e = 0; e < 3; ++e)
      {
        c[e] += p[e] / static_cast<double>(end.rim.size());
      }
    }
    for (std::size_t k = 0; k < x.size(); ++k)
    {
      const V3 a = Cross(Sub(x[k], c), Sub(x[(k + 1) % x.size()], c));
      for (int e = 0; e < 3; ++e)
      {
        area[e] += 0.5 * a[e];
      }
    }
    end.centre = c;
    end.radius = std::sqrt(Norm(area) / M_PI);
    end.normal = Normalized(area);
    if (Dot(end.normal, Sub(c, mean)) < 0)
    {
      end.normal = { { -end.normal[0], -end.normal[1], -end.normal[2] } };
    }
    if (Norm(area) > largest)
    {
      largest = Norm(area);
      for (FlowExtensionEnd& other : ends)
      {
        other.inlet = false;
      }
      end.inlet = true;
    }
    ends.push_back(std::move(end));
  }
  return ends;
}

FlowExtensionResult AddFlowExtensions(vtkPolyData* surface,
  const std::vector<FlowExtensionEnd>& ends,
  const FlowExtensionOptions& options)
{
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    throw InputError("flow extensions: the surface is empty");
  }
  for (const double f : { options.inletFactor, options.outletFactor })
  {
    if (!std::isfinite(f) || f < 0 || f > 100)
    {
      throw InputError(
        "flow extensions: the length factor " + std::to_string(f) + " is not in [0, 100]");
    }
  }
  const vtkIdType np = surface->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < np; ++i)
  {
    V3 p;
    surface->GetPoint(i, p.data());
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      throw InputError("flow extensions: the surface has non-finite point coordinates");
    }
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> polys;
  const std::vector<std::int64_t> tris = CollectTriangles(surface);
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    const vtkIdType ids[3] = { tris[t], tris[t + 1], tris[t + 2] };
    polys->InsertNextCell(3, ids);
  }
  FlowExtensionResult result;
  const std::vector<double> lengths = ClearLengths(surface, ends, options, result.warnings);
  for (std::size_t index = 0; index < ends.size(); ++index)
  {
    const FlowExtensionEnd& end = ends[index];
    const double factor = lengths[index] / end.radius;
    const std::size_t m = end.rim.size();
    const V3 n = Normalized(end.normal);
    ExtendedEnd out;
    out.normal = n;
    out.radius = end.radius;
    out.factor = factor;
    out.length = lengths[index];
    out.requestedLength =
      (end.factor >= 0 ? end.factor : (end.inlet ? options.inletFactor : options.outletFactor)) *
      end.radius;
    out.farRim = end.rim;
    for (int e = 0; e < 3; ++e)
    {
      out.farCentre[e] = end.centre[e] + out.length * n[e];
    }
    if (out.length <= 0)
    {
      result.ends.push_back(std::move(out));
      continue;
    }
    // The rim in the end's plane, and its target circle with even spacing in the rim's
    // direction of travel about n.
    std::vector<V3> q(m);
    double spacing = 0.0;
    for (std::size_t j = 0; j < m; ++j)
    {
      V3 p;
      points->GetPoint(end.rim[j], p.data());
      const V3 d = Sub(p, end.centre);
      const double off = Dot(d, n);
      q[j] = { { d[0] - off * n[0], d[1] - off * n[1], d[2] - off * n[2] } };
    }
    for (std::size_t j = 0; j < m; ++j)
    {
      spacing += std::sqrt(Dot(Sub(q[(j + 1) % m], q[j]), Sub(q[(j + 1) % m], q[j]))) /
        static_cast<double>(m);
    }
    // The rim's radius as a function of the angle about n (the rim seen from its centre),
    // and its sense of travel.
    V3 e1 = Normalized(q[0]);
    if (Norm(e1) == 0.0)
    {
      e1 = Normalized(Cross(n, std::abs(n[0]) < 0.9 ? V3{ { 1, 0, 0 } } : V3{ { 0, 1, 0 } }));
    }
    const V3 e2 = Cross(n, e1);
    double turn = 0.0;
    std::vector<std::pair<double, double>> polar;
    for (std::size_t j = 0; j < m; ++j)
    {
      turn += Dot(Cross(q[j], q[(j + 1) % m]), n);
      polar.emplace_back(std::atan2(Dot(q[j], e2), Dot(q[j], e1)), Norm(q[j]));
    }
    std::sort(polar.begin(), polar.end());
    auto rimRadius = [&polar](double angle)
    {
      angle = std::remainder(angle, 2.0 * M_PI);
      auto it = std::lower_bound(
        polar.begin(), polar.end(), std::make_pair(angle, -std::numeric_limits<double>::max()));
      const auto& hi = it == polar.end() ? polar.front() : *it;
      const auto& lo = it == polar.begin() ? polar.back() : *(it - 1);
      double span = hi.first - lo.first, t = angle - lo.first;
      if (span <= 0)
      {
        span += 2.0 * M_PI;
      }
      if (t < 0)
      {
        t += 2.0 * M_PI;
      }
      return lo.second + (hi.second - lo.second) * std::clamp(t / span, 0.0, 1.0);
    };
    const double sense = turn >= 0 ? 1.0 : -1.0;
    const int rings = std::max(2, static_cast<int>(std::lround(out.length / spacing)));
    const double blend = std::min(0.5 * out.length, 2.0 * end.radius);
    std::vector<vtkIdType> previous;
    for (int k = 1; k <= rings; ++k)
    {
      // Ring k: m points evenly spaced in angle, from the rim's shape to the circle.
      const double d = out.length * k / rings;
      const double u = std::min(1.0, d / blend);
      const double w = u * u * (3.0 - 2.0 * u);
      std::vector<vtkIdType> ring(m);
      for (std::size_t j = 0; j < m; ++j)
      {
        const double a = sense * 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(m);
        const double radius = (1.0 - w) * rimRadius(a) + w * end.radius;
        V3 p;
        for (int e = 0; e < 3; ++e)
        {
          p[e] = end.centre[e] + d * n[e] + radius * (std::cos(a) * e1[e] + std::sin(a) * e2[e]);
        }
        ring[j] = points->InsertNextPoint(p.data());
      }
      if (k == 1)
      {
        // Zip the rim (uneven) to the first ring (even), always along the shorter diagonal.
        // The wall runs the rim forwards; the extension runs it the other way.
        std::size_t i = 0, j = 0;
        auto at = [&points](vtkIdType id)
        {
          V3 p;
          points->GetPoint(id, p.data());
          return p;
        };
        while (i < m || j < m)
        {
          const vtkIdType a0 = end.rim[i % m], a1 = end.rim[(i + 1) % m];
          const vtkIdType b0 = ring[j % m], b1 = ring[(j + 1) % m];
          const bool advanceRim =
            j == m || (i < m && Norm(Sub(at(a1), at(b0))) <= Norm(Sub(at(a0), at(b1))));
          if (advanceRim)
          {
            const vtkIdType t[3] = { a1, a0, b0 };
            polys->InsertNextCell(3, t);
            ++i;
          }
          else
          {
            const vtkIdType t[3] = { a0, b0, b1 };
            polys->InsertNextCell(3, t);
            ++j;
          }
        }
      }
      else
      {
        for (std::size_t j = 0; j < m; ++j)
        {
          const std::size_t j1 = (j + 1) % m;
          const vtkIdType t1[3] = { previous[j1], previous[j], ring[j] };
          const vtkIdType t2[3] = { previous[j1], ring[j], ring[j1] };
          polys->InsertNextCell(3, t1);
          polys->InsertNextCell(3, t2);
        }
      }
      previous = ring;
    }
    out.farRim.assign(previous.begin(), previous.end());
    result.ends.push_back(std::move(out));
  }
  result.surface = vtkSmartPointer<vtkPolyData>::New();
  result.surface->SetPoints(points);
  result.surface->SetPolys(polys);
  return result;
}

} // namespace bender
