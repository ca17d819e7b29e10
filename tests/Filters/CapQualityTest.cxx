// vtkBenderCapFilter's caps: flat (every cap point on one plane), well shaped away from the
// rim (minimum angle >= 20 degrees), sharing the rim vertices (closed, manifold, consistent),
// facing outwards whatever the input's orientation, labelled through PatchLabels (largest cap
// "inlet", names by position), on frustums with long and uneven rims.

#include "BenderMeshCheck.h"
#include "MeshTopology.h"
#include "PatchLabels.h"
#include "VtkErrorWatch.h"
#include "vtkBenderCapFilter.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace
{
// An open frustum along z from radius r0 at z = 0 to r1 at z = length, `around` points per
// ring and `along` segments, oriented outwards (or inwards). wobble > 0 makes the rim points
// unevenly spaced (angles jittered deterministically by up to wobble x the spacing).
vtkSmartPointer<vtkPolyData> Frustum(double r0,
  double r1,
  double length,
  int around,
  int along,
  bool outwards = true,
  double wobble = 0.0)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (int j = 0; j <= along; ++j)
  {
    const double z = length * j / along;
    const double r = r0 + (r1 - r0) * j / along;
    for (int i = 0; i < around; ++i)
    {
      const double jitter = wobble * std::sin(7.3 * i + 1.1 * j);
      const double a = 2 * M_PI * (i + jitter) / around;
      pts->InsertNextPoint(r * std::cos(a), r * std::sin(a), z);
    }
  }
  vtkNew<vtkCellArray> polys;
  for (int j = 0; j < along; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const vtkIdType a = j * around + i, b = j * around + (i + 1) % around;
      const vtkIdType c = a + around, d = b + around;
      vtkIdType t1[3] = { a, b, d }, t2[3] = { a, d, c };
      if (!outwards)
      {
        std::swap(t1[1], t1[2]);
        std::swap(t2[1], t2[2]);
      }
      polys->InsertNextCell(3, t1);
      polys->InsertNextCell(3, t2);
    }
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  return pd;
}

double MinAngle(const double a[3], const double b[3], const double c[3])
{
  const double* v[3] = { a, b, c };
  double best = 180;
  for (int k = 0; k < 3; ++k)
  {
    double u[3], w[3];
    vtkMath::Subtract(v[(k + 1) % 3], v[k], u);
    vtkMath::Subtract(v[(k + 2) % 3], v[k], w);
    best = std::min(best, vtkMath::DegreesFromRadians(vtkMath::AngleBetweenVectors(u, w)));
  }
  return best;
}

struct CapMeasures
{
  double maxPlaneDistance = 0; // of every cap point to the plane fitted through the rim
  double minInteriorAngle = 180;
  int interiorTriangles = 0;
  std::set<vtkIdType> capPoints;
  double normal[3] = { 0, 0, 0 }; // area-weighted, unnormalised
  double centre[3] = { 0, 0, 0 };
};

// Measures the triangles of patch `id` (rim = points also used by the wall).
CapMeasures Measure(vtkPolyData* mesh, int id)
{
  const std::vector<int> ids = bender::CellPatchIds(mesh);
  std::set<vtkIdType> wallPoints;
  const auto tris = bender::CollectTriangles(mesh);
  CapMeasures m;
  for (std::size_t t = 0; t < ids.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      (ids[t] == id ? m.capPoints : wallPoints).insert(tris[3 * t + k]);
    }
  }
  int count = 0;
  for (vtkIdType v : m.capPoints)
  {
    double p[3];
    mesh->GetPoint(v, p);
    vtkMath::Add(m.centre, p, m.centre);
    ++count;
  }
  vtkMath::MultiplyScalar(m.centre, 1.0 / count);
  for (std::size_t t = 0; t < ids.size(); ++t)
  {
    if (ids[t] != id)
    {
      continue;
    }
    double a[3], b[3], c[3], u[3], w[3], n[3];
    mesh->GetPoint(tris[3 * t], a);
    mesh->GetPoint(tris[3 * t + 1], b);
    mesh->GetPoint(tris[3 * t + 2], c);
    vtkMath::Subtract(b, a, u);
    vtkMath::Subtract(c, a, w);
    vtkMath::Cross(u, w, n);
    vtkMath::Add(m.normal, n, m.normal);
    bool onRim = false;
    for (int k = 0; k < 3; ++k)
    {
      onRim = onRim || wallPoints.count(tris[3 * t + k]) > 0;
    }
    if (!onRim)
    {
      m.minInteriorAngle = std::min(m.minInteriorAngle, MinAngle(a, b, c));
      ++m.interiorTriangles;
    }
  }
  double unit[3] = { m.normal[0], m.normal[1], m.normal[2] };
  vtkMath::Normalize(unit);
  for (vtkIdType v : m.capPoints)
  {
    double p[3], d[3];
    mesh->GetPoint(v, p);
    vtkMath::Subtract(p, m.centre, d);
    m.maxPlaneDistance = std::max(m.maxPlaneDistance, std::abs(vtkMath::Dot(d, unit)));
  }
  return m;
}

