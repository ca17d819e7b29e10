// The gmsh aneurysm (data/external/aneurysm_data.stl: a parent artery with a side branch and a
// saccular aneurysm, three open ends): endpoints, branch graph, the dome not taken for a
// vessel (open and capped), rigid-motion and remeshing (finer, coarser) invariance.

#include "MeshIO.h"
#include "VesselArrayNames.h"
#include "VesselCenterlines.h"
#include "VesselMeasures.h"
#include "VesselTestUtilities.h"
#include "vtkBenderCapFilter.h"

#include <vtkDataArray.h>
#include <vtkLinearSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkQuadricDecimation.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace bender;
using namespace bender::test;

namespace
{
vtkSmartPointer<vtkPolyData> Aneurysm()
{
  return ReadMesh(std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl");
}

double Distance(const Point3& a, const Point3& b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

double MaxRadius(vtkPolyData* lines)
{
  vtkDataArray* r = lines->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius);
  double range[2];
  r->GetRange(range);
  return range[1];
}

// Largest distance from the points of a (outside the balls given) to the lines of b.
double MaxDistanceOutside(vtkPolyData* a,
  vtkPolyData* b,
  const std::vector<Point3>& centres,
  double radius)
{
  vtkNew<vtkPolyData> kept;
  vtkNew<vtkPoints> points;
  for (const auto& p : PointsOf(a))
  {
    bool inBall = false;
    for (const auto& c : centres)
    {
      inBall = inBall || Distance(p, c) < radius;
    }
    if (!inBall)
    {
      points->InsertNextPoint(p.data());
    }
  }
  kept->SetPoints(points);
  return MaxDistanceToLines(kept, b);
}

} // namespace

class AneurysmCenterlines : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    Surface = Aneurysm();
    Result = new CenterlineResult(ComputeCenterlines(Surface));
  }
  static void TearDownTestSuite()
  {
    delete Result;
    Result = nullptr;
    Surface = nullptr;
  }
  static vtkSmartPointer<vtkPolyData> Surface;
  static CenterlineResult* Result;
};
vtkSmartPointer<vtkPolyData> AneurysmCenterlines::Surface;
CenterlineResult* AneurysmCenterlines::Result = nullptr;

TEST_F(AneurysmCenterlines, ThreeOpenEndsOneBifurcationThreeBranches)
{
  ASSERT_TRUE(Result->Ok) << Result->Message;
  ASSERT_EQ(Result->Endpoints.size(), 3u);
  for (const auto& end : Result->Endpoints)
  {
    EXPECT_EQ(end.Kind, EndpointKind::OpenEnd);
    EXPECT_TRUE(end.Reached);
  }
  EXPECT_TRUE(Result->Endpoints[0].Inlet);
  EXPECT_EQ(Result->Bifurcations.size(), 1u);
  EXPECT_EQ(Result->Branches->GetNumberOfCells(), 3);
  EXPECT_EQ(Result->Paths->GetNumberOfCells(), 2);
  const VesselMeasurements m = MeasureBranches(Result->Branches);
  ASSERT_EQ(m.Branches.size(), 3u);
  ASSERT_EQ(m.Bifurcations.size(), 1u);
  EXPECT_EQ(m.Bifurcations[0].ChildBranchIds.size(), 2u);
  for (const auto& b : m.Branches)
  {
    EXPECT_GT(b.Length, 2 * b.MeanRadius);
    EXPECT_GE(b.Tortuosity, 1.0);
    EXPECT_GT(b.MinRadius, 0.0);
  }
}

TEST_F(AneurysmCenterlines, TheDomeIsNotABranch)
{
  ASSERT_TRUE(Result->Ok) << Result->Message;
  // The centerlines stay in the vessels: no inscribed sphere along them is much larger than the
  // largest open end (the dome's would be).
  double largestEnd = 0.0;
  for (const auto& end : Result->Endpoints)
  {
    largestEnd = std::max(largestEnd, end.Radius);
  }
  EXPECT_LT(MaxRadius(Result->Branches), 1.3 * largestEnd);
}

TEST_F(AneurysmCenterlines, CappedSurfaceFindsTheSameThreeEndsAndRejectsTheDome)
{
  ASSERT_TRUE(Result->Ok) << Result->Message;
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(Surface);
  cap->Update();
  ASSERT_EQ(cap->GetNumberOfCaps(), 3);
  const CenterlineResult closed = ComputeCenterlines(cap->GetOutput());
  ASSERT_TRUE(closed.Ok) << closed.Message;
  ASSERT_EQ(closed.Endpoints.size(), 3u) << "the dome must not be taken for a vessel end";
  for (const auto& open : Result->Endpoints)
  {
    double nearest = 1e300;
    for (const auto& tip : closed.Endpoints)
    {
      EXPECT_EQ(tip.Kind, EndpointKind::VoronoiTip);
      nearest = std::min(nearest, Distance(open.Position, tip.Position));
    }
    EXPECT_LT(nearest, 3.0 * open.Radius)
      << "open end at " << open.Position[0] << ", " << open.Position[1] << ", " << open.Position[2];
  }
  EXPECT_EQ(closed.Bifurcations.size(), 1u);
  EXPECT_LT(MaxRadius(closed.Branches), 1.3 * MaxRadius(Result->Branches));
}

