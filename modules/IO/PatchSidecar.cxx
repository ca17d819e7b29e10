#include "PatchSidecar.h"

#include "FileUtilities.h"

#include <nlohmann/json.hpp>

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>

namespace bender
{
namespace
{
using Vec = std::array<double, 3>;

Vec Sub(const Vec& a, const Vec& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

Vec Cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double Norm(const Vec& a)
{
  return std::sqrt(Dot(a, a));
}

bool IsClosed(const std::vector<std::array<vtkIdType, 3>>& triangles)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  for (const auto& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType a = t[k], b = t[(k + 1) % 3];
      ++edges[{ std::min(a, b), std::max(a, b) }];
    }
  }
  return std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second == 2; });
}

// The point inside the lumen (see PatchSidecar::insidePoint); false when none is verified.
bool FindInsidePoint(const std::vector<Vec>& points,
  const std::vector<std::array<vtkIdType, 3>>& triangles,
  const std::vector<std::size_t>& patchOf,
  const std::vector<PatchGeometry>& patches,
  double orientation,
  Vec& best,
  double& clearance)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    pts->SetPoint(static_cast<vtkIdType>(i), points[i].data());
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& t : triangles)
  {
    polys->InsertNextCell({ t[0], t[1], t[2] });
  }
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(pts);
  surface->SetPolys(polys);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(surface);
  locator->BuildLocator();
  double bounds[6];
  surface->GetBounds(bounds);
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  if (!(diagonal > 0))
  {
    return false;
  }

  // Rays into the volume: from each end's centre against its outward normal, and from wall
  // triangles spread along the triangle list against theirs.
  std::vector<std::pair<Vec, Vec>> rays;
  for (const PatchGeometry& patch : patches)
  {
    if (patch.hasNormal)
    {
      rays.push_back({ patch.centre, { -patch.normal[0], -patch.normal[1], -patch.normal[2] } });
    }
  }
  const std::size_t wanted = 48;
  const std::size_t stride = std::max<std::size_t>(1, triangles.size() / wanted);
  for (std::size_t t = 0; t < triangles.size(); t += stride)
  {
    if (patches[patchOf[t]].label.id != kWallEntityId)
    {
      continue;
    }
    const Vec& a = points[static_cast<std::size_t>(triangles[t][0])];
    const Vec& b = points[static_cast<std::size_t>(triangles[t][1])];
    const Vec& c = points[static_cast<std::size_t>(triangles[t][2])];
    Vec n = Cross(Sub(b, a), Sub(c, a));
    const double len = Norm(n);
    if (!(len > 0))
    {
      continue;
    }
    const Vec centroid{
      (a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3
    };
    rays.push_back({ centroid,
      { -orientation * n[0] / len, -orientation * n[1] / len, -orientation * n[2] / len } });
  }

  bool found = false;
  clearance = 0.0;
  for (const auto& [origin, direction] : rays)
  {
    const double eps = 1e-7 * diagonal;
    double p1[3], p2[3];
    for (int a = 0; a < 3; ++a)
    {
      p1[a] = origin[a] + eps * direction[a];
      p2[a] = origin[a] + 2.0 * diagonal * direction[a];
    }
    double t = 0, x[3], pcoords[3];
    int subId = 0;
    vtkIdType cell = -1;
    if (!locator->IntersectWithLine(p1, p2, 0.0, t, x, pcoords, subId, cell))
    {
      continue;
    }
    const Vec candidate{ (p1[0] + x[0]) / 2, (p1[1] + x[1]) / 2, (p1[2] + x[2]) / 2 };
    double closest[3], dist2 = 0;
    vtkIdType closestCell = -1;
    locator->FindClosestPoint(candidate.data(), closest, closestCell, subId, dist2);
    const double distance = std::sqrt(dist2);
    if (distance <= clearance)
    {
      continue;
    }
    if (std::abs(WindingNumber(points, triangles, candidate.data())) > 0.5)
    {
      best = candidate;
      clearance = distance;
      found = true;
    }
  }
  return found;
}
} // namespace

