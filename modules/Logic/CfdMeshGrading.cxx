#include "CfdMeshGrading.h"

#include "CfdDictionaries.h"
#include "CfdPatches.h"
#include "PatchLabels.h"
#include "Vec3.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <locale>
#include <sstream>

namespace bender
{
namespace
{

Vec3 PointOf(vtkPolyData* surface, vtkIdType id)
{
  double x[3];
  surface->GetPoint(id, x);
  return { x[0], x[1], x[2] };
}

/// The cells sharing a point with each cell (itself included), from the cell array.
std::vector<std::vector<vtkIdType>> CellNeighbours(vtkPolyData* surface)
{
  const vtkIdType cells = surface->GetNumberOfCells();
  std::vector<std::vector<vtkIdType>> byPoint(
    static_cast<std::size_t>(surface->GetNumberOfPoints()));
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < cells; ++c)
  {
    surface->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      byPoint[static_cast<std::size_t>(ids->GetId(k))].push_back(c);
    }
  }
  std::vector<std::vector<vtkIdType>> neighbours(static_cast<std::size_t>(cells));
  for (vtkIdType c = 0; c < cells; ++c)
  {
    surface->GetCellPoints(c, ids);
    auto& n = neighbours[static_cast<std::size_t>(c)];
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      const auto& around = byPoint[static_cast<std::size_t>(ids->GetId(k))];
      n.insert(n.end(), around.begin(), around.end());
    }
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return neighbours;
}

double Median(std::vector<double>& values)
{
  const std::size_t middle = values.size() / 2;
  std::nth_element(
    values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle), values.end());
  return values[middle];
}

/// The share of the cells across that an end may lack before it is refined: two ends of one
/// width measured a hair apart (0.01 %) are meshed alike.
constexpr double kEndCellsTolerance = 0.99;

} // namespace

std::vector<double> LocalLumenDiameters(vtkPolyData* surface, const std::vector<bool>& measure)
{
  const vtkIdType cells = surface->GetNumberOfCells();
  std::vector<double> diameters(static_cast<std::size_t>(cells), 0.0);
  std::vector<Vec3> centres(diameters.size()), normals(diameters.size());
  vtkNew<vtkIdList> ids;
  double volume6 = 0.0;
  for (vtkIdType c = 0; c < cells; ++c)
  {
    surface->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() < 3)
    {
      continue;
    }
    const Vec3 a = PointOf(surface, ids->GetId(0));
    const Vec3 b = PointOf(surface, ids->GetId(1));
    const Vec3 d = PointOf(surface, ids->GetId(2));
    volume6 += Dot(a, Cross(b, d));
    centres[static_cast<std::size_t>(c)] = (a + b + d) / 3.0;
    normals[static_cast<std::size_t>(c)] = Cross(b - a, d - a);
  }
  // Outward triangles enclose a positive volume: the chords go against their normals.
  const double inward = volume6 < 0.0 ? 1.0 : -1.0;
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(surface);
  locator->BuildLocator();
  const double diagonal = surface->GetLength();
  for (vtkIdType c = 0; c < cells; ++c)
  {
    const std::size_t i = static_cast<std::size_t>(c);
    const double length = Norm(normals[i]);
    if (!measure[i] || !(length > 0.0))
    {
      continue;
    }
    const Vec3 direction = normals[i] * (inward / length);
    const Vec3 from = centres[i] + direction * (1e-7 * diagonal);
    const Vec3 to = centres[i] + direction * (2.0 * diagonal);
    double p1[3] = { from.x, from.y, from.z }, p2[3] = { to.x, to.y, to.z };
    double t = 0.0, x[3], pcoords[3];
    int subId = 0;
    vtkIdType hit = -1;
    if (locator->IntersectWithLine(p1, p2, 0.0, t, x, pcoords, subId, hit) && hit != c)
    {
      diameters[i] = Distance(centres[i], Vec3{ x[0], x[1], x[2] });
    }
  }

  // Medians over each cell's neighbours: a bump of the segmentation or a chord grazing a fold
  // does not refine a stretch of its own.
  const std::vector<std::vector<vtkIdType>> neighbours = CellNeighbours(surface);
  std::vector<double> values;
  for (int pass = 0; pass < 3; ++pass)
  {
    std::vector<double> smoothed = diameters;
    for (std::size_t i = 0; i < diameters.size(); ++i)
    {
      if (!(diameters[i] > 0.0))
      {
        continue;
      }
      values.clear();
      for (const vtkIdType n : neighbours[i])
      {
        if (diameters[static_cast<std::size_t>(n)] > 0.0)
        {
          values.push_back(diameters[static_cast<std::size_t>(n)]);
        }
      }
      smoothed[i] = Median(values);
    }
    diameters.swap(smoothed);
  }
  return diameters;
}

