// Degenerate inputs give Ok = false and one line, never a crash, a hang or a one-point line.

#include "VesselCenterlines.h"
#include "VesselMeasures.h"
#include "VesselTestUtilities.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include <gtest/gtest.h>

#include <stdexcept>

using namespace bender;

namespace
{
void ExpectCleanFailure(const CenterlineResult& result)
{
  EXPECT_FALSE(result.ok);
  EXPECT_FALSE(result.message.empty());
  EXPECT_EQ(result.message.find('\n'), std::string::npos);
  ASSERT_NE(result.branches, nullptr);
  EXPECT_EQ(result.branches->GetNumberOfPoints(), 0);
}
} // namespace

TEST(VesselDegenerate, NullSurfaceAndBadOptionsThrow)
{
  EXPECT_THROW(ComputeCenterlines(nullptr), std::invalid_argument);
  vtkNew<vtkPolyData> empty;
  CenterlineOptions options;
  options.step = -1;
  EXPECT_THROW(ComputeCenterlines(empty, options), std::invalid_argument);
  options = {};
  options.seeds = { { { 0, 0, 0 } } };
  EXPECT_THROW(ComputeCenterlines(empty, options), std::invalid_argument);
}

TEST(VesselDegenerate, EmptyAndSingleTriangle)
{
  vtkNew<vtkPolyData> empty;
  ExpectCleanFailure(ComputeCenterlines(empty));
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  vtkNew<vtkCellArray> cells;
  const vtkIdType ids[3] = { 0, 1, 2 };
  cells->InsertNextCell(3, ids);
  vtkNew<vtkPolyData> triangle;
  triangle->SetPoints(points);
  triangle->SetPolys(cells);
  ExpectCleanFailure(ComputeCenterlines(triangle));
}

TEST(VesselDegenerate, FlatSheetHasNoLumen)
{
  const bender::test::Curve line = [](double t) { return Point3{ { t, 0, 0 } }; };
  // A tube squashed to zero radius is a flat, doubled sheet.
  auto sheet = bender::test::SweptTube(line, 0, 10, 11, 8, 1e-12);
  ExpectCleanFailure(ComputeCenterlines(sheet));
}

TEST(VesselDegenerate, SphereIsNotAVessel)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(5.0);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  sphere->Update();
  const CenterlineResult result = ComputeCenterlines(sphere->GetOutput());
  ExpectCleanFailure(result);
  EXPECT_NE(result.message.find("sphere"), std::string::npos) << result.message;
}

TEST(VesselDegenerate, UnreachableOutletIsReportedNotTraced)
{
  // Two separate tubes: the seeds put the inlet in one and an outlet in the other.
  const bender::test::Curve a = [](double t) { return Point3{ { 0, 0, t } }; };
  const bender::test::Curve b = [](double t) { return Point3{ { 20, 0, t } }; };
  auto first = bender::test::SweptTube(a, 0, 20, 41, 32, 2.0);
  auto second = bender::test::SweptTube(b, 0, 20, 41, 32, 2.0);
  vtkNew<vtkPolyData> both;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  for (vtkPolyData* part : { first.GetPointer(), second.GetPointer() })
  {
    const vtkIdType offset = points->GetNumberOfPoints();
    for (vtkIdType i = 0; i < part->GetNumberOfPoints(); ++i)
    {
      points->InsertNextPoint(part->GetPoint(i));
    }
    const vtkIdType* ids = nullptr;
    vtkIdType n = 0;
    part->GetPolys()->InitTraversal();
    while (part->GetPolys()->GetNextCell(n, ids))
    {
      vtkIdType shifted[3] = { ids[0] + offset, ids[1] + offset, ids[2] + offset };
      cells->InsertNextCell(3, shifted);
    }
  }
  both->SetPoints(points);
  both->SetPolys(cells);
  CenterlineOptions options;
  options.seeds = { { { 0, 0, 0 } }, { { 20, 0, 20 } } };
  const CenterlineResult result = ComputeCenterlines(both, options);
  ExpectCleanFailure(result);
  EXPECT_NE(result.message.find("reached"), std::string::npos) << result.message;
  EXPECT_FALSE(result.warnings.empty());
  // With a reachable outlet too, the result keeps the reachable one and warns about the other.
  options.seeds = { { { 0, 0, 0 } }, { { 20, 0, 20 } }, { { 0, 0, 20 } } };
  const CenterlineResult partial = ComputeCenterlines(both, options);
  ASSERT_TRUE(partial.ok) << partial.message;
  EXPECT_EQ(partial.branches->GetNumberOfCells(), 1);
  EXPECT_FALSE(partial.endpoints[1].reached);
  EXPECT_TRUE(partial.endpoints[2].reached);
}

TEST(VesselDegenerate, MeasuresNeedTheRadius)
{
  EXPECT_THROW(MeasureBranches(nullptr), std::invalid_argument);
  vtkNew<vtkPolyData> lines;
  const VesselMeasurements m = MeasureBranches(lines);
  EXPECT_FALSE(m.message.empty());
  EXPECT_TRUE(m.branches.empty());
}

TEST(VesselDegenerate, HoleInTheWallIsNotAnEnd)
{
  const bender::test::Curve line = [](double t) { return Point3{ { 0, 0, t } }; };
  auto tube = bender::test::SweptTube(line, 0, 30, 61, 48, 2.0);
  // Remove two triangles in the middle of the wall: a small, nearly flat hole.
  vtkNew<vtkCellArray> kept;
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType cell = 0;
  tube->GetPolys()->InitTraversal();
  while (tube->GetPolys()->GetNextCell(n, ids))
  {
    if (cell != 30 * 96 + 10 && cell != 30 * 96 + 11)
    {
      kept->InsertNextCell(n, ids);
    }
    ++cell;
  }
  tube->SetPolys(kept);
  const CenterlineResult result = ComputeCenterlines(tube);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.endpoints.size(), 2u);
  EXPECT_EQ(result.branches->GetNumberOfCells(), 1);
  EXPECT_FALSE(result.warnings.empty());
}
