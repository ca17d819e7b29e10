// The level of detail while dragging (issue 12, "interactive on big meshes"): a surface above
// the session's threshold is dragged as its decimated copy, the release commits the exact warp
// of the whole surface, the copy follows the surface, small surfaces never use one. The
// threshold is lowered so that the demo vessel subdivided once (81k triangles) counts as big.
#include "BenderSession.h"
#include "DemoPipeline.h"
#include "LogicTestUtilities.h"
#include "MeshIO.h"
#include "WarpPlanIO.h"

#include <vtkLinearSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace
{

using bender::test::MaxDifference;

class LevelOfDetailTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Plan = bender::ReadWarpPlan(bender::DemoPlanPath());
    ASSERT_FALSE(this->Plan.warps.empty());
    this->Vessel = bender::ReadMesh(bender::DemoVesselPath());
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(this->Vessel);
    vtkNew<vtkLinearSubdivisionFilter> subdivide;
    subdivide->SetInputConnection(triangles->GetOutputPort());
    subdivide->SetNumberOfSubdivisions(1);
    subdivide->Update();
    this->Big = subdivide->GetOutput();
    ASSERT_GT(this->Big->GetNumberOfPolys(), 4 * this->Vessel->GetNumberOfPolys() - 10);
  }

  /// A session on `surface` with the plan's parameters, the commit guard off (the guard is
  /// not what is tested) and the threshold `threshold`.
  void Prepare(bender::BenderSession& session, vtkPolyData* surface, long long threshold)
  {
    ASSERT_TRUE(session.SetSurface(surface, "vessel"));
    bender::WarpParameters parameters;
    parameters.radius = this->Warp().radius;
    parameters.decay = this->Warp().decay;
    ASSERT_TRUE(session.SetParameters(parameters));
    session.SetCommitGuard(false);
    session.SetLevelOfDetailThreshold(threshold);
  }

  /// Grab, a few moves towards the plan's final ribbon, the final ribbon.
  void Drag(bender::BenderSession& session)
  {
    ASSERT_TRUE(session.Grab(this->Warp().initial));
    for (double t : { 0.25, 0.5, 0.75 })
    {
      bender::RibbonSpec moved = this->Warp().initial;
      moved.end.position =
        (1 - t) * this->Warp().initial.end.position + t * this->Warp().final.end.position;
      ASSERT_TRUE(session.MoveFinal(moved)) << session.GetLiveProblem();
    }
    ASSERT_TRUE(session.MoveFinal(this->Warp().final)) << session.GetLiveProblem();
  }

  const bender::WarpSpec& Warp() const { return this->Plan.warps.front(); }
  long long Threshold() const { return this->Big->GetNumberOfPolys() / 2; }

  bender::WarpPlan Plan;
  vtkSmartPointer<vtkPolyData> Vessel;
  vtkSmartPointer<vtkPolyData> Big;
};

TEST_F(LevelOfDetailTest, BigSurfaceDragsItsCopyAndReleaseCommitsTheWholeSurfaceExactly)
{
  bender::BenderSession withCopy;
  this->Prepare(withCopy, this->Big, this->Threshold());
  bender::BenderSession whole;
  this->Prepare(whole, this->Big, -1 + (1LL << 62));

  ASSERT_TRUE(withCopy.Grab(this->Warp().initial));
  EXPECT_TRUE(withCopy.IsDraggingProxy());
  // The ghost is then the view's decimated copy of the whole original.
  EXPECT_EQ(withCopy.GetOriginalInPlay(), nullptr);
  EXPECT_EQ(withCopy.GetProxyBuildCount(), 1);
  vtkNew<vtkPolyData> copyAtGrab;
  copyAtGrab->DeepCopy(withCopy.GetProxySurface());
  EXPECT_GT(copyAtGrab->GetNumberOfPolys(), 1000);
  EXPECT_LT(copyAtGrab->GetNumberOfPoints(), this->Big->GetNumberOfPoints() / 2);
  EXPECT_GT(withCopy.GetNumberOfBoundPoints(), 0);
  EXPECT_LT(withCopy.GetNumberOfBoundPoints(), copyAtGrab->GetNumberOfPoints());
  withCopy.CancelGrab("test");

  this->Drag(withCopy);
  this->Drag(whole);
  EXPECT_TRUE(withCopy.IsDraggingProxy());
  EXPECT_FALSE(whole.IsDraggingProxy());
  // The moves warped the copy (its points moved, as many as at the grab) ...
  vtkPolyData* copy = withCopy.GetProxySurface();
  ASSERT_EQ(copy->GetNumberOfPoints(), copyAtGrab->GetNumberOfPoints());
  EXPECT_GT(MaxDifference(copy, copyAtGrab), 1.0);
  // ... and never the whole surface: its filter did not even bind.
  EXPECT_EQ(withCopy.GetLiveFilter()->GetBindingCount(), 0);
  EXPECT_GT(whole.GetLiveFilter()->GetBindingCount(), 0);
  // Asked for, the whole surface's live warp is the one the plain session shows.
  EXPECT_LE(MaxDifference(withCopy.GetDisplaySurface(), whole.GetDisplaySurface()), 1e-9);

  ASSERT_TRUE(withCopy.Release());
  ASSERT_TRUE(whole.Release());
  EXPECT_FALSE(withCopy.IsDraggingProxy());
  ASSERT_EQ(withCopy.GetSurface()->GetNumberOfPoints(), this->Big->GetNumberOfPoints());
  // The committed surface is the exact warp of the whole surface, as without the copy.
  EXPECT_LE(MaxDifference(withCopy.GetSurface(), whole.GetSurface()), 1e-9);
  EXPECT_GT(MaxDifference(withCopy.GetSurface(), this->Big), 1.0);
  EXPECT_EQ(withCopy.GetPlan().warps.size(), 1u);
  // After the release the display shows the committed surface, the copy passes through.
  EXPECT_EQ(withCopy.GetDisplaySurface()->GetPoints(), withCopy.GetSurface()->GetPoints());
}

