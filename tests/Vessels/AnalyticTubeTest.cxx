// Centerlines of tubes with known axes: straight, a torus section, a helix (swept circles)
// and a Y bifurcation (iso-surface of three tubes), with the tolerances: axis within
// 2 % of the radius, radius within 3 %, helix curvature and torsion within 5 %, tortuosity and
// bend angle within 1 %.

#include "VesselArrayNames.h"
#include "VesselCenterlines.h"
#include "VesselMeasures.h"
#include "VesselTestUtilities.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace bender;
using namespace bender::test;

namespace
{
const double Pi = 3.14159265358979323846;

struct AxisErrors
{
  double maxAxisDistance = 0;
  double maxRadiusError = 0;
  int points = 0;
};

// Distances of the centerline points to the true axis and radius errors, skipping points
// closer than `skip` to any of the `excluded` points.
AxisErrors CompareWithAxis(vtkPolyData* lines,
  const std::vector<std::vector<Point3>>& axes,
  const std::vector<double>& radii,
  const std::vector<Point3>& excluded = {},
  double skip = 0)
{
  AxisErrors e;
  vtkDataArray* radius =
    lines->GetPointData()->GetArray(VesselArrays::MaximumInscribedSphereRadius);
  EXPECT_NE(radius, nullptr);
  if (!radius)
  {
    return e;
  }
  const auto points = PointsOf(lines);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    bool skipped = false;
    for (const auto& x : excluded)
    {
      const double d = std::sqrt((points[i][0] - x[0]) * (points[i][0] - x[0]) +
        (points[i][1] - x[1]) * (points[i][1] - x[1]) +
        (points[i][2] - x[2]) * (points[i][2] - x[2]));
      skipped = skipped || d < skip;
    }
    if (skipped)
    {
      continue;
    }
    std::size_t nearest = 0;
    double best = 1e300;
    for (std::size_t a = 0; a < axes.size(); ++a)
    {
      const double d = DistanceToPolyline(points[i], axes[a]);
      if (d < best)
      {
        best = d;
        nearest = a;
      }
    }
    e.maxAxisDistance = std::max(e.maxAxisDistance, best / radii[nearest]);
    e.maxRadiusError = std::max(e.maxRadiusError,
      std::abs(radius->GetComponent(static_cast<vtkIdType>(i), 0) - radii[nearest]) /
        radii[nearest]);
    ++e.points;
  }
  return e;
}

} // namespace

TEST(AnalyticTube, StraightTubeAxisRadiusAndTortuosity)
{
  const double R = 2.0;
  const Curve axis = [](double t) { return Point3{ { 0.3 * t, -0.2 * t, t } }; };
  auto surface = SweptTube(axis, 0.0, 40.0, 81, 64, R);
  const CenterlineResult result = ComputeCenterlines(surface);
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.endpoints.size(), 2u);
  EXPECT_EQ(result.branches->GetNumberOfCells(), 1);
  EXPECT_TRUE(result.bifurcations.empty());
  const AxisErrors e = CompareWithAxis(result.branches, { SampleCurve(axis, 0, 40, 2) }, { R });
  EXPECT_GT(e.points, 100);
  EXPECT_LT(e.maxAxisDistance, 0.02);
  EXPECT_LT(e.maxRadiusError, 0.03);
  const VesselMeasurements m = MeasureBranches(result.branches);
  ASSERT_EQ(m.branches.size(), 1u);
  const double trueLength = 40.0 * std::sqrt(1 + 0.09 + 0.04);
  EXPECT_NEAR(m.branches[0].length, trueLength, 0.01 * trueLength);
  EXPECT_NEAR(m.branches[0].tortuosity, 1.0, 0.01);
  EXPECT_LT(m.branches[0].bendAngle, 1.0);
  EXPECT_LT(m.branches[0].maxCurvature, 0.02 / R);
}

TEST(AnalyticTube, TorusSectionBendAngleAndTortuosity)
{
  const double R = 3.0, rho = 20.0;
  const Curve axis = [rho](double t) {
    return Point3{ { rho * std::cos(t), rho * std::sin(t), 0 } };
  };
  auto surface = SweptTube(axis, 0.0, Pi / 2, 121, 64, R);
  const CenterlineResult result = ComputeCenterlines(surface);
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.branches->GetNumberOfCells(), 1);
  const AxisErrors e =
    CompareWithAxis(result.branches, { SampleCurve(axis, 0, Pi / 2, 4000) }, { R });
  EXPECT_LT(e.maxAxisDistance, 0.02);
  EXPECT_LT(e.maxRadiusError, 0.03);
  const VesselMeasurements m = MeasureBranches(result.branches);
  ASSERT_EQ(m.branches.size(), 1u);
  const double tortuosity = (rho * Pi / 2) / (rho * std::sqrt(2.0));
  EXPECT_NEAR(m.branches[0].tortuosity, tortuosity, 0.01 * tortuosity);
  EXPECT_NEAR(m.branches[0].bendAngle, 90.0, 0.9);
  EXPECT_NEAR(m.branches[0].meanCurvature, 1.0 / rho, 0.05 / rho);
}

