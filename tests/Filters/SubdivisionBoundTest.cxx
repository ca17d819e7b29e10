// Issue 13: subdivision is bounded up front. A tolerance below the rounding noise of the
// surface with many passes used to run for minutes and gigabytes until the 25 M-point stop.

#include "vtkBenderAdaptiveSubdivisionFilter.h"

#include "RibbonWarp.h"
#include "VtkErrorWatch.h"

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

namespace
{

bender::WarpSpec Bend()
{
  bender::WarpSpec w;
  w.initial.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.initial.end = { { 10, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  w.final.start = w.initial.start;
  w.final.end = { { 7, 6, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  w.radius = 4.0;
  return w;
}

vtkSmartPointer<vtkPolyData> Sphere320()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(5, 0, 0);
  sphere->SetRadius(2.0);
  sphere->SetThetaResolution(20);
  sphere->SetPhiResolution(10); // 2 * 20 * (10 - 2) = 320 triangles
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  return sphere->GetOutput();
}

} // namespace

TEST(SubdivisionBound, AbsurdToleranceWithManyPassesIsRefusedBeforeWork)
{
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  auto sphere = Sphere320();
  ASSERT_EQ(sphere->GetNumberOfPolys(), 320);
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> filter;
  bendertest::VtkErrorWatch errors(filter);
  filter->SetInputData(sphere);
  filter->SetWarp(Bend());
  filter->SetTolerance(1e-12);
  filter->SetMaxPasses(64);
  filter->Update();
  const std::string message = filter->GetLastError();
  EXPECT_NE(message.find("below the rounding noise"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_TRUE(errors.ExpectError("rounding noise"));
  EXPECT_EQ(filter->GetNumberOfPassesRun(), 0); // refused before the first pass
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  // The same tolerance with few passes is bounded (320 * 4^2 triangles at most): it runs.
  filter->SetMaxPasses(2);
  filter->Update();
  EXPECT_EQ(filter->GetLastError(), "");
  EXPECT_TRUE(errors.ExpectNone());
  EXPECT_GT(filter->GetOutput()->GetNumberOfPoints(), sphere->GetNumberOfPoints());
}