int CfdRefinementLevel(double diameter, double cellSize, double cellsAcross)
{
  if (!(diameter > 0.0) || !(cellSize > 0.0))
  {
    return 1;
  }
  // The smallest k with diameter / (cellSize / 2^k) >= cellsAcross (a hair of tolerance, so
  // that a diameter of exactly cellsAcross cells stays at its level).
  const double extra = std::ceil(std::log2(cellsAcross * cellSize / diameter) - 1e-9);
  return 1 + static_cast<int>(std::clamp(extra, 0.0, static_cast<double>(kCfdMaxExtraLevels)));
}

double CfdLevelCellSize(int level, double cellSize)
{
  return std::ldexp(cellSize, 1 - level);
}

CfdGradedMesh GradeCfdMesh(const LabelledSurface& surface,
  const std::vector<CfdPatch>& patches,
  double cellSize,
  double cellsAcross)
{
  CfdGradedMesh graded;
  CfdMeshGrading& g = graded.grading;
  g.cellsAcross = cellsAcross;
  for (const CfdPatch& p : patches)
  {
    if (IsEndPatch(p.type))
    {
      CfdEndCells end;
      end.name = p.name;
      end.level = CfdRefinementLevel(p.diameter, cellSize, kEndCellsTolerance * cellsAcross);
      end.cellSize = CfdLevelCellSize(end.level, cellSize);
      end.cellsAcross = p.diameter / end.cellSize;
      g.ends.push_back(end);
    }
  }

  // The wall's triangles, their local diameters (mm) and levels.
  vtkPolyData* mesh = surface.surface;
  const std::vector<int> patchIds = CellPatchIds(mesh);
  std::vector<bool> wall(patchIds.size(), false);
  for (const PatchLabel& l : surface.patches)
  {
    if (l.type == PatchType::Wall)
    {
      for (std::size_t i = 0; i < patchIds.size(); ++i)
      {
        wall[i] = wall[i] || patchIds[i] == l.id;
      }
    }
  }
  const std::vector<double> diameters = LocalLumenDiameters(mesh, wall);
  std::vector<int> levels(diameters.size(), 0);
  g.wallCellsAcross = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < diameters.size(); ++i)
  {
    if (!wall[i] || !(diameters[i] > 0.0))
    {
      continue;
    }
    const double d = 1e-3 * diameters[i];
    levels[i] = CfdRefinementLevel(d, cellSize, kCfdWallCellsMargin * cellsAcross);
    const double across = d / CfdLevelCellSize(levels[i], cellSize);
    g.wallCellsAcross = std::min(g.wallCellsAcross, across);
    if (g.narrowestDiameter == 0.0 || d < g.narrowestDiameter)
    {
      g.narrowestDiameter = d;
      g.narrowestCellsAcross = across;
      double centre[3] = { 0.0, 0.0, 0.0 };
      vtkNew<vtkIdList> ids;
      mesh->GetCellPoints(static_cast<vtkIdType>(i), ids);
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        const Vec3 x = PointOf(mesh, ids->GetId(k));
        centre[0] += x.x / ids->GetNumberOfIds();
        centre[1] += x.y / ids->GetNumberOfIds();
        centre[2] += x.z / ids->GetNumberOfIds();
      }
      g.narrowestAt = { 1e-3 * centre[0], 1e-3 * centre[1], 1e-3 * centre[2] };
    }
  }
  if (!std::isfinite(g.wallCellsAcross))
  {
    g.wallCellsAcross = 0.0;
  }

  // One region per level above the base: the wall triangles of that level or finer.
  for (int level = 2; level <= 1 + kCfdMaxExtraLevels; ++level)
  {
    vtkNew<vtkCellArray> cells;
    CfdRefinementRegion region;
    region.name = "refinement_level_" + std::to_string(level);
    region.level = level;
    region.cellSize = CfdLevelCellSize(level, cellSize);
    vtkNew<vtkIdList> ids;
    for (std::size_t i = 0; i < levels.size(); ++i)
    {
      if (levels[i] >= level)
      {
        mesh->GetCellPoints(static_cast<vtkIdType>(i), ids);
        cells->InsertNextCell(ids);
        region.distance = std::max(region.distance, 0.5e-3 * diameters[i]);
        ++region.triangles;
      }
    }
    if (region.triangles == 0)
    {
      break;
    }
    auto part = vtkSmartPointer<vtkPolyData>::New();
    part->SetPoints(mesh->GetPoints());
    part->SetPolys(cells);
    g.regions.push_back(region);
    graded.regionSurfaces.push_back(part);
  }
  return graded;
}