double WindingNumber(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<vtkIdType, 3>>& triangles,
  const double point[3])
{
  // Sum of the signed solid angles of the triangles seen from the point (Van Oosterom and
  // Strackee), over 4 pi.
  const Vec q{ point[0], point[1], point[2] };
  double total = 0.0;
  for (const auto& t : triangles)
  {
    const Vec a = Sub(points[static_cast<std::size_t>(t[0])], q);
    const Vec b = Sub(points[static_cast<std::size_t>(t[1])], q);
    const Vec c = Sub(points[static_cast<std::size_t>(t[2])], q);
    const double la = Norm(a), lb = Norm(b), lc = Norm(c);
    const double numerator = Dot(a, Cross(b, c));
    const double denominator = la * lb * lc + Dot(a, b) * lc + Dot(a, c) * lb + Dot(b, c) * la;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

PatchSidecar ComputePatchSidecar(vtkPolyData* mesh, const ExportTransform& transform)
{
  const LabelledTriangles labels = CollectLabelledTriangles(mesh);
  PatchSidecar out;
  out.unit = transform.Unit();
  out.frame = transform.Frame();
  std::vector<Vec> points(static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double in[3];
    mesh->GetPoint(i, in);
    transform.Apply(in, points[static_cast<std::size_t>(i)].data());
  }
  out.closed = IsClosed(labels.triangles);
  std::vector<Vec> normalSum(labels.patches.size(), Vec{ 0, 0, 0 });
  out.patches.resize(labels.patches.size());
  double volume6 = 0.0;
  for (std::size_t t = 0; t < labels.triangles.size(); ++t)
  {
    const Vec& a = points[static_cast<std::size_t>(labels.triangles[t][0])];
    const Vec& b = points[static_cast<std::size_t>(labels.triangles[t][1])];
    const Vec& c = points[static_cast<std::size_t>(labels.triangles[t][2])];
    const Vec n = Cross(Sub(b, a), Sub(c, a)); // twice the area, along the normal
    const double area = 0.5 * Norm(n);
    volume6 += Dot(a, Cross(b, c));
    PatchGeometry& patch = out.patches[labels.patch[t]];
    patch.triangles++;
    patch.area += area;
    for (int k = 0; k < 3; ++k)
    {
      patch.centre[k] += area * (a[k] + b[k] + c[k]) / 3.0;
      normalSum[labels.patch[t]][k] += 0.5 * n[k];
    }
  }
  // Outward: a closed surface whose triangles turn the other way has a negative volume.
  const double orientation = volume6 < 0 ? -1.0 : 1.0;
  out.volume = std::abs(volume6) / 6.0;
  for (std::size_t k = 0; k < out.patches.size(); ++k)
  {
    PatchGeometry& patch = out.patches[k];
    patch.label = labels.patches[k];
    if (patch.area > 0)
    {
      for (double& c : patch.centre)
      {
        c /= patch.area;
      }
    }
    if (patch.label.id == kWallEntityId)
    {
      continue;
    }
    patch.equivalentDiameter = std::sqrt(4.0 * patch.area / M_PI);
    const double len = Norm(normalSum[k]);
    // A flat end's normals add up to its area; far less means a patch folded on itself.
    if (len > 1e-3 * patch.area && len > 0)
    {
      patch.hasNormal = true;
      for (int a = 0; a < 3; ++a)
      {
        patch.normal[a] = orientation * normalSum[k][a] / len;
      }
    }
  }
  if (out.closed)
  {
    out.hasInsidePoint = FindInsidePoint(points,
      labels.triangles,
      labels.patch,
      out.patches,
      orientation,
      out.insidePoint,
      out.insideClearance);
  }
  return out;
}

std::string PatchSidecarJson(const PatchSidecar& sidecar)
{
  using nlohmann::ordered_json;
  ordered_json root;
  root["format"] = "bender-patches";
  root["version"] = 1;
  root["unit"] = sidecar.unit;
  root["frame"] = StlFrameName(sidecar.frame);
  root["closed"] = sidecar.closed;
  root["volume"] = sidecar.volume;
  root["insidePoint"] = sidecar.hasInsidePoint
    ? ordered_json(std::vector<double>(sidecar.insidePoint.begin(), sidecar.insidePoint.end()))
    : ordered_json(nullptr);
  ordered_json patches = ordered_json::array();
  for (const PatchGeometry& p : sidecar.patches)
  {
    ordered_json patch;
    patch["name"] = p.label.name;
    patch["id"] = p.label.id;
    patch["type"] = PatchTypeName(p.label.type);
    patch["triangles"] = p.triangles;
    patch["area"] = p.area;
    patch["centre"] = std::vector<double>(p.centre.begin(), p.centre.end());
    patch["normal"] = p.hasNormal
      ? ordered_json(std::vector<double>(p.normal.begin(), p.normal.end()))
      : ordered_json(nullptr);
    patch["equivalentDiameter"] =
      p.label.id == kWallEntityId ? ordered_json(nullptr) : ordered_json(p.equivalentDiameter);
    patches.push_back(patch);
  }
  root["patches"] = patches;
  return root.dump(2) + "\n";
}

std::string PatchSidecarPath(const std::string& exportPath)
{
  const std::string ext = io_detail::LowerExtension(exportPath);
  const std::size_t slash = exportPath.find_last_of('/');
  std::string stem = exportPath;
  if (!ext.empty() && (slash == std::string::npos || exportPath.size() - ext.size() > slash + 1))
  {
    stem.resize(exportPath.size() - ext.size());
  }
  return stem + ".patches.json";
}

AtomicFile PatchSidecarFile(vtkPolyData* mesh,
  const std::string& path,
  const ExportTransform& transform,
  PatchSidecar* measured)
{
  std::shared_ptr<const std::string> text;
  try
  {
    const PatchSidecar sidecar = ComputePatchSidecar(mesh, transform);
    if (measured)
    {
      *measured = sidecar;
    }
    text = std::make_shared<const std::string>(PatchSidecarJson(sidecar));
  }
  catch (const StlExportError& e)
  {
    throw StlExportError(io_detail::DisplayName(path) + ": " + e.what());
  }
  return { path,
    [text](const std::string& temp, std::string& problem)
    {
      std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(
        std::fopen(temp.c_str(), "wb"), &std::fclose);
      if (!f || std::fwrite(text->data(), 1, text->size(), f.get()) != text->size() ||
        std::fclose(f.release()) != 0)
      {
        problem = "write failed";
        return false;
      }
      return true;
    } };
}

} // namespace bender