class CapQuality : public ::testing::Test
{
protected:
  void SetUp() override { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
};
} // namespace

TEST_F(CapQuality, FlatWellShapedWatertightOutwardCaps)
{
  for (const bool outwards : { true, false })
  {
    // A long uneven rim at z = 0 (radius 3, 160 points) and a small one at z = 20.
    auto frustum = Frustum(3.0, 1.5, 20.0, 160, 40, outwards, 0.3);
    vtkNew<vtkBenderCapFilter> cap;
    bendertest::VtkErrorWatch errors(cap);
    cap->SetInputData(frustum);
    cap->Update();
    ASSERT_TRUE(errors.ExpectNone());
    ASSERT_EQ(cap->GetNumberOfCaps(), 2);
    vtkPolyData* out = cap->GetOutput();
    bender::MeshCheckOptions check;
    check.requireClosed = true;
    const auto report = bender::CheckMesh(out, nullptr, check);
    EXPECT_TRUE(report.Clean()) << bender::FormatReportText(report, "capped");
    EXPECT_TRUE(report.closed);
    EXPECT_EQ(report.nonManifoldEdges, 0);
    EXPECT_EQ(report.inconsistentEdges, 0);
    EXPECT_GT(report.volume, 0.0) << "outwards " << outwards; // faces outwards
    // Rim shared exactly: the wall's points are unchanged in number and the caps add only
    // interior points.
    int interior = 0;
    const auto labels = bender::ReadPatchLabels(out);
    ASSERT_EQ(labels.size(), 3u);
    EXPECT_EQ(labels[1].name, "inlet"); // the larger cap
    EXPECT_EQ(labels[2].name, "outlet_1");
    for (int id : { 2, 3 })
    {
      const CapMeasures m = Measure(out, id);
      const double radius = id == 2 ? 3.0 : 1.5;
      EXPECT_LE(m.maxPlaneDistance, 1e-6 * radius) << "cap " << id;
      EXPECT_GT(m.interiorTriangles, 0) << "cap " << id;
      EXPECT_GE(m.minInteriorAngle, 20.0) << "cap " << id;
      // Outwards: the inlet (z = 0) faces -z, the outlet +z.
      const double expected = id == 2 ? -1.0 : 1.0;
      EXPECT_GT(expected * m.normal[2], 0.99 * vtkMath::Norm(m.normal)) << "cap " << id;
      const auto& info = cap->GetCaps()[static_cast<std::size_t>(id - 2)];
      EXPECT_EQ(info.id, id);
      EXPECT_NEAR(info.normal[2], expected, 1e-9);
      EXPECT_NEAR(info.centre[2], id == 2 ? 0.0 : 20.0, 1e-9);
      EXPECT_NEAR(info.radius, radius, 0.03 * radius);
      EXPECT_GE(info.minInteriorAngle, 20.0);
      interior += static_cast<int>(m.capPoints.size()) - (id == 2 ? 160 : 160);
    }
    EXPECT_EQ(out->GetNumberOfPoints(), frustum->GetNumberOfPoints() + interior);
  }
}

TEST_F(CapQuality, RimOffItsPlaneIsProjected)
{
  // The rim at z = 20 tilted by up to 0.2 (out of a 1.5 radius): projected onto its plane.
  auto frustum = Frustum(3.0, 1.5, 20.0, 80, 20);
  for (vtkIdType i = 0; i < frustum->GetNumberOfPoints(); ++i)
  {
    double p[3];
    frustum->GetPoint(i, p);
    if (p[2] > 19.99)
    {
      p[2] += 0.2 * p[0] / 1.5 + 0.05 * std::sin(5 * std::atan2(p[1], p[0]));
      frustum->GetPoints()->SetPoint(i, p);
    }
  }
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(frustum);
  cap->Update();
  ASSERT_EQ(cap->GetNumberOfCaps(), 2);
  EXPECT_GT(cap->GetCaps()[1].maxRimDistance, 0.04);
  const CapMeasures m = Measure(cap->GetOutput(), 3);
  EXPECT_LE(m.maxPlaneDistance, 1e-6 * 1.5);
  EXPECT_GE(m.minInteriorAngle, 20.0);
  bender::MeshCheckOptions check;
  check.requireClosed = true;
  EXPECT_TRUE(bender::CheckMesh(cap->GetOutput(), nullptr, check).Clean());
}

