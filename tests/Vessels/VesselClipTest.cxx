// VesselClip: the ends of analytic vessels (an open Y, the same Y closed, a narrow Y whose
// children run side by side, an obliquely cut tube) and of the gmsh aneurysm are cut by planes
// perpendicular to the centerline, leaving one open surface with one planar rim per end and
// the neighbouring vessels whole; bad requests are one-line InputErrors.

#include "VesselClip.h"
#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "MeshIO.h"
#include "VesselArrayNames.h"
#include "VesselCenterlines.h"
#include "VesselTestUtilities.h"
#include "vtkBenderCapFilter.h"

#include <gtest/gtest.h>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>

#include <cmath>

using namespace bender;
using namespace bender::test;

namespace
{
double Dot3(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double Dist(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  const std::array<double, 3> d{ { a[0] - b[0], a[1] - b[1], a[2] - b[2] } };
  return std::sqrt(Dot3(d, d));
}

std::array<double, 3> UnitOf(std::array<double, 3> a)
{
  const double n = std::sqrt(Dot3(a, a));
  return { { a[0] / n, a[1] / n, a[2] / n } };
}

/// Checks what every clip result must satisfy: one open, manifold, consistent component whose
/// boundary loops are exactly the rims, each rim on its plane.
void ExpectCleanOpenResult(const ClipResult& r, std::size_t ends, vtkPolyData* input)
{
  ASSERT_EQ(r.ends.size(), ends);
  const MeshCheckReport report = CheckMesh(r.surface);
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.boundaryLoops.size(), ends);
  EXPECT_EQ(report.nonManifoldEdges, 0);
  EXPECT_EQ(report.nonManifoldVertices, 0);
  EXPECT_EQ(report.inconsistentEdges, 0);
  EXPECT_LE(report.degenerateTriangles, CheckMesh(input).degenerateTriangles);
  for (const ClippedEnd& end : r.ends)
  {
    ASSERT_GE(end.rim.size(), 3u);
    for (long long v : end.rim)
    {
      std::array<double, 3> p;
      r.surface->GetPoint(v, p.data());
      const std::array<double, 3> d{
        { p[0] - end.centre[0], p[1] - end.centre[1], p[2] - end.centre[2] }
      };
      EXPECT_LE(std::abs(Dot3(d, end.normal)), 1e-9 * end.radius);
    }
    EXPECT_GT(end.radius, 0.5 * end.inscribedRadius);
    EXPECT_LT(Dist(end.centre, end.centerlineEnd), end.distance + end.radius);
  }
}

struct Y
{
  vtkSmartPointer<vtkPolyData> surface;
  std::array<double, 3> axis[3]; // unit directions outwards: trunk, left, right
};

Y MakeY(double halfAngleDegrees, double rt, double rc)
{
  const double a = halfAngleDegrees * M_PI / 180.0;
  const Point3 o{ { 0, 0, 0 } };
  const Point3 left{ { -40 * std::sin(a), 0, 40 * std::cos(a) } };
  const Point3 right{ { 40 * std::sin(a), 0, 40 * std::cos(a) } };
  const std::vector<Segment> tubes = {
    { { { 0, 0, -40 } }, o, rt }, { o, left, rc }, { o, right, rc }
  };
  const double bounds[6] = { -25, 25, -4.5, 4.5, -25, 25 };
  Y y;
  y.surface = ImplicitTubes(tubes, bounds, 0.4);
  y.axis[0] = { { 0, 0, -1 } };
  y.axis[1] = { { -std::sin(a), 0, std::cos(a) } };
  y.axis[2] = { { std::sin(a), 0, std::cos(a) } };
  return y;
}

/// The axis (of three) an end's normal is closest to; the angle in degrees.
int NearestAxis(const Y& y, const ClippedEnd& end, double& degrees)
{
  int best = 0;
  for (int k = 1; k < 3; ++k)
  {
    if (Dot3(end.normal, y.axis[k]) > Dot3(end.normal, y.axis[best]))
    {
      best = k;
    }
  }
  degrees = std::acos(std::min(1.0, Dot3(end.normal, y.axis[best]))) * 180.0 / M_PI;
  return best;
}

/// The Y of 35 degrees and its centerlines, computed once.
const Y& Y35()
{
  static const Y y = MakeY(35.0, 3.0, 2.4);
  return y;
}
const CenterlineResult& Y35Centerlines()
{
  static const CenterlineResult cl = ComputeCenterlines(Y35().surface);
  return cl;
}

/// A tube of radius 3 along z (open at z = +-20) with a side branch 1.2 mm wide along +x, open
/// at x = 20; computed once.
vtkPolyData* ThinBranch()
{
  // Radii off the grid's nodes: no iso-surface vertex lands twice on one node.
  static const vtkSmartPointer<vtkPolyData> surface = []
  {
    const std::vector<Segment> tubes = { { { { 0, 0, -40 } }, { { 0, 0, 40 } }, 3.013 },
      { { { 0, 0, 0 } }, { { 40, 0, 0 } }, 0.6013 } };
    const double bounds[6] = { -5, 20, -4.2, 4.2, -20, 20 };
    return ImplicitTubes(tubes, bounds, 0.2);
  }();
  return surface;
}

class VesselClipTest : public ::testing::Test
{
protected:
  void SetUp() override { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
};
} // namespace

TEST_F(VesselClipTest, OpenYEndsArePerpendicularToTheAxes)
{
  const Y& y = Y35();
  const CenterlineResult& cl = Y35Centerlines();
  ASSERT_TRUE(cl.ok) << cl.message;
  ASSERT_EQ(FindCenterlineEnds(cl.paths).size(), 3u);
  ASSERT_EQ(FindCenterlineEnds(cl.branches).size(), 3u); // the bifurcation is not an end
  const ClipResult r = ClipVesselEnds(y.surface, cl.paths);
  ExpectCleanOpenResult(r, 3, y.surface);
  bool seen[3] = { false, false, false };
  for (const ClippedEnd& end : r.ends)
  {
    double degrees = 0;
    const int axis = NearestAxis(y, end, degrees);
    seen[axis] = true;
    EXPECT_LT(degrees, 2.0) << "end at " << end.centre[0] << " " << end.centre[2];
    EXPECT_NEAR(end.radius, axis == 0 ? 3.0 : 2.4, 0.1);
    EXPECT_GE(end.distance, end.inscribedRadius * 0.99); // at least one radius inside
    // The cut is at least a radius inside the old open end (measured along the axis).
    EXPECT_LT(
      std::abs(end.centre[2]), 25.0 - 0.9 * end.inscribedRadius * std::abs(y.axis[axis][2]));
  }
  EXPECT_TRUE(seen[0] && seen[1] && seen[2]);
}

TEST_F(VesselClipTest, EndPathsGiveThePlanesTheClipCutsBy)
{
  // The application slides each end's clip plane along FindCenterlineEndPaths' path and asks
  // for the cut at that arc length: ClipVesselEnds must cut exactly on ClipPlaneAt's plane.
  const Y& y = Y35();
  const CenterlineResult& cl = Y35Centerlines();
  ASSERT_TRUE(cl.ok) << cl.message;
  const std::vector<CenterlineEndPath> paths = FindCenterlineEndPaths(cl.paths);
  const std::vector<CenterlineEnd> ends = FindCenterlineEnds(cl.paths);
  ASSERT_EQ(paths.size(), 3u);
  const ClipResult defaults = ClipVesselEnds(y.surface, cl.paths);
  ASSERT_EQ(defaults.ends.size(), 3u);
  for (std::size_t k = 0; k < paths.size(); ++k)
  {
    const CenterlineEndPath& path = paths[k];
    EXPECT_EQ(path.position, ends[k].position);
    ASSERT_GE(path.points.size(), 2u);
    ASSERT_EQ(path.arcLengths.size(), path.points.size());
    EXPECT_EQ(path.points.front(), path.position);
    for (std::size_t i = 1; i < path.arcLengths.size(); ++i)
    {
      EXPECT_NEAR(path.arcLengths[i] - path.arcLengths[i - 1],
        Dist(path.points[i], path.points[i - 1]),
        1e-9);
    }
    EXPECT_NEAR(path.maximumDistance, 0.5 * path.arcLengths.back(), 1e-9);
    // The default: at least a radius in, where the default clip cut (the open Y's first try
    // succeeds).
    EXPECT_GT(path.defaultDistance, 0.9 * path.radius);
    EXPECT_NEAR(defaults.ends[k].distance, path.defaultDistance, 1e-9);

    // A cut 3 mm deeper than the default, requested by the end and the distance.
    const double d = path.defaultDistance + 3.0;
    ASSERT_LT(d, path.maximumDistance);
    const ClipPlane plane = ClipPlaneAt(path, d);
    EXPECT_NEAR(NearestDistanceOnPath(path, plane.centre), d, 1e-6);
    EXPECT_NEAR(Dot3(plane.normal, plane.normal), 1.0, 1e-12);
    // Outwards: towards the end.
    EXPECT_GT(Dot3(plane.normal,
                { { path.position[0] - plane.centre[0],
                  path.position[1] - plane.centre[1],
                  path.position[2] - plane.centre[2] } }),
      0.0);
    ClipOptions options;
    options.ends.push_back({ path.position, d });
    const ClipResult r = ClipVesselEnds(y.surface, cl.paths, options);
    ExpectCleanOpenResult(r, 3, y.surface);
    const ClippedEnd& end = r.ends[k];
    EXPECT_TRUE(end.userChosen);
    EXPECT_NEAR(end.distance, d, 1e-12);
    EXPECT_GT(Dot3(end.normal, plane.normal), 1.0 - 1e-9);
    EXPECT_NEAR(end.inscribedRadius, plane.radius, 1e-12);
    for (long long v : end.rim)
    {
      std::array<double, 3> p;
      r.surface->GetPoint(v, p.data());
      EXPECT_LE(std::abs(Dot3(
                  { { p[0] - plane.centre[0], p[1] - plane.centre[1], p[2] - plane.centre[2] } },
                  plane.normal)),
        1e-9 * plane.radius);
    }
    // The rim is centred on the centerline (the tubes are round) and 3 mm deeper than the
    // default's.
    EXPECT_LT(Dist(end.centre, plane.centre), 0.1 * plane.radius);
    EXPECT_NEAR(Dist(end.centre, defaults.ends[k].centre), 3.0, 0.1 * plane.radius);
  }
  // Clamped to the path.
  const ClipPlane before = ClipPlaneAt(paths[0], -5.0);
  EXPECT_EQ(before.centre, paths[0].position);
  // The far end of the path is beyond the range: the nearest allowed point is its limit.
  EXPECT_NEAR(
    NearestDistanceOnPath(paths[0], paths[0].points.back()), paths[0].maximumDistance, 1e-9);
}

TEST_F(VesselClipTest, ClosedYIsOpenedAtItsThreeEnds)
{
  const Y& y = Y35();
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(y.surface);
  cap->Update();
  ASSERT_TRUE(CheckMesh(cap->GetOutput()).closed);
  vtkSmartPointer<vtkPolyData> closed = cap->GetOutput();
  const CenterlineResult cl = ComputeCenterlines(closed);
  ASSERT_TRUE(cl.ok) << cl.message;
  const ClipResult r = ClipVesselEnds(closed, cl.branches);
  ExpectCleanOpenResult(r, 3, closed);
  for (const ClippedEnd& end : r.ends)
  {
    // The centerline of a closed surface runs a few degrees off the axis near an oblique flat
    // end (it veers towards the end's corner); the cut follows the centerline (5 degrees: 4.8
    // measured), where the open Y's is within 2 degrees of the axis.
    double degrees = 0;
    NearestAxis(y, end, degrees);
    EXPECT_LT(degrees, 6.0);
    // The flat caps (z = -25, z = 25) are gone: the whole rim is inside the box.
    for (long long v : end.rim)
    {
      std::array<double, 3> p;
      r.surface->GetPoint(v, p.data());
      EXPECT_LT(std::abs(p[2]), 24.9);
    }
  }
}

TEST_F(VesselClipTest, NeighbourRunningAlongsideIsNotCut)
{
  // Children 2 x 8 degrees apart: near their ends the gap between them is about one radius,
  // so each end's plane, extended, crosses the other child.
  const Y y = MakeY(8.0, 3.0, 2.0);
  const CenterlineResult cl = ComputeCenterlines(y.surface);
  ASSERT_TRUE(cl.ok) << cl.message;
  ClipOptions options;
  // Cut the left child deep, 8 mm from its end (where the children are 2.2 mm apart).
  const double z = 25.0;
  options.ends.push_back({ { { -z * std::tan(8.0 * M_PI / 180.0), 0, z } }, 8.0 });
  const ClipResult r = ClipVesselEnds(y.surface, cl.paths, options);
  ExpectCleanOpenResult(r, 3, y.surface);
  // The right child keeps its length: its points reach near its own default cut.
  double leftReach = 0, rightReach = 0;
  for (vtkIdType i = 0; i < r.surface->GetNumberOfPoints(); ++i)
  {
    std::array<double, 3> p;
    r.surface->GetPoint(i, p.data());
    if (p[0] < -0.5)
    {
      leftReach = std::max(leftReach, Dot3(p, y.axis[1]));
    }
    else if (p[0] > 0.5)
    {
      rightReach = std::max(rightReach, Dot3(p, y.axis[2]));
    }
  }
  int user = 0;
  for (const ClippedEnd& end : r.ends)
  {
    user += end.userChosen ? 1 : 0;
    if (end.userChosen)
    {
      EXPECT_NEAR(end.distance, 8.0, 1e-9);
    }
  }
  EXPECT_EQ(user, 1);
  EXPECT_LT(leftReach, rightReach - 4.0) << leftReach << " " << rightReach;
}

TEST_F(VesselClipTest, ObliqueOpenEndIsRecutPerpendicular)
{
  // A straight tube along z whose top end is cut at 30 degrees.
  auto tube = SweptTube([](double t) { return Point3{ { 0, 0, t } }; }, 0.0, 30.0, 121, 48, 2.0);
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    double p[3];
    tube->GetPoint(i, p);
    if (p[2] > 29.99)
    {
      p[2] += std::tan(30.0 * M_PI / 180.0) * p[0];
      tube->GetPoints()->SetPoint(i, p);
    }
  }
  const CenterlineResult cl = ComputeCenterlines(tube);
  ASSERT_TRUE(cl.ok) << cl.message;
  const ClipResult r = ClipVesselEnds(tube, cl.paths);
  ExpectCleanOpenResult(r, 2, tube);
  for (const ClippedEnd& end : r.ends)
  {
    EXPECT_GT(std::abs(end.normal[2]), std::cos(1.0 * M_PI / 180.0));
    EXPECT_NEAR(end.radius, 2.0, 0.05);
    if (end.normal[2] > 0)
    {
      EXPECT_LT(end.centre[2], 30.0 - 2.0 * std::tan(30.0 * M_PI / 180.0)); // below the slant
    }
  }
}

