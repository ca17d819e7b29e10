// The one inside-point algorithm (InsidePoint.h) on shapes where a point found by walking in
// from an end along its normal leaves the lumen: a U-bend with short legs, a tight elbow; and
// on the straight labelled cylinder. Every point found is checked by an independent test
// (vtkSelectEnclosedPoints) and by its distance to the known centreline.

#include "InsidePoint.h"
#include "MesherTestUtilities.h"
#include "PatchLabels.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSelectEnclosedPoints.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace bender;

namespace
{

// A closed tube of radius r around a circular arc of radius R and angle `sweep` in the xy
// plane (centre at the origin), with straight legs of length `leg` at both ends, capped by
// fans; labelled wall, inlet, outlet_1. Triangles outward. The centreline is returned.
struct BentTube
{
  vtkSmartPointer<vtkPolyData> surface;
  std::vector<Vec3> centreline;
  double radius = 0.0;
};

BentTube MakeBentTube(double r, double R, double sweep, double leg)
{
  const int segments = 48;
  const int arcRings = 64;
  const int legRings = 8;
  std::vector<Vec3> centres, tangents, normals;
  // Start leg along -y ending at (R, 0, 0), the arc counter-clockwise, the end leg along its
  // tangent.
  for (int i = 0; i < legRings; ++i)
  {
    const double s = leg * (1.0 - double(i) / legRings);
    centres.push_back({ R, -s, 0 });
    tangents.push_back({ 0, 1, 0 });
    normals.push_back({ 1, 0, 0 });
  }
  for (int i = 0; i <= arcRings; ++i)
  {
    const double a = sweep * i / arcRings;
    centres.push_back({ R * std::cos(a), R * std::sin(a), 0 });
    tangents.push_back({ -std::sin(a), std::cos(a), 0 });
    normals.push_back({ std::cos(a), std::sin(a), 0 });
  }
  for (int i = 1; i <= legRings; ++i)
  {
    const Vec3 last = centres[static_cast<std::size_t>(legRings + arcRings)];
    const Vec3 t = tangents.back();
    centres.push_back(last + t * (leg * i / legRings));
    tangents.push_back(t);
    normals.push_back(normals[static_cast<std::size_t>(legRings + arcRings)]);
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const Vec3 up{ 0, 0, 1 };
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    for (int j = 0; j < segments; ++j)
    {
      const double a = 2 * M_PI * j / segments;
      const Vec3 p = centres[i] + normals[i] * (r * std::cos(a)) + up * (r * std::sin(a));
      points->InsertNextPoint(p.x, p.y, p.z);
    }
  }
  const vtkIdType first = points->InsertNextPoint(centres.front().x, centres.front().y, 0);
  const vtkIdType last = points->InsertNextPoint(centres.back().x, centres.back().y, 0);
  vtkNew<vtkCellArray> polys;
  std::vector<int> ids;
  const auto at = [&](std::size_t i, int j)
  { return static_cast<vtkIdType>(i * segments + static_cast<std::size_t>(j % segments)); };
  // Every edge is used once in each direction: the surface is closed and consistently
  // oriented (which way does not matter to the algorithm).
  for (std::size_t i = 0; i + 1 < centres.size(); ++i)
  {
    for (int j = 0; j < segments; ++j)
    {
      polys->InsertNextCell({ at(i, j), at(i + 1, j), at(i + 1, j + 1) });
      polys->InsertNextCell({ at(i, j), at(i + 1, j + 1), at(i, j + 1) });
      ids.insert(ids.end(), { kWallEntityId, kWallEntityId });
    }
  }
  for (int j = 0; j < segments; ++j)
  {
    polys->InsertNextCell({ first, at(0, j), at(0, j + 1) });
    ids.push_back(2);
    polys->InsertNextCell({ last, at(centres.size() - 1, j + 1), at(centres.size() - 1, j) });
    ids.push_back(3);
  }
  BentTube tube;
  tube.surface = vtkSmartPointer<vtkPolyData>::New();
  tube.surface->SetPoints(points);
  tube.surface->SetPolys(polys);
  WritePatchLabels(tube.surface,
    ids,
    { { kWallEntityId, "wall", PatchType::Wall },
      { 2, "inlet", PatchType::Inlet },
      { 3, "outlet_1", PatchType::Outlet } });
  tube.centreline = centres;
  tube.radius = r;
  return tube;
}

double DistanceToPolyline(const std::vector<Vec3>& line, const Vec3& p)
{
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
  {
    const Vec3 d = line[i + 1] - line[i];
    const double t = std::clamp(Dot(p - line[i], d) / Dot(d, d), 0.0, 1.0);
    best = std::min(best, Norm(p - (line[i] + d * t)));
  }
  return best;
}

bool EnclosedByVtk(vtkPolyData* surface, const Vec3& p)
{
  vtkNew<vtkSelectEnclosedPoints> enclosed;
  enclosed->SetTolerance(1e-6);
  enclosed->Initialize(surface);
  double x[3] = { p.x, p.y, p.z };
  const bool inside = enclosed->IsInsideSurface(x) != 0;
  enclosed->Complete();
  return inside;
}

void ExpectDeepInside(const BentTube& tube)
{
  const std::optional<LumenPoint> inside = FindInsidePoint(ReadLabelledSurface(tube.surface));
  ASSERT_TRUE(inside.has_value());
  EXPECT_TRUE(EnclosedByVtk(tube.surface, inside->point));
  // Far from the wall: within half a radius of the centreline, its clearance what that leaves.
  EXPECT_LT(DistanceToPolyline(tube.centreline, inside->point), 0.5 * tube.radius);
  EXPECT_GT(inside->clearance, 0.5 * tube.radius);
  EXPECT_LE(inside->clearance, tube.radius * (1 + 1e-9));
}

} // namespace