TEST_F(CapQuality, NamesByPosition)
{
  auto frustum = Frustum(3.0, 1.5, 20.0, 60, 20);
  vtkNew<vtkBenderCapFilter> cap;
  const double nearSmall[3] = { 0.5, 0, 19 }, nearLarge[3] = { 0, 0, -2 };
  cap->AddCapName(nearSmall, "ascending_aorta", true);
  cap->SetInputData(frustum);
  cap->Update();
  auto labels = bender::ReadPatchLabels(cap->GetOutput());
  ASSERT_EQ(labels.size(), 3u);
  // Ids still by area: the large cap is 2 (now an outlet), the small one 3 (the inlet).
  EXPECT_EQ(labels[1].name, "outlet_1");
  EXPECT_EQ(labels[1].type, bender::PatchType::Outlet);
  EXPECT_EQ(labels[2].name, "ascending_aorta");
  EXPECT_EQ(labels[2].type, bender::PatchType::Inlet);

  // Two names on the same cap, an invalid name: one-line errors, empty output.
  cap->AddCapName(nearSmall, "other");
  bendertest::VtkErrorWatch errors(cap);
  cap->Update();
  EXPECT_TRUE(errors.ExpectError("both point at the cap"));
  EXPECT_EQ(cap->GetOutput()->GetNumberOfPoints(), 0);
  cap->ClearCapNames();
  cap->AddCapName(nearLarge, "9lives");
  cap->Update();
  EXPECT_TRUE(errors.ExpectError("invalid cap name '9lives'"));
  cap->ClearCapNames();
  cap->Update();
  EXPECT_TRUE(errors.ExpectNone());
  EXPECT_EQ(cap->GetNumberOfCaps(), 2);
}

TEST_F(CapQuality, ClosedSurfaceIsAllWallOrKeepsItsLabels)
{
  auto frustum = Frustum(3.0, 1.5, 20.0, 40, 10);
  vtkNew<vtkBenderCapFilter> first;
  first->SetInputData(frustum);
  first->Update();
  // Capped again: nothing to cap, the labels stay.
  vtkNew<vtkBenderCapFilter> again;
  again->SetInputData(first->GetOutput());
  again->Update();
  EXPECT_EQ(again->GetNumberOfCaps(), 0);
  EXPECT_EQ(bender::ReadPatchLabels(again->GetOutput()).size(), 3u);
  EXPECT_EQ(bender::CellPatchIds(again->GetOutput()), bender::CellPatchIds(first->GetOutput()));
  // Without labels: all wall.
  vtkNew<vtkPolyData> plain;
  plain->SetPoints(first->GetOutput()->GetPoints());
  plain->SetPolys(first->GetOutput()->GetPolys());
  again->SetInputData(plain);
  again->Update();
  EXPECT_EQ(again->GetNumberOfCaps(), 0);
  const auto labels = bender::ReadPatchLabels(again->GetOutput());
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0].name, "wall");
}

TEST_F(CapQuality, LabelsOfTheInputAreKept)
{
  // Cap a frustum, name its small cap, then remove that cap: the open, labelled surface capped
  // again keeps wall and inlet, and its new cap comes after them.
  auto frustum = Frustum(3.0, 1.5, 20.0, 48, 20);
  vtkNew<vtkBenderCapFilter> first;
  first->SetInputData(frustum);
  first->Update();
  vtkPolyData* closed = first->GetOutput();
  const std::vector<int> ids = bender::CellPatchIds(closed);
  vtkNew<vtkCellArray> kept;
  std::vector<int> keptIds;
  const auto tris = bender::CollectTriangles(closed);
  for (std::size_t t = 0; t < ids.size(); ++t)
  {
    if (ids[t] != 3)
    {
      const vtkIdType tri[3] = { tris[3 * t], tris[3 * t + 1], tris[3 * t + 2] };
      kept->InsertNextCell(3, tri);
      keptIds.push_back(ids[t]);
    }
  }
  vtkNew<vtkPolyData> open;
  open->SetPoints(closed->GetPoints());
  open->SetPolys(kept);
  bender::WritePatchLabels(open,
    keptIds,
    { { 1, "wall", bender::PatchType::Wall }, { 2, "aorta", bender::PatchType::Inlet } });
  vtkNew<vtkBenderCapFilter> again;
  bendertest::VtkErrorWatch errors(again);
  again->SetInputData(open);
  again->Update();
  ASSERT_TRUE(errors.ExpectNone());
  ASSERT_EQ(again->GetNumberOfCaps(), 1);
  EXPECT_EQ(again->GetCaps()[0].id, 3);
  EXPECT_FALSE(again->GetCaps()[0].inlet);
  const auto labels = bender::ReadPatchLabels(again->GetOutput());
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[1].name, "aorta");
  EXPECT_EQ(labels[1].type, bender::PatchType::Inlet);
  EXPECT_EQ(labels[2].name, "outlet_1");
  EXPECT_EQ(labels[2].type, bender::PatchType::Outlet);
  const std::vector<int> after = bender::CellPatchIds(again->GetOutput());
  EXPECT_TRUE(std::equal(keptIds.begin(), keptIds.end(), after.begin())); // input cells first
  bender::MeshCheckOptions check;
  check.requireClosed = true;
  EXPECT_TRUE(bender::CheckMesh(again->GetOutput(), nullptr, check).Clean());
}