std::string FormatCfdMeshGrading(const CfdMeshGrading& g)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "  wall cells across each end (its equivalent diameter / its cell size):";
  for (const CfdEndCells& e : g.ends)
  {
    s << " " << e.name << " " << CfdShort(e.cellsAcross, 2);
  }
  s << "\n  grading: at least " << CfdShort(g.cellsAcross, 2) << " cells across every end";
  for (const CfdEndCells& e : g.ends)
  {
    if (e.level > 1)
    {
      s << "; " << e.name << " refined to " << CfdShort(1e3 * e.cellSize) << " mm (level "
        << e.level << ")";
    }
  }
  s << "\n";
  if (g.narrowestDiameter > 0.0)
  {
    s << "  the lumen: at least " << CfdShort(g.wallCellsAcross, 2)
      << " cells across everywhere on the wall; narrowest " << CfdShort(1e3 * g.narrowestDiameter)
      << " mm at (" << CfdShort(1e3 * g.narrowestAt[0], 4) << ", "
      << CfdShort(1e3 * g.narrowestAt[1], 4) << ", " << CfdShort(1e3 * g.narrowestAt[2], 4)
      << ") mm, " << CfdShort(g.narrowestCellsAcross, 2) << " cells across\n";
  }
  for (const CfdRefinementRegion& r : g.regions)
  {
    s << "  refined to " << CfdShort(1e3 * r.cellSize) << " mm (level " << r.level << ") within "
      << CfdShort(1e3 * r.distance) << " mm of " << r.triangles << " wall triangles\n";
  }
  return s.str();
}

nlohmann::ordered_json CfdMeshGradingJson(const CfdMeshGrading& g)
{
  nlohmann::ordered_json ends = nlohmann::ordered_json::array();
  for (const CfdEndCells& e : g.ends)
  {
    ends.push_back({ { "name", e.name },
      { "level", e.level },
      { "cellSize_m", e.cellSize },
      { "cellsAcross", e.cellsAcross } });
  }
  nlohmann::ordered_json regions = nlohmann::ordered_json::array();
  for (const CfdRefinementRegion& r : g.regions)
  {
    regions.push_back({ { "name", r.name },
      { "level", r.level },
      { "cellSize_m", r.cellSize },
      { "distance_m", r.distance },
      { "wallTriangles", r.triangles } });
  }
  return { { "cellsAcrossEachEnd", g.cellsAcross },
    { "ends", ends },
    { "wallCellsAcrossMin", g.wallCellsAcross },
    { "narrowestDiameter_m", g.narrowestDiameter },
    { "narrowestAt_m", g.narrowestAt },
    { "narrowestCellsAcross", g.narrowestCellsAcross },
    { "regions", regions } };
}

} // namespace bender
