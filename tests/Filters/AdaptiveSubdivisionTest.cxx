// vtkBenderAdaptiveSubdivisionFilter: spec 8 items 26-28, watertight in -> watertight out,
// the paper's Fig. 11 (a plane stretched by a warp), data interpolation and bad input.

#include "vtkBenderAdaptiveSubdivisionFilter.h"
#include "vtkBenderWarpFilter.h"

#include "BenderMeshCheck.h"
#include "RibbonWarp.h"
#include "VtkErrorWatch.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>
#include <vtkTriangleFilter.h>

#include <cmath>
#include <map>

namespace
{
using bender::Vec3;

// A straight wire along x bent by 90 degrees in the xy plane (bell decay).
bender::WarpSpec Bend(double radius)
{
  bender::WarpSpec w;
  w.initial.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.initial.end = { { 10, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.final.start = w.initial.start;
  w.final.end = { { 7, 6, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  w.radius = radius;
  return w;
}

// Fig. 11: the wire lies on a plane and is pulled out of it and stretched.
bender::WarpSpec Stretch()
{
  bender::WarpSpec w;
  w.initial.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.initial.end = { { 10, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.final.start = w.initial.start;
  w.final.end = { { 14, 0, 5 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.radius = 5.0;
  return w;
}

vtkSmartPointer<vtkPolyData>
Plane(double x0, double y0, double x1, double y1, double z, int nx, int ny)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(x0, y0, z);
  plane->SetPoint1(x1, y0, z);
  plane->SetPoint2(x0, y1, z);
  plane->SetResolution(nx, ny);
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(plane->GetOutputPort());
  tri->Update();
  vtkSmartPointer<vtkPolyData> out = tri->GetOutput();
  out->GetPointData()->SetNormals(nullptr);
  out->GetPointData()->SetTCoords(nullptr);
  return out;
}

vtkSmartPointer<vtkPolyData> Sphere(double cx, int resolution)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(cx, 0, 0);
  sphere->SetRadius(2.0);
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  return sphere->GetOutput();
}

vtkSmartPointer<vtkPolyData> Subdivide(vtkPolyData* in,
  const bender::WarpSpec& w,
  double tol,
  int passes,
  vtkBenderAdaptiveSubdivisionFilter* keep = nullptr)
{
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> f;
  vtkBenderAdaptiveSubdivisionFilter* filter = keep ? keep : f.Get();
  filter->SetInputData(in);
  filter->SetWarp(w);
  filter->SetTolerance(tol);
  filter->SetMaxPasses(passes);
  filter->KeepInitialPositionsOn();
  bendertest::VtkErrorWatch errors(filter);
  filter->Update();
  EXPECT_TRUE(errors.ExpectNone());
  EXPECT_EQ(filter->GetLastError(), "");
  vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(filter->GetOutput());
  return out;
}

Vec3 Point(vtkPolyData* pd, vtkIdType i)
{
  double p[3];
  pd->GetPoint(i, p);
  return { p[0], p[1], p[2] };
}

Vec3 Initial(vtkPolyData* pd, vtkIdType i)
{
  double p[3];
  pd->GetPointData()
    ->GetArray(vtkBenderAdaptiveSubdivisionFilter::InitialPositionArrayName())
    ->GetTuple(i, p);
  return { p[0], p[1], p[2] };
}

double Length(const Vec3& v)
{
  return std::sqrt(bender::Dot(v, v));
}

// Largest distance between the piecewise-linear surface and the exact warp of the surface,
// sampled at edge midpoints (and triangle centroids with centroids = true). With
// initial == nullptr the vertices' initial positions are read from the InitialPosition array.
double MaxDeviation(vtkPolyData* warped,
  const bender::RibbonWarp& warp,
  vtkPolyData* initial,
  bool centroids)
{
  const std::vector<std::int64_t> tris = bender::CollectTriangles(warped);
  double worst = 0.0;
  auto x = [&](vtkIdType i) { return initial ? Point(initial, i) : Initial(warped, i); };
  const double samples[4][3] = {
    { 0.5, 0.5, 0 }, { 0, 0.5, 0.5 }, { 0.5, 0, 0.5 }, { 1.0 / 3, 1.0 / 3, 1.0 / 3 }
  };
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    for (const auto& s : samples)
    {
      if (!centroids && s[2] > 0 && s[0] > 0 && s[1] > 0)
      {
        continue;
      }
      Vec3 xs, ys;
      for (int k = 0; k < 3; ++k)
      {
        xs += s[k] * x(tris[t + k]);
        ys += s[k] * Point(warped, tris[t + k]);
      }
      worst = std::max(worst, Length(warp.Apply(xs) - ys));
    }
  }
  return worst;
}

// Edge -> number of incident triangles.
std::map<std::pair<std::int64_t, std::int64_t>, int> EdgeCounts(vtkPolyData* pd)
{
  std::map<std::pair<std::int64_t, std::int64_t>, int> edges;
  const std::vector<std::int64_t> tris = bender::CollectTriangles(pd);
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = tris[t + k], b = tris[t + (k + 1) % 3];
      ++edges[{ std::min(a, b), std::max(a, b) }];
    }
  }
  return edges;
}

class AdaptiveSubdivision : public ::testing::Test
{
protected:
  void SetUp() override { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
};
} // namespace

// Item 26: after every pass a closed manifold stays closed and manifold (every edge has
// exactly 2 triangles: a T-junction would leave boundary edges), and the checker agrees.
TEST_F(AdaptiveSubdivision, ManifoldWatertightAfterEveryPass)
{
  auto sphere = Sphere(5.0, 16);
  const auto before = bender::CheckMesh(sphere);
  ASSERT_TRUE(before.closed);
  vtkIdType previous = sphere->GetNumberOfPolys();
  for (int passes = 1; passes <= 4; ++passes)
  {
    auto out = Subdivide(sphere, Bend(4.0), 1e-3, passes);
    EXPECT_GT(out->GetNumberOfPolys(), previous) << "pass " << passes;
    previous = out->GetNumberOfPolys();
    for (const auto& [edge, count] : EdgeCounts(out))
    {
      ASSERT_EQ(count, 2) << "pass " << passes << " edge " << edge.first << "-" << edge.second;
    }
    const auto report = bender::CheckMesh(out);
    EXPECT_TRUE(report.closed);
    EXPECT_EQ(report.components, 1);
    EXPECT_EQ(report.nonManifoldVertices, 0);
    EXPECT_EQ(report.inconsistentEdges, 0);
    EXPECT_EQ(report.selfIntersections, 0);
  }
}

// Item 27: the triangle count grows by the sum over triangles of their marked edges, counted
// independently here with the exact warp; old vertices keep their warped positions.
TEST_F(AdaptiveSubdivision, TriangleCountGrowsByMarkedEdgesAndOldVerticesStay)
{
  auto sphere = Sphere(5.0, 12);
  const auto spec = Bend(4.0);
  const double tol = 2e-3;
  const bender::RibbonWarp warp(spec);
  const std::vector<std::int64_t> tris = bender::CollectTriangles(sphere);
  vtkIdType sumM = 0;
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Vec3 a = Point(sphere, tris[t + k]), b = Point(sphere, tris[t + (k + 1) % 3]);
      const Vec3 d = warp.Apply((a + b) * 0.5) - (warp.Apply(a) + warp.Apply(b)) * 0.5;
      sumM += Length(d) > tol ? 1 : 0;
    }
  }
  ASSERT_GT(sumM, 0);
  auto out = Subdivide(sphere, spec, tol, 1);
  EXPECT_EQ(out->GetNumberOfPolys(), sphere->GetNumberOfPolys() + sumM);

  vtkNew<vtkBenderWarpFilter> plain;
  plain->SetInputData(sphere);
  plain->SetWarp(spec);
  plain->Update();
  auto deep = Subdivide(sphere, spec, tol, 6);
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    ASSERT_LT(Length(Point(deep, i) - Point(plain->GetOutput(), i)), 1e-12) << i;
    ASSERT_EQ(Length(Initial(deep, i) - Point(sphere, i)), 0.0) << i;
  }
}

// Item 28: inside the plateau of a rigid warp W is affine and nothing is marked; outside the
// plateau (bell decay) W is not affine and edges are marked; the loop terminates.
TEST_F(AdaptiveSubdivision, RigidPlateauMarksNothing)
{
  bender::WarpSpec rigid;
  rigid.initial.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  rigid.initial.end = { { 10, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  // Final = G(initial): rotation by 30 degrees about z, then a shift.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  auto g = [&](const Vec3& p) { return Vec3{ c * p.x - s * p.y + 1, s * p.x + c * p.y + 2, p.z }; };
  auto r = [&](const Vec3& v) { return Vec3{ c * v.x - s * v.y, s * v.x + c * v.y, v.z }; };
  rigid.final.start = { g(rigid.initial.start.position), r({ 1, 0, 0 }), { 0, 0, 1 } };
  rigid.final.end = { g(rigid.initial.end.position), r({ 1, 0, 0 }), { 0, 0, 1 } };
  rigid.radius = 10.0;
  rigid.decay = { bender::DecayShape::Plateau, 0.9 };
  auto plane = Plane(3, -2, 7, 2, 1, 8, 8);

  vtkNew<vtkBenderAdaptiveSubdivisionFilter> filter;
  auto out = Subdivide(plane, rigid, 1e-9, 8, filter);
  EXPECT_EQ(out->GetNumberOfPolys(), plane->GetNumberOfPolys());
  EXPECT_EQ(filter->GetNumberOfPassesRun(), 0);
  EXPECT_TRUE(filter->GetConverged());
  EXPECT_LT(filter->GetLastMaximumDeviation(), 1e-9);
  for (vtkIdType i = 0; i < plane->GetNumberOfPoints(); ++i)
  {
    ASSERT_LT(Length(Point(out, i) - g(Point(plane, i))), 1e-9);
  }

  // The same rigid motion with a bell: W = G^f is not affine, edges get marked.
  rigid.decay = { bender::DecayShape::Bell, 0.5 };
  auto bent = Subdivide(plane, rigid, 1e-3, 8, filter);
  EXPECT_GT(bent->GetNumberOfPolys(), plane->GetNumberOfPolys());
  EXPECT_GT(filter->GetNumberOfPassesRun(), 0);
  EXPECT_LE(filter->GetNumberOfPassesRun(), 8);
}

// Fig. 11: a plane pulled out of itself by the wire. Before subdivision the flat triangles are
// far from the exact warped surface; after, every sampled point is within the tolerance.
TEST_F(AdaptiveSubdivision, Fig11PlaneStretchedFollowsTheExactWarp)
{
  auto plane = Plane(1, -7, 9, 7, 0, 4, 7);
  const auto spec = Stretch();
  const bender::RibbonWarp warp(spec);
  vtkNew<vtkBenderWarpFilter> plain;
  plain->SetInputData(plane);
  plain->SetWarp(spec);
  plain->Update();
  const double tol = 0.01;
  const double before = MaxDeviation(plain->GetOutput(), warp, plane, false);
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> filter;
  auto out = Subdivide(plane, spec, tol, 12, filter);
  const double after = MaxDeviation(out, warp, nullptr, false);
  const double afterCentroids = MaxDeviation(out, warp, nullptr, true);
  EXPECT_TRUE(filter->GetConverged());
  EXPECT_GT(before, 20 * tol);
  // The edge test bounds the deviation at edge midpoints; inside a triangle the piecewise
  // linear surface can be a little farther (the centroid sees the three edges' curvature).
  EXPECT_LT(after, tol);
  EXPECT_LT(afterCentroids, 1.5 * tol);
  std::printf("Fig. 11: %lld -> %lld triangles in %d passes, max deviation at edge midpoints "
              "%.4g -> %.4g, at midpoints and centroids %.4g (tolerance %g)\n",
    static_cast<long long>(plane->GetNumberOfPolys()),
    static_cast<long long>(out->GetNumberOfPolys()),
    filter->GetNumberOfPassesRun(),
    before,
    after,
    afterCentroids,
    tol);
}

// Point data is interpolated linearly at new vertices, normals are dropped, cell data follows
// the input cell; polygons are fanned.
TEST_F(AdaptiveSubdivision, DataInterpolatedAndPolygonsFanned)
{
  vtkNew<vtkPlaneSource> quads;
  quads->SetOrigin(-2, -3, 0);
  quads->SetPoint1(12, -3, 0);
  quads->SetPoint2(-2, 3, 0);
  quads->SetResolution(6, 3);
  quads->Update();
  vtkNew<vtkPolyData> in;
  in->DeepCopy(quads->GetOutput());
  vtkNew<vtkDoubleArray> fx;
  fx->SetName("fx");
  for (vtkIdType i = 0; i < in->GetNumberOfPoints(); ++i)
  {
    fx->InsertNextValue(2 * in->GetPoint(i)[0] - in->GetPoint(i)[1]);
  }
  in->GetPointData()->AddArray(fx);
  vtkNew<vtkIntArray> label;
  label->SetName("label");
  for (vtkIdType c = 0; c < in->GetNumberOfCells(); ++c)
  {
    label->InsertNextValue(static_cast<int>(c % 5));
  }
  in->GetCellData()->AddArray(label);
  ASSERT_NE(in->GetPointData()->GetNormals(), nullptr);

  vtkNew<vtkBenderAdaptiveSubdivisionFilter> filter;
  auto out = Subdivide(in, Bend(4.0), 1e-3, 3, filter);
  EXPECT_GT(out->GetNumberOfPolys(), 2 * in->GetNumberOfPolys());
  EXPECT_EQ(out->GetPointData()->GetNormals(), nullptr);
  auto* ofx = out->GetPointData()->GetArray("fx");
  ASSERT_NE(ofx, nullptr);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const Vec3 x = Initial(out, i);
    ASSERT_NEAR(ofx->GetTuple1(i), 2 * x.x - x.y, 1e-9) << i;
  }
  auto* olabel = out->GetCellData()->GetArray("label");
  ASSERT_NE(olabel, nullptr);
  EXPECT_EQ(olabel->GetNumberOfTuples(), out->GetNumberOfPolys());
  // Every output triangle lies inside the quad its label came from (initial space).
  const std::vector<std::int64_t> tris = bender::CollectTriangles(out);
  std::vector<int> perLabel(5, 0);
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    ++perLabel[static_cast<int>(olabel->GetTuple1(static_cast<vtkIdType>(t / 3)))];
  }
  for (int c : perLabel)
  {
    EXPECT_GE(c, 2);
  }
}

// Boundary edges and a non-manifold fin (three triangles on one edge): no crash, the
// shared edge is split once, and its halves still carry three triangles each.
TEST_F(AdaptiveSubdivision, NonManifoldAndBoundaryInput)
{
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(2, 0, 0);
  pts->InsertNextPoint(8, 0, 0);
  pts->InsertNextPoint(5, 2, 0);
  pts->InsertNextPoint(5, -2, 0);
  pts->InsertNextPoint(5, 0, 2);
  vtkNew<vtkCellArray> polys;
  const vtkIdType t0[3] = { 0, 1, 2 }, t1[3] = { 1, 0, 3 }, t2[3] = { 0, 1, 4 };
  polys->InsertNextCell(3, t0);
  polys->InsertNextCell(3, t1);
  polys->InsertNextCell(3, t2);
  vtkNew<vtkPolyData> fin;
  fin->SetPoints(pts);
  fin->SetPolys(polys);
  auto out = Subdivide(fin, Bend(4.0), 1e-4, 6);
  ASSERT_GT(out->GetNumberOfPolys(), 3);
  int finEdges = 0;
  for (const auto& [edge, count] : EdgeCounts(out))
  {
    EXPECT_LE(count, 3);
    finEdges += count == 3 ? 1 : 0;
  }
  EXPECT_GE(finEdges, 2); // the fin edge was split and both halves stay shared by three
  const auto report = bender::CheckMesh(out);
  EXPECT_EQ(report.nonManifoldEdges, finEdges);
}

TEST_F(AdaptiveSubdivision, EmptyNaNAndBadTolerance)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> filter;
  bendertest::VtkErrorWatch errors(filter);
  filter->SetInputData(empty);
  filter->SetWarp(Bend(4.0));
  filter->Update();
  EXPECT_EQ(filter->GetLastError(), "");
  EXPECT_TRUE(errors.ExpectNone()); // an empty input is not an error
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  auto plane = Plane(0, 0, 1, 1, 0, 2, 2);
  plane->GetPoints()->SetPoint(3, std::nan(""), 0, 0);
  filter->SetInputData(plane);
  filter->Update();
  EXPECT_NE(filter->GetLastError().find("non-finite"), std::string::npos);
  EXPECT_TRUE(errors.ExpectError("non-finite"));
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  filter->SetInputData(Plane(0, 0, 1, 1, 0, 2, 2));
  filter->SetTolerance(0.0);
  filter->Update();
  EXPECT_NE(filter->GetLastError().find("tolerance"), std::string::npos);
  EXPECT_TRUE(errors.ExpectError("tolerance"));

