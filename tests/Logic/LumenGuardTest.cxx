// The lumen guard (issue 22): the centerlines of a vessel before and after a bend give each
// branch's minimal inscribed radius; a branch the bend moved that lost more than the threshold
// is a problem, shown where it is narrowest. A bend that keeps the cross-sections passes; a
// shape that is no vessel is not measured.
#include "LumenGuard.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "LogicTestUtilities.h"

#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace bender;
using bender::test::MakeTube;

namespace
{

constexpr double TubeRadius = 2.0;
constexpr double TubeLength = 40.0;

// The tube's points mapped by `map` (a copy; same cells).
vtkSmartPointer<vtkPolyData> Mapped(vtkPolyData* tube,
  const std::function<Point3(const Point3&)>& map)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(tube);
  for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
  {
    Point3 p;
    copy->GetPoint(i, p.data());
    const Point3 q = map(p);
    copy->GetPoints()->SetPoint(i, q.data());
  }
  return copy;
}

// A waist centred at x = `at`: the cross-section shrinks smoothly to (1 - depth) of its
// radius over a few millimetres.
vtkSmartPointer<vtkPolyData> Pinched(vtkPolyData* tube, double at, double depth)
{
  return Mapped(tube,
    [at, depth](const Point3& p)
    {
      const double u = (p[0] - at) / 3.0;
      const double scale = 1.0 - depth * std::exp(-u * u);
      return Point3{ { p[0], scale * p[1], scale * p[2] } };
    });
}

// The tube bent into an arc of radius `bend` (cross-sections kept exactly).
vtkSmartPointer<vtkPolyData> ArcOfRadius(vtkPolyData* tube, double bend)
{
  return Mapped(tube,
    [bend](const Point3& p)
    {
      const double a = p[0] / bend;
      return Point3{ { (bend - p[1]) * std::sin(a), bend - (bend - p[1]) * std::cos(a), p[2] } };
    });
}

}

TEST(LumenGuard, AnUntouchedVesselPasses)
{
  auto tube = MakeTube(0, TubeLength, TubeRadius);
  const LumenCheck check = CheckLumen(tube, tube);
  ASSERT_TRUE(check.checked) << check.notMeasured;
  EXPECT_TRUE(check.Passed()) << check.Summary();
  ASSERT_FALSE(check.branches.empty());
  for (const BranchLumenChange& branch : check.branches)
  {
    EXPECT_FALSE(branch.moved); // nothing moved: nothing judged
    EXPECT_NEAR(branch.afterMinRadius, branch.beforeMinRadius, 1e-9);
  }
  EXPECT_EQ(check.worst, -1);
}

TEST(LumenGuard, AWaistIsHeldAndShownWhereItIs)
{
  auto tube = MakeTube(0, TubeLength, TubeRadius);
  const double at = 25.0;
  const LumenCheck check = CheckLumen(tube, Pinched(tube, at, 0.2));
  ASSERT_TRUE(check.checked) << check.notMeasured;
  EXPECT_FALSE(check.Passed());
  ASSERT_GE(check.worst, 0);
  const BranchLumenChange& worst = check.branches[static_cast<std::size_t>(check.worst)];
  EXPECT_TRUE(worst.moved);
  EXPECT_TRUE(worst.tooNarrow);
  EXPECT_LT(worst.afterMinRadius, worst.beforeMinRadius);
  // The waist takes a fifth off the radius; the inscribed sphere measures about that.
  EXPECT_GT(worst.narrowing, 0.12);
  EXPECT_LT(worst.narrowing, 0.28);
  EXPECT_NEAR(worst.narrowest[0], at, 2.0);
  EXPECT_NE(check.Summary().find("narrowed by"), std::string::npos) << check.Summary();
  const auto json = LumenCheckToJson(check);
  EXPECT_EQ(json.at("passed"), false);
  EXPECT_EQ(json.at("problems").size(), check.problems.size());
}

TEST(LumenGuard, TheThresholdDecides)
{
  auto tube = MakeTube(0, TubeLength, TubeRadius);
  auto pinched = Pinched(tube, 20.0, 0.1);
  LumenGuardOptions strict;
  strict.maxNarrowing = 0.03;
  LumenGuardOptions lenient;
  lenient.maxNarrowing = 0.3;
  const LumenCheck held = CheckLumen(tube, pinched, strict);
  const LumenCheck passed = CheckLumen(tube, pinched, lenient);
  EXPECT_FALSE(held.Passed());
  EXPECT_TRUE(passed.Passed()) << passed.Summary();
  ASSERT_GE(passed.worst, 0);
  // The same measure, judged twice.
  EXPECT_DOUBLE_EQ(held.branches[static_cast<std::size_t>(held.worst)].narrowing,
    passed.branches[static_cast<std::size_t>(passed.worst)].narrowing);
}

TEST(LumenGuard, ABendThatKeepsTheCrossSectionsPasses)
{
  auto tube = MakeTube(0, TubeLength, TubeRadius);
  const LumenCheck check = CheckLumen(tube, ArcOfRadius(tube, 30.0));
  ASSERT_TRUE(check.checked) << check.notMeasured;
  EXPECT_TRUE(check.Passed()) << check.Summary();
  ASSERT_GE(check.worst, 0);
  EXPECT_LT(std::fabs(check.branches[static_cast<std::size_t>(check.worst)].narrowing), 0.05);
}

TEST(LumenGuard, TheBeforeCenterlinesCanBeGivenOnce)
{
  auto tube = MakeTube(0, TubeLength, TubeRadius);
  const CenterlineResult before = LumenCenterlines(tube);
  ASSERT_TRUE(before.ok) << before.message;
  auto pinched = Pinched(tube, 15.0, 0.2);
  const LumenCheck given = CheckLumen(tube, pinched, {}, &before);
  const LumenCheck computed = CheckLumen(tube, pinched);
  ASSERT_GE(given.worst, 0);
  ASSERT_GE(computed.worst, 0);
  EXPECT_DOUBLE_EQ(given.branches[static_cast<std::size_t>(given.worst)].narrowing,
    computed.branches[static_cast<std::size_t>(computed.worst)].narrowing);
}

TEST(LumenGuard, AShapeWithoutCenterlineIsNotMeasured)
{
  // A flat sheet has no lumen.
  auto sheet = MakeTube(0, 10, 2.0, 11, 3);
  auto flat = Mapped(sheet, [](const Point3& p) { return Point3{ { p[0], p[1], 0.0 } }; });
  const LumenCheck check = CheckLumen(flat, flat);
  EXPECT_FALSE(check.checked);
  EXPECT_FALSE(check.notMeasured.empty());
  EXPECT_TRUE(check.Passed());
}

TEST(LumenGuard, RefusesAThresholdOutsideItsRange)
{
  auto tube = MakeTube(0, 10, TubeRadius, 11, 16);
  LumenGuardOptions options;
  options.maxNarrowing = 1.0;
  EXPECT_THROW(CheckLumen(tube, tube, options), InputError);
  options.maxNarrowing = -0.1;
  EXPECT_THROW(CheckLumen(tube, tube, options), InputError);
  EXPECT_THROW(CheckLumen(nullptr, tube), InputError);
}