TEST_F(LevelOfDetailTest, CopyIsRemadeWhenTheSurfaceChanges)
{
  bender::BenderSession session;
  this->Prepare(session, this->Big, this->Threshold());
  EXPECT_EQ(session.GetProxyBuildCount(), 0); // made when first needed
  ASSERT_TRUE(session.Grab(this->Warp().initial));
  EXPECT_EQ(session.GetProxyBuildCount(), 1);
  session.CancelGrab("test");
  ASSERT_TRUE(session.Grab(this->Warp().initial));
  EXPECT_EQ(session.GetProxyBuildCount(), 1); // the same surface: the same copy
  session.CancelGrab("test");

  // The copy lies on the surface it was made of: each of its points is near the surface's box,
  // and the copy of the bent surface differs from the copy of the straight one.
  auto boundsMatch = [&](vtkPolyData* copy, vtkPolyData* surface)
  {
    double a[6], b[6];
    copy->GetBounds(a);
    surface->GetBounds(b);
    double worst = 0.0;
    for (int i = 0; i < 6; ++i)
    {
      worst = std::max(worst, std::abs(a[i] - b[i]));
    }
    return worst;
  };
  vtkNew<vtkPolyData> before;
  before->DeepCopy(session.GetProxySurface());
  EXPECT_LT(boundsMatch(before, session.GetSurface()), 1.0);

  this->Drag(session);
  ASSERT_TRUE(session.Release());
  // The release job made the copy of the bent surface.
  EXPECT_EQ(session.GetProxyBuildCount(), 2);
  vtkPolyData* after = session.GetProxySurface();
  EXPECT_LT(boundsMatch(after, session.GetSurface()), 1.0);
  EXPECT_GT(boundsMatch(after, before), 1.0);
  ASSERT_TRUE(session.Grab(this->Warp().final));
  EXPECT_TRUE(session.IsDraggingProxy());
  EXPECT_EQ(session.GetProxyBuildCount(), 2); // ready
  session.CancelGrab("test");

  // Undo: the straight surface again, its copy made again.
  ASSERT_TRUE(session.Undo());
  ASSERT_TRUE(session.Grab(this->Warp().initial));
  EXPECT_EQ(session.GetProxyBuildCount(), 3);
  EXPECT_LT(boundsMatch(session.GetProxySurface(), session.GetSurface()), 1.0);
  session.CancelGrab("test");

  // A new surface: its own copy.
  vtkNew<vtkPolyData> moved;
  moved->DeepCopy(this->Big);
  for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
  {
    double p[3];
    moved->GetPoint(i, p);
    p[2] += 5.0;
    moved->GetPoints()->SetPoint(i, p);
  }
  ASSERT_TRUE(session.SetSurface(moved, "moved"));
  bender::RibbonSpec lifted = this->Warp().initial;
  lifted.start.position.z += 5.0;
  lifted.end.position.z += 5.0;
  ASSERT_TRUE(session.Grab(lifted));
  EXPECT_EQ(session.GetProxyBuildCount(), 4);
  EXPECT_LT(boundsMatch(session.GetProxySurface(), moved), 1.0);
}

TEST_F(LevelOfDetailTest, NonFiniteBigSurfaceIsRefusedAsWithoutACopy)
{
  vtkNew<vtkPolyData> broken;
  broken->DeepCopy(this->Big);
  broken->GetPoints()->SetPoint(7, std::nan(""), 0.0, 0.0);
  bender::BenderSession session;
  this->Prepare(session, broken, this->Threshold());
  session.ClearMessages();
  EXPECT_FALSE(session.Grab(this->Warp().initial));
  EXPECT_EQ(session.GetState(), bender::GrabState::Idle);
  ASSERT_FALSE(session.GetMessages().empty());
  EXPECT_NE(session.GetMessages().back().text.find("non-finite"), std::string::npos)
    << session.GetMessages().back().text;
  EXPECT_FALSE(session.IsDraggingProxy());
  // The copy of such a surface is the surface itself, never a clustering of NaN.
  EXPECT_EQ(bender::MakeLevelOfDetail(broken)->GetNumberOfPoints(), broken->GetNumberOfPoints());
}

TEST_F(LevelOfDetailTest, SmallSurfacesNeverUseACopy)
{
  bender::BenderSession session;
  // The default threshold (500k triangles): the demo vessel and its subdivision are small.
  const long long defaultThreshold = session.GetLevelOfDetailThreshold();
  EXPECT_EQ(defaultThreshold, 500000);
  this->Prepare(session, this->Big, defaultThreshold);
  this->Drag(session);
  EXPECT_FALSE(session.IsDraggingProxy());
  EXPECT_GT(session.GetLiveFilter()->GetBindingCount(), 0);
  ASSERT_TRUE(session.Release());
  EXPECT_EQ(session.GetProxyBuildCount(), 0);

  // Exactly at the threshold is not above it.
  bender::BenderSession atThreshold;
  this->Prepare(atThreshold, this->Vessel, this->Vessel->GetNumberOfPolys());
  ASSERT_TRUE(atThreshold.Grab(this->Warp().initial));
  EXPECT_FALSE(atThreshold.IsDraggingProxy());
  atThreshold.CancelGrab("test");
  atThreshold.SetLevelOfDetailThreshold(this->Vessel->GetNumberOfPolys() - 1);
  ASSERT_TRUE(atThreshold.Grab(this->Warp().initial));
  EXPECT_TRUE(atThreshold.IsDraggingProxy());
}

} // namespace