TEST_F(AneurysmCenterlines, RigidMotionMovesTheCenterlineWithTheSurface)
{
  ASSERT_TRUE(Result->Ok) << Result->Message;
  vtkNew<vtkTransform> motion;
  motion->Translate(12.0, -7.0, 30.0);
  motion->RotateWXYZ(37.0, 0.3, -0.8, 0.5);
  vtkNew<vtkTransformPolyDataFilter> moveSurface;
  moveSurface->SetInputData(Surface);
  moveSurface->SetTransform(motion);
  moveSurface->Update();
  const CenterlineResult moved = ComputeCenterlines(moveSurface->GetOutput());
  ASSERT_TRUE(moved.Ok) << moved.Message;
  vtkNew<vtkTransformPolyDataFilter> moveLines;
  moveLines->SetInputData(Result->Paths);
  moveLines->SetTransform(motion);
  moveLines->Update();
  double smallest = 1e300, largest = 0.0;
  for (const auto& end : Result->Endpoints)
  {
    smallest = std::min(smallest, end.Radius);
    largest = std::max(largest, end.Radius);
  }
  // Issue 10: the centerline moves with the surface, within 2 % of the radius away from the
  // bifurcation region (the centerline is placed on the centroids of the wall's cross-sections,
  // which do not depend on the Delaunay's tie-breaking): measured 0.0004 mm, 0.01 % (0.006 mm with
  // Qhull's Delaunay).
  EXPECT_LT(
    MaxDistanceOutside(moved.Paths, moveLines->GetOutput(), moved.Bifurcations, 2 * largest),
    0.02 * smallest);
  EXPECT_LT(MaxDistanceToLines(moved.Paths, moveLines->GetOutput()), 0.15 * smallest);
}

TEST_F(AneurysmCenterlines, FinerRemeshingChangesTheCenterlineLittle)
{
  ASSERT_TRUE(Result->Ok) << Result->Message;
  vtkNew<vtkLinearSubdivisionFilter> finer;
  finer->SetInputData(Surface);
  finer->SetNumberOfSubdivisions(1);
  finer->Update();
  const CenterlineResult fine = ComputeCenterlines(finer->GetOutput());
  ASSERT_TRUE(fine.Ok) << fine.Message;
  ASSERT_EQ(fine.Endpoints.size(), 3u);
  double smallest = 1e300, largest = 0.0;
  for (const auto& end : Result->Endpoints)
  {
    smallest = std::min(smallest, end.Radius);
    largest = std::max(largest, end.Radius);
  }
  // Issue 10: a uniform remeshing changes the centerline by less than 2 % of the radius away
  // from the bifurcation region: measured 0.047 mm, 1.6 % of the smallest end radius.
  EXPECT_LT(
    MaxDistanceOutside(fine.Paths, Result->Paths, fine.Bifurcations, 2 * largest), 0.02 * smallest);
  EXPECT_LT(MaxDistanceToLines(fine.Paths, Result->Paths), 0.25 * smallest);
}

TEST_F(AneurysmCenterlines, CoarserRemeshingChangesTheCenterlineLittle)
{
  ASSERT_TRUE(Result->Ok) << Result->Message;
  vtkNew<vtkQuadricDecimation> coarser;
  coarser->SetInputData(Surface);
  coarser->SetTargetReduction(0.5);
  coarser->Update();
  const CenterlineResult coarse = ComputeCenterlines(coarser->GetOutput());
  ASSERT_TRUE(coarse.Ok) << coarse.Message;
  ASSERT_EQ(coarse.Endpoints.size(), 3u);
  double smallest = 1e300, largest = 0.0;
  for (const auto& end : Result->Endpoints)
  {
    smallest = std::min(smallest, end.Radius);
    largest = std::max(largest, end.Radius);
  }
  // Half the triangles (quadric decimation): measured 0.051 mm, 1.7 % of the smallest end radius
  // away from the bifurcation region.
  EXPECT_LT(MaxDistanceOutside(coarse.Paths, Result->Paths, coarse.Bifurcations, 2 * largest),
    0.02 * smallest);
  EXPECT_LT(MaxDistanceToLines(coarse.Paths, Result->Paths), 0.25 * smallest);
}
