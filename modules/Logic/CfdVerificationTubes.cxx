#include "CfdVerificationTubes.h"

#include "BenderErrors.h"
#include "PatchLabels.h"

#include <vtkCellArray.h>
#include <vtkPoints.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace bender
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

// Point k (modulo sides) of ring r.
vtkIdType Ring(int sides, std::size_t r, int k)
{
  return static_cast<vtkIdType>(
    r * static_cast<std::size_t>(sides) + static_cast<std::size_t>(k % sides));
}

// Throws InputError unless there are 2 stations or more, radius > 0 and `minSides` sides or more.
void CheckTube(const std::vector<TubeStation>& stations, double radius, int sides, int minSides)
{
  if (stations.size() < 2 || !(radius > 0.0) || sides < minSides)
  {
    throw InputError("generated tube: " + std::to_string(stations.size()) + " stations, radius " +
      std::to_string(radius) + " mm, " + std::to_string(sides) +
      " sides (give 2 stations or more, a radius > 0 and " + std::to_string(minSides) +
      " sides or more)");
  }
}
} // namespace

std::vector<TubeStation> StraightCentreline(double length, double spacing)
{
  return StraightCentreline(
    0.0, length, std::max(1, static_cast<int>(std::ceil(length / spacing))));
}

std::vector<TubeStation> StraightCentreline(double from, double to, int pieces)
{
  pieces = std::max(1, pieces);
  std::vector<TubeStation> stations;
  for (int i = 0; i <= pieces; ++i)
  {
    const double x = from + (to - from) * i / pieces;
    stations.push_back({ { x, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, x - from });
  }
  return stations;
}

std::vector<TubeStation> ArcCentreline(double bendRadius, double angle, double spacing)
{
  const int pieces = std::max(1, static_cast<int>(std::ceil(bendRadius * angle / spacing)));
  std::vector<TubeStation> stations;
  for (int i = 0; i <= pieces; ++i)
  {
    const double a = angle * i / pieces;
    const Vec3 centre{ bendRadius * std::sin(a), bendRadius * (1.0 - std::cos(a)), 0.0 };
    const Vec3 tangent{ std::cos(a), std::sin(a), 0.0 };
    // Towards the arc's centre: the inner wall of the bend starts each ring.
    const Vec3 normal{ -std::sin(a), std::cos(a), 0.0 };
    stations.push_back({ centre, tangent, normal, bendRadius * a });
  }
  return stations;
}

vtkSmartPointer<vtkPolyData> SweepOpenTube(const std::vector<TubeStation>& stations,
  double radius,
  int sides)
{
  CheckTube(stations, radius, sides, 3);
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  for (const TubeStation& s : stations)
  {
    const Vec3 binormal = Cross(s.tangent, s.normal);
    for (int k = 0; k < sides; ++k)
    {
      const double a = 2.0 * Pi * k / sides;
      const Vec3 p = s.centre + radius * (std::cos(a) * s.normal + std::sin(a) * binormal);
      points->InsertNextPoint(p.x, p.y, p.z);
    }
  }
  // Rings ordered counter-clockwise about the tangent: (a, b, d) and (a, d, c) face outwards.
  auto triangles = vtkSmartPointer<vtkCellArray>::New();
  for (std::size_t r = 0; r + 1 < stations.size(); ++r)
  {
    for (int k = 0; k < sides; ++k)
    {
      const vtkIdType a = Ring(sides, r, k), b = Ring(sides, r, k + 1), c = Ring(sides, r + 1, k),
                      d = Ring(sides, r + 1, k + 1);
      const vtkIdType t1[3] = { a, b, d };
      const vtkIdType t2[3] = { a, d, c };
      triangles->InsertNextCell(3, t1);
      triangles->InsertNextCell(3, t2);
    }
  }
  auto tube = vtkSmartPointer<vtkPolyData>::New();
  tube->SetPoints(points);
  tube->SetPolys(triangles);
  return tube;
}

vtkSmartPointer<vtkPolyData> SweepClosedTube(const std::vector<TubeStation>& stations,
  double radius,
  int sides)
{
  CheckTube(stations, radius, sides, 8);
  vtkSmartPointer<vtkPolyData> tube = SweepOpenTube(stations, radius, sides);
  vtkPoints* points = tube->GetPoints();
  vtkCellArray* triangles = tube->GetPolys();
  std::vector<int> ids(static_cast<std::size_t>(triangles->GetNumberOfCells()), kWallEntityId);
  const vtkIdType inletCentre = points->InsertNextPoint(
    stations.front().centre.x, stations.front().centre.y, stations.front().centre.z);
  const vtkIdType outletCentre = points->InsertNextPoint(
    stations.back().centre.x, stations.back().centre.y, stations.back().centre.z);
  // Flat caps as fans: the inlet faces against the first tangent, the outlet along the last.
  const std::size_t last = stations.size() - 1;
  for (int k = 0; k < sides; ++k)
  {
    const vtkIdType in[3] = { inletCentre, Ring(sides, 0, k + 1), Ring(sides, 0, k) };
    triangles->InsertNextCell(3, in);
    ids.push_back(kWallEntityId + 1);
  }
  for (int k = 0; k < sides; ++k)
  {
    const vtkIdType out[3] = { outletCentre, Ring(sides, last, k), Ring(sides, last, k + 1) };
    triangles->InsertNextCell(3, out);
    ids.push_back(kWallEntityId + 2);
  }
  WritePatchLabels(tube,
    ids,
    { { kWallEntityId, "wall", PatchType::Wall },
      { kWallEntityId + 1, "inlet", PatchType::Inlet },
      { kWallEntityId + 2, "outlet_1", PatchType::Outlet } });
  return tube;
}

} // namespace bender