  bender::WarpSpec bad = Bend(4.0);
  bad.radius = -1;
  filter->SetWarp(bad);
  filter->SetTolerance(1e-3);
  filter->Update();
  EXPECT_NE(filter->GetLastError().find("invalid warp"), std::string::npos);
  EXPECT_TRUE(errors.ExpectError("invalid warp"));
}

// The plan form: WarpSpec::subdivision sets tolerance and passes; maxPasses 0 only warps.
TEST_F(AdaptiveSubdivision, PlanSubdivisionObjectAndZeroPasses)
{
  auto sphere = Sphere(5.0, 12);
  bender::WarpSpec spec = Bend(4.0);
  spec.subdivision = bender::SubdivisionSpec{ 0.02, 0 };
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> filter;
  filter->SetInputData(sphere);
  filter->SetWarp(spec);
  EXPECT_EQ(filter->GetTolerance(), 0.02);
  EXPECT_EQ(filter->GetMaxPasses(), 0);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPolys(), sphere->GetNumberOfPolys());
  spec.subdivision->maxPasses = 2;
  filter->SetWarp(spec);
  filter->Update();
  EXPECT_GT(filter->GetOutput()->GetNumberOfPolys(), sphere->GetNumberOfPolys());
  EXPECT_LE(filter->GetNumberOfPassesRun(), 2);
}