TEST(InsidePoint, UBendWithShortLegs)
{
  // The inlet's inward normal runs straight into the far wall of the bend within 1.5 radii.
  ExpectDeepInside(MakeBentTube(1.0, 1.6, M_PI, 0.3));
}

TEST(InsidePoint, TightElbow)
{
  ExpectDeepInside(MakeBentTube(2.0, 2.5, 0.5 * M_PI, 0.5));
}

TEST(InsidePoint, EitherOrientation)
{
  BentTube tube = MakeBentTube(1.0, 4.0, 0.75 * M_PI, 2.0);
  ExpectDeepInside(tube);
  // The same surface with every triangle turned: the winding number is -1 inside.
  vtkNew<vtkCellArray> flipped;
  tube.surface->GetPolys()->InitTraversal();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  while (tube.surface->GetPolys()->GetNextCell(n, ids))
  {
    flipped->InsertNextCell({ ids[0], ids[2], ids[1] });
  }
  tube.surface->SetPolys(flipped);
  ExpectDeepInside(tube);
}

TEST(InsidePoint, LabelledCylinder)
{
  const auto cylinder = bender_test::LabelledCylinder();
  const std::optional<LumenPoint> inside = FindInsidePoint(ReadLabelledSurface(cylinder));
  ASSERT_TRUE(inside.has_value());
  const double off = std::hypot(inside->point.x - bender_test::Offset, inside->point.y);
  EXPECT_LT(off, 0.5);
  EXPECT_GT(inside->point.z, 0.0);
  EXPECT_LT(inside->point.z, bender_test::Rings - 1.0);
  EXPECT_TRUE(EnclosedByVtk(cylinder, inside->point));
}

TEST(InsidePoint, NoneForAnOpenSurface)
{
  BentTube tube = MakeBentTube(1.0, 3.0, 0.5 * M_PI, 1.0);
  // Drop the caps: an open tube has no inside.
  vtkNew<vtkCellArray> wall;
  tube.surface->GetPolys()->InitTraversal();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType cell = 0;
  const vtkIdType wallCells = tube.surface->GetNumberOfPolys() - 2 * 48;
  while (tube.surface->GetPolys()->GetNextCell(n, ids) && cell++ < wallCells)
  {
    wall->InsertNextCell(n, ids);
  }
  vtkNew<vtkPolyData> open;
  open->SetPoints(tube.surface->GetPoints());
  open->SetPolys(wall);
  EXPECT_FALSE(FindInsidePoint(ReadLabelledSurface(open)).has_value());
}