TEST_F(VesselClipTest, AneurysmThreeEndsPerpendicularDomeWhole)
{
  auto surface = ReadMesh(std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl");
  const CenterlineResult cl = ComputeCenterlines(surface);
  ASSERT_TRUE(cl.ok) << cl.message;
  const ClipResult r = ClipVesselEnds(surface, cl.paths);
  ExpectCleanOpenResult(r, 3, surface);
  vtkDataArray* tangent = cl.branches->GetPointData()->GetArray(VesselArrays::FrenetTangent);
  ASSERT_NE(tangent, nullptr);
  for (const ClippedEnd& end : r.ends)
  {
    // The tangent of the nearest centerline point.
    vtkIdType nearest = 0;
    double best = 1e300;
    for (vtkIdType i = 0; i < cl.branches->GetNumberOfPoints(); ++i)
    {
      std::array<double, 3> p;
      cl.branches->GetPoint(i, p.data());
      if (Dist(p, end.centre) < best)
      {
        best = Dist(p, end.centre);
        nearest = i;
      }
    }
    std::array<double, 3> t;
    tangent->GetTuple(nearest, t.data());
    t = UnitOf(t);
    const double degrees = std::acos(std::min(1.0, std::abs(Dot3(t, end.normal)))) * 180 / M_PI;
    EXPECT_LT(degrees, 5.0);
    EXPECT_LT(best, 0.25 * end.radius); // the rim is centred on the centerline
  }
  // Only the three end pieces are removed: most of the area is kept, the dome included.
  const double before = CheckMesh(surface).area;
  const double after = CheckMesh(r.surface).area;
  EXPECT_GT(after, 0.6 * before);
  EXPECT_LT(after, before);
}

TEST_F(VesselClipTest, BadRequestsAreOneLineErrors)
{
  const Y& y = Y35();
  const CenterlineResult& cl = Y35Centerlines();
  ASSERT_TRUE(cl.ok) << cl.message;
  ClipOptions far;
  far.ends.push_back({ { { 100, 100, 100 } }, -1.0 });
  try
  {
    ClipVesselEnds(y.surface, cl.paths, far);
    ADD_FAILURE() << "no exception";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("is not on a vessel"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  ClipOptions tooDeep;
  tooDeep.ends.push_back({ { { 0, 0, -25 } }, 500.0 });
  EXPECT_THROW(ClipVesselEnds(y.surface, cl.paths, tooDeep), InputError);
  vtkNew<vtkPolyData> empty;
  EXPECT_THROW(ClipVesselEnds(empty, cl.paths), InputError);
  vtkNew<vtkPolyData> noRadius;
  noRadius->DeepCopy(cl.paths);
  noRadius->GetPointData()->RemoveArray(VesselArrays::MaximumInscribedSphereRadius);
  try
  {
    ClipVesselEnds(y.surface, noRadius);
    ADD_FAILURE() << "no exception";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("MaximumInscribedSphereRadius"), std::string::npos);
  }
}

TEST_F(VesselClipTest, ThinBranchOfAClosedVesselIsClipped)
{
  // Its inscribed radius (0.6) is a fifth of the trunk's: once taken for a spike of the Voronoi
  // diagram, the branch was left closed and the clipped vessel had two ends, not three.
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(ThinBranch());
  cap->Update();
  vtkPolyData* closed = cap->GetOutput();
  ASSERT_TRUE(CheckMesh(closed).closed);
  const CenterlineResult cl = ComputeCenterlines(closed);
  ASSERT_TRUE(cl.ok) << cl.message;
  const ClipResult r = ClipVesselEnds(closed, cl.paths);
  ExpectCleanOpenResult(r, 3, closed);
  EXPECT_TRUE(r.unclipped.empty());
  int thin = 0;
  for (const ClippedEnd& end : r.ends)
  {
    if (end.radius < 1.0)
    {
      ++thin;
      EXPECT_NEAR(end.radius, 0.6, 0.1);
      EXPECT_GT(end.normal[0], std::cos(5.0 * M_PI / 180.0));
      EXPECT_GT(end.centre[0], 10.0);
    }
  }
  EXPECT_EQ(thin, 1);
}

TEST_F(VesselClipTest, EndsTheCenterlinesMissAreReportedAndNeverReCutElsewhere)
{
  // Centerlines of the trunk only: the branch's open end is left as it was and reported.
  CenterlineOptions trunk;
  trunk.seeds = { { { 0, 0, -20 } }, { { 0, 0, 20 } } };
  const CenterlineResult cl = ComputeCenterlines(ThinBranch(), trunk);
  ASSERT_TRUE(cl.ok) << cl.message;
  const ClipResult r = ClipVesselEnds(ThinBranch(), cl.paths);
  ASSERT_EQ(r.ends.size(), 2u);
  ASSERT_EQ(r.unclipped.size(), 1u);
  EXPECT_NEAR(r.unclipped[0].centre[0], 20.0, 0.01);
  EXPECT_NEAR(r.unclipped[0].radius, 0.6, 0.1);
  EXPECT_EQ(CheckMesh(r.surface).boundaryLoops.size(), 3u);
  // A cut asked at the branch's tip: the nearest end is the trunk's, 28 mm away, whose wall
  // is 16.5 mm from the point. Refused, not a cut of the trunk.
  ClipOptions atTip;
  atTip.ends.push_back({ { { 19.5, 0, 0 } }, 3.0 });
  try
  {
    ClipVesselEnds(ThinBranch(), cl.paths, atTip);
    ADD_FAILURE() << "no exception";
  }
  catch (const InputError& e)
  {
    const std::string what = e.what();
    const std::size_t at = what.find(" mm from the vessel of the nearest end");
    ASSERT_NE(at, std::string::npos) << what;
    // 19.5 mm from its centerline, 16.5 from its wall.
    EXPECT_NEAR(std::stod(what.substr(what.rfind(" is ", at) + 4)), 16.5, 0.3) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  // On the trunk, near its end: cut there.
  ClipOptions onTrunk;
  onTrunk.ends.push_back({ { { 1.0, 0, 18 } }, 4.0 });
  const ClipResult cut = ClipVesselEnds(ThinBranch(), cl.paths, onTrunk);
  int user = 0;
  for (const ClippedEnd& end : cut.ends)
  {
    if (end.userChosen)
    {
      ++user;
      EXPECT_NEAR(end.distance, 4.0, 1e-9);
      EXPECT_GT(end.centerlineEnd[2], 0.0);
    }
  }
  EXPECT_EQ(user, 1);
}