TEST(AnalyticTube, HelixCurvatureAndTorsion)
{
  const double R = 2.0, a = 10.0, b = 4.0;
  const Curve axis = [a, b](double t) {
    return Point3{ { a * std::cos(t), a * std::sin(t), b * t } };
  };
  auto surface = SweptTube(axis, 0.0, 2 * Pi, 241, 64, R);
  const CenterlineResult result = ComputeCenterlines(surface);
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.branches->GetNumberOfCells(), 1);
  const AxisErrors e =
    CompareWithAxis(result.branches, { SampleCurve(axis, 0, 2 * Pi, 8000) }, { R });
  EXPECT_LT(e.maxAxisDistance, 0.02);
  EXPECT_LT(e.maxRadiusError, 0.03);
  const double kappa = a / (a * a + b * b), tau = b / (a * a + b * b);
  vtkDataArray* k = result.branches->GetPointData()->GetArray(VesselArrays::Curvature);
  vtkDataArray* t = result.branches->GetPointData()->GetArray(VesselArrays::Torsion);
  vtkDataArray* s = result.branches->GetPointData()->GetArray(VesselArrays::Abscissa);
  ASSERT_TRUE(k && t && s);
  const double length = s->GetComponent(s->GetNumberOfTuples() - 1, 0);
  EXPECT_NEAR(length, 2 * Pi * std::sqrt(a * a + b * b), 0.01 * 2 * Pi * std::sqrt(a * a + b * b));
  int checked = 0;
  double worstK = 0, worstT = 0;
  for (vtkIdType i = 0; i < k->GetNumberOfTuples(); ++i)
  {
    // Away from the open ends, where the fits are one-sided.
    const double si = s->GetComponent(i, 0);
    if (si < 2 * R || si > length - 2 * R)
    {
      continue;
    }
    worstK = std::max(worstK, std::abs(k->GetComponent(i, 0) - kappa) / kappa);
    worstT = std::max(worstT, std::abs(t->GetComponent(i, 0) - tau) / tau);
    ++checked;
  }
  EXPECT_GT(checked, 100);
  EXPECT_LT(worstK, 0.05);
  EXPECT_LT(worstT, 0.05);
}

TEST(AnalyticTube, YBifurcationBranchesAndAxes)
{
  const double Rt = 3.0, Rc = 2.4;
  const double angle = 35.0 * Pi / 180.0;
  const Point3 o{ { 0, 0, 0 } };
  const Point3 left{ { -40 * std::sin(angle), 0, 40 * std::cos(angle) } };
  const Point3 right{ { 40 * std::sin(angle), 0, 40 * std::cos(angle) } };
  const std::vector<Segment> tubes = {
    { { { 0, 0, -40 } }, o, Rt }, { o, left, Rc }, { o, right, Rc }
  };
  const double bounds[6] = { -25, 25, -4.5, 4.5, -25, 25 };
  auto surface = ImplicitTubes(tubes, bounds, 0.25);
  const CenterlineResult result = ComputeCenterlines(surface);
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.endpoints.size(), 3u);
  EXPECT_TRUE(result.endpoints[0].inlet);
  EXPECT_LT(result.endpoints[0].position[2], -20.0) << "the trunk, the largest end, is the inlet";
  ASSERT_EQ(result.bifurcations.size(), 1u);
  ASSERT_EQ(result.branches->GetNumberOfCells(), 3);
  // Axes, away from the bifurcation region (two trunk radii).
  const AxisErrors e = CompareWithAxis(result.branches,
    { { { { 0, 0, -40 } }, o }, { o, left }, { o, right } },
    { Rt, Rc, Rc },
    { o },
    2.5 * Rt);
  EXPECT_GT(e.points, 300);
  EXPECT_LT(e.maxAxisDistance, 0.02);
  EXPECT_LT(e.maxRadiusError, 0.03);
  const VesselMeasurements m = MeasureBranches(result.branches);
  ASSERT_EQ(m.bifurcations.size(), 1u);
  EXPECT_EQ(m.bifurcations[0].childBranchIds.size(), 2u);
  EXPECT_NEAR(m.bifurcations[0].childrenAngle, 70.0, 5.0);
  // The children are straight from where they separate; the trunk's branch includes the
  // bifurcation region, where the path to its first outlet starts to turn.
  for (const auto& b : m.branches)
  {
    if (b.parentBranchId >= 0)
    {
      EXPECT_NEAR(b.tortuosity, 1.0, 0.01) << "branch " << b.branchId;
    }
  }
}

TEST(AnalyticTube, RemeshingChangesTheCenterlineByLessThanTwoPercentOfTheRadius)
{
  const double R = 3.0, rho = 20.0;
  const Curve axis = [rho](double t) {
    return Point3{ { rho * std::cos(t), rho * std::sin(t), 0 } };
  };
  const CenterlineResult coarse = ComputeCenterlines(SweptTube(axis, 0.0, Pi / 2, 61, 40, R));
  const CenterlineResult fine = ComputeCenterlines(SweptTube(axis, 0.0, Pi / 2, 181, 96, R));
  ASSERT_TRUE(coarse.ok && fine.ok);
  EXPECT_LT(MaxDistanceToLines(coarse.branches, fine.branches), 0.02 * R);
  EXPECT_LT(MaxDistanceToLines(fine.branches, coarse.branches), 0.02 * R);
}

TEST(AnalyticTube, SeedsChooseTheEnds)
{
  const double R = 2.0;
  const Curve axis = [](double t) { return Point3{ { 0, 0, t } }; };
  auto surface = SweptTube(axis, 0.0, 30.0, 61, 48, R);
  CenterlineOptions options;
  // Outlet first: the seeds reverse the direction; the second seed is inside the tube.
  options.seeds = { { { 0.5, 0, 30 } }, { { 0, 0, 10 } } };
  const CenterlineResult result = ComputeCenterlines(surface, options);
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.endpoints.size(), 2u);
  EXPECT_NEAR(result.endpoints[0].position[2], 30.0, 1e-6) << "snapped to the open end's centre";
  const auto points = PointsOf(result.branches);
  ASSERT_GT(points.size(), 10u);
  EXPECT_NEAR(points.front()[2], 30.0, 1e-6);
  EXPECT_NEAR(points.back()[2], 10.0, R);
}
