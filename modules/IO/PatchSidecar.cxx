#include "PatchSidecar.h"

#include "FileUtilities.h"
#include "InsidePoint.h"
#include "StringUtil.h"
#include "Vec3.h"

#include <nlohmann/json.hpp>

#include <vtkPolyData.h>

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

Vec3 Corner(const std::vector<Vec>& points, vtkIdType id)
{
  const Vec& p = points[static_cast<std::size_t>(id)];
  return { p[0], p[1], p[2] };
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

} // namespace

PatchSidecar ComputePatchSidecar(const LabelledSurface& mesh, const ExportTransform& transform)
{
  const LabelledTriangles labels = CollectLabelledTriangles(mesh);
  PatchSidecar out;
  out.unit = transform.Unit();
  out.frame = transform.Frame();
  vtkPolyData* surface = mesh.surface;
  std::vector<Vec> points(static_cast<std::size_t>(surface->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double in[3];
    surface->GetPoint(i, in);
    transform.Apply(in, points[static_cast<std::size_t>(i)].data());
  }
  out.closed = IsClosed(labels.triangles);
  std::vector<Vec3> normalSum(labels.patches.size());
  out.patches.resize(labels.patches.size());
  double volume6 = 0.0;
  for (std::size_t t = 0; t < labels.triangles.size(); ++t)
  {
    const Vec3 a = Corner(points, labels.triangles[t][0]);
    const Vec3 b = Corner(points, labels.triangles[t][1]);
    const Vec3 c = Corner(points, labels.triangles[t][2]);
    const Vec3 n = Cross(b - a, c - a); // twice the area, along the normal
    const double area = 0.5 * Norm(n);
    volume6 += Dot(a, Cross(b, c));
    PatchGeometry& patch = out.patches[labels.patch[t]];
    patch.triangles++;
    patch.area += area;
    for (int k = 0; k < 3; ++k)
    {
      patch.areaMoment[k] += area * (a[k] + b[k] + c[k]) / 3.0;
    }
    normalSum[labels.patch[t]] += 0.5 * n;
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
      for (int a = 0; a < 3; ++a)
      {
        patch.centre[a] = patch.areaMoment[a] / patch.area;
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      patch.vectorArea[a] = orientation * normalSum[k][a];
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
        patch.normal[a] = patch.vectorArea[a] / len;
      }
    }
  }
  if (out.closed)
  {
    // Chords from each end's centre against its outward normal, then from wall triangles.
    std::vector<InwardRay> seeds;
    for (const PatchGeometry& patch : out.patches)
    {
      if (patch.hasNormal)
      {
        seeds.push_back({ { patch.centre[0], patch.centre[1], patch.centre[2] },
          { -patch.normal[0], -patch.normal[1], -patch.normal[2] } });
      }
    }
    std::vector<bool> wall(labels.triangles.size());
    for (std::size_t t = 0; t < wall.size(); ++t)
    {
      wall[t] = out.patches[labels.patch[t]].label.id == kWallEntityId;
    }
    if (const std::optional<LumenPoint> inside =
          FindLumenPoint(points, labels.triangles, seeds, wall))
    {
      out.hasInsidePoint = true;
      out.insidePoint = { inside->point.x, inside->point.y, inside->point.z };
      out.insideClearance = inside->clearance;
    }
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
  const std::string ext = LowerExtension(exportPath);
  const std::size_t slash = exportPath.find_last_of('/');
  std::string stem = exportPath;
  if (!ext.empty() && (slash == std::string::npos || exportPath.size() - ext.size() > slash + 1))
  {
    stem.resize(exportPath.size() - ext.size());
  }
  return stem + ".patches.json";
}

AtomicFile PatchSidecarFile(const LabelledSurface& mesh,
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
    throw StlExportError(DisplayName(path) + ": " + e.what());
  }
  return { path, TextProducer(text) };
}

} // namespace bender
