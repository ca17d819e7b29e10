// The vessel measure table (one row per measure, iterated by the JSON, the text tables and the
// panel) and the end-window rule shared by the plan's table and the live measures: on circular
// arcs of known angle the bend angle and the end tangents are those of the arc, and the
// measures of a polyline through MeasureBranches are those of MeasureStretch.

#include "VesselMeasureTable.h"
#include "VesselArrayNames.h"
#include "VesselMeasures.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

using namespace bender;

namespace
{
const double Pi = 3.14159265358979323846;

// A circular arc of radius `bend` turning by `angle` radians in the xy plane, from (bend, 0, 0)
// with tangent +y, sampled every `step` of arc.
std::vector<Point3> Arc(double bend, double angle, double step)
{
  std::vector<Point3> p;
  const int n = static_cast<int>(std::ceil(bend * angle / step));
  for (int i = 0; i <= n; ++i)
  {
    const double t = angle * i / n;
    p.push_back({ { bend * std::cos(t), bend * std::sin(t), 0.0 } });
  }
  return p;
}

vtkSmartPointer<vtkPolyData> Polyline(const std::vector<Point3>& p, const std::vector<double>& r)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> radius;
  radius->SetName(VesselArrays::MaximumInscribedSphereRadius);
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell(static_cast<vtkIdType>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    lines->InsertCellPoint(points->InsertNextPoint(p[i].data()));
    radius->InsertNextValue(r[i]);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  out->SetLines(lines);
  out->GetPointData()->AddArray(radius);
  return out;
}
} // namespace

TEST(VesselMeasureTable, RowsHaveUniqueKeysAndGetters)
{
  std::set<std::string> keys;
  std::set<std::string> panel;
  BranchMeasures b;
  b.length = 12.5;
  b.bendAngle = 30.0;
  b.minRadius = 1.5;
  for (const VesselMeasure& m : VesselMeasureTable())
  {
    EXPECT_FALSE(m.key.empty());
    EXPECT_FALSE(m.label.empty()) << m.key;
    EXPECT_TRUE(keys.insert(m.key).second) << m.key << " twice";
    ASSERT_TRUE(m.get) << m.key;
    EXPECT_TRUE(std::isfinite(m.get(b))) << m.key;
    if (m.panel)
    {
      panel.insert(m.key);
    }
  }
  // The panel's held branch: length, bend angle and narrowest radius, live during a bend.
  EXPECT_EQ(panel, (std::set<std::string>{ "length", "bendAngle", "minRadius" }));
  const auto& table = VesselMeasureTable();
  const auto bend = std::find_if(
    table.begin(), table.end(), [](const VesselMeasure& m) { return m.key == "bendAngle"; });
  ASSERT_NE(bend, table.end());
  EXPECT_EQ(bend->get(b), 30.0);
  EXPECT_EQ(MeasureTitle(*bend), "Bend angle (deg)");
}

TEST(VesselMeasureTable, RegisteringChecksTheRow)
{
  const std::size_t rows = VesselMeasureTable().size();
  EXPECT_THROW(
    RegisterVesselMeasure({ "", "Nothing", "", 2, [](const BranchMeasures&) { return 0.0; } }),
    std::invalid_argument);
  EXPECT_THROW(
    RegisterVesselMeasure({ "noGetter", "No getter", "", 2, nullptr }), std::invalid_argument);
  EXPECT_THROW(
    RegisterVesselMeasure(
      { "length", "Length again", "mm", 2, [](const BranchMeasures& b) { return b.length; } }),
    std::invalid_argument);
  RegisterVesselMeasure(
    { "chord", "Chord", "mm", 2, [](const BranchMeasures& b) { return b.chord; } });
  EXPECT_EQ(VesselMeasureTable().size(), rows + 1);
  EXPECT_EQ(VesselMeasureTable().back().key, "chord");
  EXPECT_TRUE(UnregisterVesselMeasure("chord"));
  EXPECT_FALSE(UnregisterVesselMeasure("chord"));
  EXPECT_EQ(VesselMeasureTable().size(), rows);
}

TEST(VesselMeasureTable, EndWindowRuleOnArcs)
{
  for (const double degrees : { 20.0, 45.0, 90.0, 150.0 })
  {
    SCOPED_TRACE(degrees);
    const double bend = 10.0, radius = 1.0, angle = degrees * Pi / 180.0;
    const std::vector<Point3> p = Arc(bend, angle, 0.05);
    const std::vector<double> r(p.size(), radius);
    EXPECT_NEAR(EndWindow(p, r), radius, 1e-12);
    const std::array<Point3, 2> ends = EndDirections(p, r);
    // The arc's tangents at its ends, pointing from start to end.
    EXPECT_NEAR(ends[0][0], 0.0, 1e-3);
    EXPECT_NEAR(ends[0][1], 1.0, 1e-3);
    EXPECT_NEAR(ends[1][0], -std::sin(angle), 1e-3);
    EXPECT_NEAR(ends[1][1], std::cos(angle), 1e-3);
    const BranchMeasures m = MeasureStretch(p, r);
    EXPECT_NEAR(m.bendAngle, degrees, 0.1);
    EXPECT_NEAR(m.length, bend * angle, 1e-3 * bend * angle);
    EXPECT_NEAR(m.maxCurvature, 1.0 / bend, 0.02 / bend);
    EXPECT_NEAR(m.minRadius, radius, 1e-12);
    // The plan's table (MeasureBranches of the polyline) and the stretch agree exactly.
    const VesselMeasurements table = MeasureBranches(Polyline(p, r));
    ASSERT_EQ(table.branches.size(), 1u);
    for (const VesselMeasure& row : VesselMeasureTable())
    {
      EXPECT_NEAR(row.get(table.branches[0]), row.get(m), 1e-9) << row.key;
    }
  }
}

TEST(VesselMeasureTable, EndWindowIsAtMostAThirdOfTheStretch)
{
  const std::vector<Point3> p = {
    { { 0, 0, 0 } }, { { 1, 0, 0 } }, { { 2, 0, 0 } }, { { 3, 0, 0 } }
  };
  const std::vector<double> r(p.size(), 5.0);
  EXPECT_NEAR(EndWindow(p, r), 1.0, 1e-12);
  const BranchMeasures m = MeasureStretch(p, r);
  EXPECT_NEAR(m.bendAngle, 0.0, 1e-9);
  EXPECT_NEAR(m.tortuosity, 1.0, 1e-12);
  // Two samples: the chord at both ends.
  const BranchMeasures two = MeasureStretch({ p[0], p[1] }, { 1.0, 1.0 });
  EXPECT_NEAR(two.bendAngle, 0.0, 1e-12);
  EXPECT_NEAR(two.startTangent[0], 1.0, 1e-12);
  // Too few points or radii of another count: the default measures.
  EXPECT_EQ(MeasureStretch({ p[0] }, { 1.0 }).length, 0.0);
  EXPECT_EQ(MeasureStretch(p, { 1.0 }).length, 0.0);
}
