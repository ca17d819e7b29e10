#include "CfdPatches.h"

#include "BenderErrors.h"
#include "InsidePoint.h"

#include <vtkCellType.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace bender
{

namespace
{

constexpr double kPi = 3.14159265358979323846;

/// Per-patch sums over the triangles of the surface (in its unit, mm).
struct PatchSums
{
  long long triangles = 0;
  double area = 0.0;
  std::array<double, 3> vectorArea{};
  std::array<double, 3> weightedCentre{};
};

void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/// Adds triangle (a, b, c) of patch index `patch` to the sums and to the signed volume.
void AddTriangle(vtkPoints* points,
  vtkIdType a,
  vtkIdType b,
  vtkIdType c,
  PatchSums& sums,
  double& volume)
{
  double p0[3], p1[3], p2[3];
  points->GetPoint(a, p0);
  points->GetPoint(b, p1);
  points->GetPoint(c, p2);
  const double e1[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  const double e2[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
  double n[3];
  Cross(e1, e2, n);
  const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  ++sums.triangles;
  sums.area += area;
  for (int k = 0; k < 3; ++k)
  {
    sums.vectorArea[k] += 0.5 * n[k];
    sums.weightedCentre[k] += area * (p0[k] + p1[k] + p2[k]) / 3.0;
  }
  double p1xp2[3];
  Cross(p1, p2, p1xp2);
  volume += (p0[0] * p1xp2[0] + p0[1] * p1xp2[1] + p0[2] * p1xp2[2]) / 6.0;
}

} // namespace

bool IsEndPatch(PatchType type)
{
  return type != PatchType::Wall;
}

std::vector<CfdPatch> MeasurePatches(vtkPolyData* surface,
  const std::vector<PatchLabel>& labels,
  const std::string& name)
{
  const std::vector<int> ids = CellPatchIds(surface);
  int maxId = 0;
  for (const auto& l : labels)
  {
    maxId = std::max(maxId, l.id);
  }
  std::vector<PatchSums> sums(static_cast<std::size_t>(maxId) + 1);
  double volume = 0.0;
  vtkPoints* points = surface->GetPoints();
  vtkNew<vtkIdList> cell;
  for (vtkIdType i = 0; i < surface->GetNumberOfCells(); ++i)
  {
    const int type = surface->GetCellType(i);
    if (type != VTK_TRIANGLE && type != VTK_POLYGON && type != VTK_QUAD &&
      type != VTK_TRIANGLE_STRIP)
    {
      continue;
    }
    surface->GetCellPoints(i, cell);
    const vtkIdType n = cell->GetNumberOfIds();
    const int id = ids[static_cast<std::size_t>(i)];
    if (id < 0 || id > maxId)
    {
      continue;
    }
    PatchSums& s = sums[static_cast<std::size_t>(id)];
    if (type == VTK_TRIANGLE_STRIP)
    {
      for (vtkIdType k = 0; k + 2 < n; ++k)
      {
        if (k % 2 == 0)
        {
          AddTriangle(points, cell->GetId(k), cell->GetId(k + 1), cell->GetId(k + 2), s, volume);
        }
        else
        {
          AddTriangle(points, cell->GetId(k + 1), cell->GetId(k), cell->GetId(k + 2), s, volume);
        }
      }
    }
    else
    {
      for (vtkIdType k = 1; k + 1 < n; ++k)
      {
        AddTriangle(points, cell->GetId(0), cell->GetId(k), cell->GetId(k + 1), s, volume);
      }
    }
  }
  if (!(std::abs(volume) > 0.0) || !std::isfinite(volume))
  {
    throw InputError(name + ": the surface encloses no volume");
  }
  const double outward = volume > 0.0 ? 1.0 : -1.0;
  std::vector<CfdPatch> patches;
  for (const auto& l : labels)
  {
    const PatchSums& s = sums[static_cast<std::size_t>(l.id)];
    CfdPatch p;
    p.name = l.name;
    p.type = l.type;
    p.triangles = s.triangles;
    p.area = s.area * 1e-6;
    if (s.area > 0.0)
    {
      for (int k = 0; k < 3; ++k)
      {
        p.centre[static_cast<std::size_t>(k)] =
          1e-3 * s.weightedCentre[static_cast<std::size_t>(k)] / s.area;
      }
    }
    const double norm = std::sqrt(s.vectorArea[0] * s.vectorArea[0] +
      s.vectorArea[1] * s.vectorArea[1] + s.vectorArea[2] * s.vectorArea[2]);
    if (norm > 0.0)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        p.normal[k] = outward * s.vectorArea[k] / norm;
      }
    }
    p.diameter = 2.0 * std::sqrt(p.area / kPi);
    patches.push_back(p);
  }
  return patches;
}

std::array<double, 3> InsidePoint(vtkPolyData* surface, double cellSize, const std::string& name)
{
  const std::optional<LumenPoint> found = FindInsidePoint(surface);
  if (!found)
  {
    throw InputError(name +
      ": no point inside the lumen was found behind its ends (is the "
      "surface oriented consistently and closed?)");
  }
  // Metres, nudged off the background grid's planes (a fraction of a cell: far less than the
  // point's distance to the wall).
  const double mm[3] = { found->point.x, found->point.y, found->point.z };
  std::array<double, 3> x{};
  for (std::size_t k = 0; k < 3; ++k)
  {
    x[k] = 1e-3 * mm[k] + (0.0173 + 0.0119 * static_cast<double>(k)) * cellSize;
  }
  return x;
}

} // namespace bender
