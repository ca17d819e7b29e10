// vtkBenderWarpFilter: agreement with the geometry core, float and double points, data
// passing, stale normals removed, binding reuse, errors on bad input, never a NaN.

#include "vtkBenderWarpFilter.h"

#include "RibbonWarp.h"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkCylinderSource.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTriangleFilter.h>

#include <cmath>
#include <memory>

namespace
{
using bender::Vec3;

// The format document's example: the end of a tube along x bent by 90 degrees.
bender::WarpSpec Bend90()
{
  bender::WarpSpec w;
  w.initial.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.initial.end = { { 40, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.final.start = w.initial.start;
  w.final.end = { { 30, 20, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  w.radius = 12.5;
  w.decay = { bender::DecayShape::Plateau, 0.4 };
  return w;
}

// A triangulated tube of radius 5 along x from -5 to 45, with normals and data arrays.
vtkSmartPointer<vtkPolyData> Tube(int pointType)
{
  vtkNew<vtkCylinderSource> cyl;
  cyl->SetRadius(5.0);
  cyl->SetHeight(50.0);
  cyl->SetResolution(48);
  cyl->SetCenter(0, 0, 0);
  cyl->SetOutputPointsPrecision(
    pointType == VTK_DOUBLE ? vtkAlgorithm::DOUBLE_PRECISION : vtkAlgorithm::SINGLE_PRECISION);
  cyl->Update();
  // The cylinder is along y: rotate to x and shift to [-5, 45]. Refine along the axis.
  vtkSmartPointer<vtkPolyData> tube = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataType(pointType);
  const int rings = 101, sides = 48;
  for (int i = 0; i < rings; ++i)
  {
    const double x = -5.0 + 50.0 * i / (rings - 1);
    for (int k = 0; k < sides; ++k)
    {
      const double a = 2.0 * 3.14159265358979 * k / sides;
      pts->InsertNextPoint(x, 5.0 * std::cos(a), 5.0 * std::sin(a));
    }
  }
  vtkNew<vtkCellArray> polys;
  for (int i = 0; i + 1 < rings; ++i)
  {
    for (int k = 0; k < sides; ++k)
    {
      const vtkIdType a = i * sides + k, b = i * sides + (k + 1) % sides;
      const vtkIdType t0[3] = { a, a + sides, b + sides };
      const vtkIdType t1[3] = { a, b + sides, b };
      polys->InsertNextCell(3, t0);
      polys->InsertNextCell(3, t1);
    }
  }
  tube->SetPoints(pts);
  tube->SetPolys(polys);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(tube);
  normals->ComputeCellNormalsOn();
  normals->SplittingOff();
  normals->Update();
  tube->DeepCopy(normals->GetOutput());
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("vertexId");
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    ids->InsertNextValue(i);
  }
  tube->GetPointData()->AddArray(ids);
  vtkNew<vtkDoubleArray> cellValue;
  cellValue->SetName("patch");
  cellValue->SetNumberOfTuples(tube->GetNumberOfCells());
  cellValue->FillValue(7.0);
  tube->GetCellData()->AddArray(cellValue);
  return tube;
}

Vec3 PointOf(vtkPolyData* pd, vtkIdType i)
{
  double p[3];
  pd->GetPoint(i, p);
  return { p[0], p[1], p[2] };
}

class QuietVtk
{
public:
  QuietVtk() { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
  ~QuietVtk() { vtkOutputWindow::GetInstance()->SetDisplayModeToDefault(); }
};

TEST(WarpFilter, MatchesGeometryCoreExactlyForDoubleAndFloatPoints)
{
  const bender::WarpSpec spec = Bend90();
  const bender::RibbonWarp warp(spec);
  for (int type : { VTK_DOUBLE, VTK_FLOAT })
  {
    auto tube = Tube(type);
    vtkNew<vtkBenderWarpFilter> filter;
    filter->SetInputData(tube);
    filter->SetWarp(spec);
    filter->Update();
    vtkPolyData* out = filter->GetOutput();
    ASSERT_EQ(out->GetNumberOfPoints(), tube->GetNumberOfPoints());
    EXPECT_EQ(out->GetPoints()->GetDataType(), type);
    double worst = 0.0;
    for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
    {
      const Vec3 expected = warp.Apply(PointOf(tube, i));
      worst = std::max(worst, bender::Distance(expected, PointOf(out, i)));
    }
    // Float points: the input is already rounded to float, the output too.
    EXPECT_LT(worst, type == VTK_DOUBLE ? 1e-12 : 1e-4) << "point type " << type;
    EXPECT_GT(filter->GetNumberOfBoundPoints(), 0);
  }
}

TEST(WarpFilter, MovesOnlyPointsInsideTheRegionOfInfluenceAndMovesThem)
{
  const bender::WarpSpec spec = Bend90();
  auto tube = Tube(VTK_DOUBLE);
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(spec);
  filter->Update();
  const bender::Ribbon initial(spec.initial);
  int moved = 0;
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    const Vec3 p = PointOf(tube, i);
    const auto pr = bender::ProjectOntoWire(initial.Wire(), p, spec.radius);
    const double shift = bender::Distance(p, PointOf(filter->GetOutput(), i));
    if (pr.count == 0)
    {
      EXPECT_EQ(shift, 0.0) << "point " << i << " outside R moved";
    }
    else if (shift > 1e-6)
    {
      ++moved;
    }
  }
  EXPECT_GT(moved, 1000);
}

TEST(WarpFilter, PassesDataAndRemovesStaleNormals)
{
  auto tube = Tube(VTK_DOUBLE);
  ASSERT_NE(tube->GetPointData()->GetNormals(), nullptr);
  ASSERT_NE(tube->GetCellData()->GetNormals(), nullptr);
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(Bend90());
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  EXPECT_EQ(out->GetPointData()->GetNormals(), nullptr);
  EXPECT_EQ(out->GetCellData()->GetNormals(), nullptr);
  ASSERT_NE(out->GetPointData()->GetArray("vertexId"), nullptr);
  ASSERT_NE(out->GetCellData()->GetArray("patch"), nullptr);
  EXPECT_EQ(out->GetPointData()->GetArray("vertexId")->GetTuple1(17), 17.0);
  EXPECT_EQ(out->GetNumberOfCells(), tube->GetNumberOfCells());
  EXPECT_EQ(out->GetPolys()->GetNumberOfCells(), tube->GetPolys()->GetNumberOfCells());
}

TEST(WarpFilter, KeepsBindingWhileOnlyTheFinalRibbonMoves)
{
  auto tube = Tube(VTK_DOUBLE);
  bender::WarpSpec spec = Bend90();
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(spec);
  filter->SetPrecision(bender::WarpPrecision::Table);
  filter->Update();
  EXPECT_EQ(filter->GetBindingCount(), 1);
  for (int step = 1; step <= 5; ++step)
  {
    spec.final.end.position = { 40.0 - 2.0 * step, 4.0 * step, 0.0 };
    filter->SetFinalRibbon(spec.final);
    filter->Update();
  }
  EXPECT_EQ(filter->GetBindingCount(), 1);
  // The table path agrees with the exact one within 1e-5 of the model size (50).
  const bender::RibbonWarp exact(spec);
  double worst = 0.0;
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    worst = std::max(
      worst, bender::Distance(exact.Apply(PointOf(tube, i)), PointOf(filter->GetOutput(), i)));
  }
  EXPECT_LT(worst, 50.0 * 1e-5);
  // A new radius, a moved initial ribbon or new input points force a new binding.
  filter->SetRadius(10.0);
  filter->Update();
  EXPECT_EQ(filter->GetBindingCount(), 2);
  spec.radius = 10.0;
  spec.initial.end.position = { 41, 0, 0 };
  filter->SetWarp(spec);
  filter->Update();
  EXPECT_EQ(filter->GetBindingCount(), 3);
  tube->GetPoints()->SetPoint(0, -5.0, 5.0, 0.1);
  tube->GetPoints()->Modified();
  filter->Update();
  EXPECT_EQ(filter->GetBindingCount(), 4);
}

TEST(WarpFilter, PassesFieldDataWhenWarpingAndWhenPassingThrough)
{
  // The CFD patch names (issue 11) live in field data: a warp must not drop them.
  auto tube = Tube(VTK_FLOAT);
  vtkNew<vtkStringArray> names;
  names->SetName("PatchNames");
  names->InsertNextValue("wall");
  names->InsertNextValue("inlet");
  tube->GetFieldData()->AddArray(names);
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(Bend90());
  for (bool passThrough : { false, true })
  {
    filter->SetPassThrough(passThrough);
    filter->Update();
    auto* got = vtkStringArray::SafeDownCast(
      filter->GetOutput()->GetFieldData()->GetAbstractArray("PatchNames"));
    ASSERT_NE(got, nullptr) << (passThrough ? "pass-through" : "warped");
    ASSERT_EQ(got->GetNumberOfValues(), 2);
    EXPECT_EQ(got->GetValue(1), "inlet");
  }
  // And the warped output moved (the field data did not replace the points).
  filter->SetPassThrough(false);
  filter->Update();
  EXPECT_GT(bender::Distance(PointOf(filter->GetOutput(), tube->GetNumberOfPoints() - 1),
              PointOf(tube, tube->GetNumberOfPoints() - 1)),
    1.0);
}

TEST(WarpFilter, ParallelResultEqualsSequential)
{
  auto tube = Tube(VTK_DOUBLE);
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(Bend90());
  filter->Update();
  vtkNew<vtkPolyData> parallel;
  parallel->DeepCopy(filter->GetOutput());
  vtkSMPTools::Initialize(1);
  vtkNew<vtkBenderWarpFilter> serial;
  serial->SetInputData(tube);
  serial->SetWarp(Bend90());
  serial->Update();
  vtkSMPTools::Initialize(0);
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    ASSERT_EQ(bender::Distance(PointOf(parallel, i), PointOf(serial->GetOutput(), i)), 0.0);
  }
}

TEST(WarpFilter, InvalidRibbonIsAnErrorAndWarpsNothing)
{
  QuietVtk quiet;
  auto tube = Tube(VTK_DOUBLE);
  bender::WarpSpec spec = Bend90();
  spec.final.end.position = spec.final.start.position; // coincident ends
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(spec);
  filter->Update();
  EXPECT_NE(filter->GetLastError().find("final"), std::string::npos) << filter->GetLastError();
  EXPECT_NE(filter->GetLastError().find("coincident"), std::string::npos);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  spec = Bend90();
  spec.radius = -1.0;
  filter->SetWarp(spec);
  filter->Update();
  EXPECT_NE(filter->GetLastError().find("radius"), std::string::npos);

  spec = Bend90();
  spec.final.end.tangent = { 0, 0, 0 };
  filter->SetWarp(spec);
  filter->Update();
  EXPECT_NE(filter->GetLastError().find("final.end.tangent"), std::string::npos)
    << filter->GetLastError();
}

TEST(WarpFilter, NonFiniteInputIsAnError)
{
  QuietVtk quiet;
  auto tube = Tube(VTK_DOUBLE);
  tube->GetPoints()->SetPoint(10, std::nan(""), 0.0, 0.0);
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(Bend90());
  filter->Update();
  EXPECT_NE(filter->GetLastError().find("non-finite"), std::string::npos);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(WarpFilter, EmptyInputAndMeshWithoutTrianglesAreHandled)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(empty);
  filter->SetWarp(Bend90());
  filter->Update();
  EXPECT_TRUE(filter->GetLastError().empty());
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  // Points only (no cells): warped all the same.
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(20, 5, 0);
  pts->InsertNextPoint(100, 0, 0);
  cloud->SetPoints(pts);
  filter->SetInputData(cloud);
  filter->Update();
  ASSERT_EQ(filter->GetOutput()->GetNumberOfPoints(), 2);
  EXPECT_GT(bender::Distance(PointOf(filter->GetOutput(), 0), { 20, 5, 0 }), 0.1);
  EXPECT_EQ(bender::Distance(PointOf(filter->GetOutput(), 1), { 100, 0, 0 }), 0.0);
}

TEST(WarpFilter, ReportsSpaceInversionRiskAndFlip)
{
  auto tube = Tube(VTK_DOUBLE);
  bender::WarpSpec spec = Bend90();
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(tube);
  filter->SetWarp(spec);
  filter->Update();
  // Final wire of the bend: r_min is the radius of its arcs (about 21 mm) > R = 12.5.
  EXPECT_FALSE(filter->GetSpaceInversionRisk()) << filter->GetLastWarning();
  spec.radius = 30.0;
  filter->SetWarp(spec);
  filter->Update();
  EXPECT_TRUE(filter->GetSpaceInversionRisk());
  EXPECT_NE(filter->GetLastWarning().find("space inversion"), std::string::npos);
}

} // namespace

// A drag hands the filter a warp built (and validated) once by the caller; the filter uses it
// as is, keeps its output points, writes only the bound points per move, and equals a filter
// that recomputes everything.
TEST(WarpFilter, PreparedWarpIsUsedAsIsAndAMoveCopiesNoSurface)
{
  auto tube = Tube(VTK_DOUBLE);
  vtkPoints* inputPoints = tube->GetPoints();
  const vtkMTimeType inputTime = inputPoints->GetMTime();
  bender::WarpSpec spec = Bend90();
  spec.final = spec.initial;
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetPrecision(bender::WarpPrecision::Table);
  filter->SetInputData(tube);
  filter->SetPreparedWarp(std::make_shared<const bender::RibbonWarp>(spec));
  filter->Update();
  ASSERT_TRUE(filter->GetLastError().empty()) << filter->GetLastError();
  vtkPoints* outputPoints = filter->GetOutput()->GetPoints();
  EXPECT_EQ(filter->GetPointsCopyCount(), 1);
  for (int step = 1; step <= 6; ++step)
  {
    spec.final.end.position = { 40.0 - 2.0 * step, 3.0 * step, 0 };
    spec.final.end.tangent = bender::Normalized(Vec3{ 1.0, 0.15 * step, 0 });
    filter->SetPreparedWarp(std::make_shared<const bender::RibbonWarp>(spec));
    filter->Update();
    ASSERT_TRUE(filter->GetLastError().empty()) << filter->GetLastError();
    EXPECT_EQ(filter->GetOutput()->GetPoints(), outputPoints);

    vtkNew<vtkBenderWarpFilter> fresh;
    fresh->SetPrecision(bender::WarpPrecision::Table);
    fresh->SetInputData(tube);
    fresh->SetWarp(spec);
    fresh->Update();
    double worst = 0.0;
    for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
    {
      worst = std::max(
        worst, bender::Distance(PointOf(filter->GetOutput(), i), PointOf(fresh->GetOutput(), i)));
    }
    EXPECT_EQ(worst, 0.0) << "step " << step;
    EXPECT_EQ(fresh->GetWarpBuildCount(), 1);
  }
  EXPECT_EQ(filter->GetWarpBuildCount(), 0);
  EXPECT_EQ(filter->GetBindingCount(), 1);
  EXPECT_EQ(filter->GetPointsCopyCount(), 1);
  EXPECT_EQ(tube->GetPoints(), inputPoints);
  EXPECT_EQ(inputPoints->GetMTime(), inputTime);

  // Somebody holding the output points gets a new array at the next update (their copy keeps
  // the previous shape).
  vtkSmartPointer<vtkPoints> held = filter->GetOutput()->GetPoints();
  const Vec3 before = PointOf(filter->GetOutput(), 4000);
  spec.final.end.position = { 20, 25, 0 };
  filter->SetPreparedWarp(std::make_shared<const bender::RibbonWarp>(spec));
  filter->Update();
  EXPECT_NE(filter->GetOutput()->GetPoints(), held.GetPointer());
  double p[3];
  held->GetPoint(4000, p);
  EXPECT_EQ(bender::Norm(Vec3{ p[0], p[1], p[2] } - before), 0.0);
  EXPECT_EQ(filter->GetPointsCopyCount(), 2);

  // Pass-through shares the input's points; a warp of another blend mode is rebuilt here.
  filter->PassThroughOn();
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetPoints(), inputPoints);
  filter->PassThroughOff();
  filter->SetBlendMode(bender::BlendMode::SingleProjection);
  filter->Update();
  EXPECT_EQ(filter->GetWarpBuildCount(), 1);
}
