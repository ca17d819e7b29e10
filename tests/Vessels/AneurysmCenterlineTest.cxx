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
  ASSERT_TRUE(Result->ok) << Result->message;
  ASSERT_EQ(Result->endpoints.size(), 3u);
  for (const auto& end : Result->endpoints)
  {
    EXPECT_EQ(end.kind, EndpointKind::OpenEnd);
    EXPECT_TRUE(end.reached);
  }
  EXPECT_TRUE(Result->endpoints[0].inlet);
  EXPECT_EQ(Result->bifurcations.size(), 1u);
  EXPECT_EQ(Result->branches->GetNumberOfCells(), 3);
  EXPECT_EQ(Result->paths->GetNumberOfCells(), 2);
  const VesselMeasurements m = MeasureBranches(Result->branches);
  ASSERT_EQ(m.branches.size(), 3u);
  ASSERT_EQ(m.bifurcations.size(), 1u);
  EXPECT_EQ(m.bifurcations[0].childBranchIds.size(), 2u);
  for (const auto& b : m.branches)
  {
    EXPECT_GT(b.length, 2 * b.meanRadius);
    EXPECT_GE(b.tortuosity, 1.0);
    EXPECT_GT(b.minRadius, 0.0);
  }
}

TEST_F(AneurysmCenterlines, TheDomeIsNotABranch)
{
  ASSERT_TRUE(Result->ok) << Result->message;
  // The centerlines stay in the vessels: no inscribed sphere along them is much larger than the
  // largest open end (the dome's would be).
  double largestEnd = 0.0;
  for (const auto& end : Result->endpoints)
  {
    largestEnd = std::max(largestEnd, end.radius);
  }
  EXPECT_LT(MaxRadius(Result->branches), 1.3 * largestEnd);
}

TEST_F(AneurysmCenterlines, CappedSurfaceFindsTheSameThreeEndsAndRejectsTheDome)
{
  ASSERT_TRUE(Result->ok) << Result->message;
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(Surface);
  cap->Update();
  ASSERT_EQ(cap->GetNumberOfCaps(), 3);
  const CenterlineResult closed = ComputeCenterlines(cap->GetOutput());
  ASSERT_TRUE(closed.ok) << closed.message;
  ASSERT_EQ(closed.endpoints.size(), 3u) << "the dome must not be taken for a vessel end";
  for (const auto& open : Result->endpoints)
  {
    double nearest = 1e300;
    for (const auto& tip : closed.endpoints)
    {
      EXPECT_EQ(tip.kind, EndpointKind::VoronoiTip);
      nearest = std::min(nearest, Distance(open.position, tip.position));
    }
    EXPECT_LT(nearest, 3.0 * open.radius)
      << "open end at " << open.position[0] << ", " << open.position[1] << ", " << open.position[2];
  }
  EXPECT_EQ(closed.bifurcations.size(), 1u);
  EXPECT_LT(MaxRadius(closed.branches), 1.3 * MaxRadius(Result->branches));
}

TEST_F(AneurysmCenterlines, RigidMotionMovesTheCenterlineWithTheSurface)
{
  ASSERT_TRUE(Result->ok) << Result->message;
  vtkNew<vtkTransform> motion;
  motion->Translate(12.0, -7.0, 30.0);
  motion->RotateWXYZ(37.0, 0.3, -0.8, 0.5);
  vtkNew<vtkTransformPolyDataFilter> moveSurface;
  moveSurface->SetInputData(Surface);
  moveSurface->SetTransform(motion);
  moveSurface->Update();
  const CenterlineResult moved = ComputeCenterlines(moveSurface->GetOutput());
  ASSERT_TRUE(moved.ok) << moved.message;
  vtkNew<vtkTransformPolyDataFilter> moveLines;
  moveLines->SetInputData(Result->paths);
  moveLines->SetTransform(motion);
  moveLines->Update();
  double smallest = 1e300, largest = 0.0;
  for (const auto& end : Result->endpoints)
  {
    smallest = std::min(smallest, end.radius);
    largest = std::max(largest, end.radius);
  }
  // Issue 10: the centerline moves with the surface, within 2 % of the radius away from the
  // bifurcation region (the centerline is placed on the centroids of the wall's cross-sections,
  // which do not depend on the Delaunay's tie-breaking): measured 0.0004 mm, 0.01 % (0.006 mm with
  // Qhull's Delaunay).
  EXPECT_LT(
    MaxDistanceOutside(moved.paths, moveLines->GetOutput(), moved.bifurcations, 2 * largest),
    0.02 * smallest);
  EXPECT_LT(MaxDistanceToLines(moved.paths, moveLines->GetOutput()), 0.15 * smallest);
}

TEST_F(AneurysmCenterlines, FinerRemeshingChangesTheCenterlineLittle)
{
  ASSERT_TRUE(Result->ok) << Result->message;
  vtkNew<vtkLinearSubdivisionFilter> finer;
  finer->SetInputData(Surface);
  finer->SetNumberOfSubdivisions(1);
  finer->Update();
  const CenterlineResult fine = ComputeCenterlines(finer->GetOutput());
  ASSERT_TRUE(fine.ok) << fine.message;
  ASSERT_EQ(fine.endpoints.size(), 3u);
  double smallest = 1e300, largest = 0.0;
  for (const auto& end : Result->endpoints)
  {
    smallest = std::min(smallest, end.radius);
    largest = std::max(largest, end.radius);
  }
  // Issue 10: a uniform remeshing changes the centerline by less than 2 % of the radius away
  // from the bifurcation region: measured 0.047 mm, 1.6 % of the smallest end radius.
  EXPECT_LT(
    MaxDistanceOutside(fine.paths, Result->paths, fine.bifurcations, 2 * largest), 0.02 * smallest);
  EXPECT_LT(MaxDistanceToLines(fine.paths, Result->paths), 0.25 * smallest);
}

TEST_F(AneurysmCenterlines, CoarserRemeshingChangesTheCenterlineLittle)
{
  ASSERT_TRUE(Result->ok) << Result->message;
  vtkNew<vtkQuadricDecimation> coarser;
  coarser->SetInputData(Surface);
  coarser->SetTargetReduction(0.5);
  coarser->Update();
  const CenterlineResult coarse = ComputeCenterlines(coarser->GetOutput());
  ASSERT_TRUE(coarse.ok) << coarse.message;
  ASSERT_EQ(coarse.endpoints.size(), 3u);
  double smallest = 1e300, largest = 0.0;
  for (const auto& end : Result->endpoints)
  {
    smallest = std::min(smallest, end.radius);
    largest = std::max(largest, end.radius);
  }
  // Half the triangles (quadric decimation): measured 0.051 mm, 1.7 % of the smallest end radius
  // away from the bifurcation region.
  EXPECT_LT(MaxDistanceOutside(coarse.paths, Result->paths, coarse.bifurcations, 2 * largest),
    0.02 * smallest);
  EXPECT_LT(MaxDistanceToLines(coarse.paths, Result->paths), 0.25 * smallest);
}
