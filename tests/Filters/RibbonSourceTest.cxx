// vtkBenderRibbonSource: the strip follows the frames, the wire interpolates the ends, the
// tube is closed and at distance R from the wire, an invalid ribbon is reported.

#include "vtkBenderRibbonSource.h"

#include "VtkErrorWatch.h"

#include "Ribbon.h"
#include "WireProjection.h"

#include <gtest/gtest.h>

#include <vtkFeatureEdges.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

namespace
{
bender::RibbonSpec Bent()
{
  bender::RibbonSpec r;
  r.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  r.end = { { 30, 20, 0 }, { 0, 1, 0 }, { 1, 0, 1 } };
  return r;
}

TEST(RibbonSource, WireAndStripFollowTheRibbon)
{
  vtkNew<vtkBenderRibbonSource> src;
  src->SetRibbon(Bent());
  src->SetResolution(64);
  src->SetWidth(2.0);
  src->Update();
  ASSERT_TRUE(src->GetValid());
  vtkPolyData* wire = src->GetOutput(1);
  ASSERT_EQ(wire->GetNumberOfPoints(), 65);
  double p[3];
  wire->GetPoint(0, p);
  EXPECT_NEAR(p[0], 0.0, 1e-12);
  wire->GetPoint(64, p);
  EXPECT_NEAR(p[0], 30.0, 1e-9);
  EXPECT_NEAR(p[1], 20.0, 1e-9);

  const bender::Ribbon ribbon(Bent());
  vtkPolyData* strip = src->GetOutput(0);
  ASSERT_EQ(strip->GetNumberOfPoints(), 130);
  for (int i = 0; i <= 64; ++i)
  {
    const bender::Frame f = ribbon.FrameAt(i / 64.0);
    double a[3], b[3];
    strip->GetPoint(2 * i, a);
    strip->GetPoint(2 * i + 1, b);
    // The two edge points are at +-Width along N_s.
    const bender::Vec3 d{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    EXPECT_LT(bender::Distance(d, f.n * 4.0), 1e-9);
  }
}

TEST(RibbonSource, TubeIsClosedAtDistanceRFromTheWire)
{
  vtkNew<vtkBenderRibbonSource> src;
  src->SetRibbon(Bent());
  src->SetRadius(3.0);
  src->Update();
  vtkPolyData* tube = src->GetOutput(2);
  ASSERT_GT(tube->GetNumberOfCells(), 0);
  const bender::Ribbon ribbon(Bent());
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    double p[3];
    tube->GetPoint(i, p);
    const auto pr = bender::ProjectOntoWire(ribbon.Wire(), { p[0], p[1], p[2] }, 1e9);
    ASSERT_GE(pr.count, 1);
    EXPECT_NEAR(pr.items[0].distance, 3.0, 1e-6) << "tube point " << i;
  }
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(tube);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  EXPECT_EQ(edges->GetOutput()->GetNumberOfCells(), 0) << "tube has boundary edges";
}

TEST(RibbonSource, InvalidRibbonGivesEmptyOutputAndAReason)
{
  bender::RibbonSpec r = Bent();
  r.end.position = r.start.position;
  vtkNew<vtkBenderRibbonSource> src;
  bendertest::VtkErrorWatch errors(src);
  src->SetRibbon(r);
  src->SetRadius(2.0);
  src->Update();
  // An invalid ribbon is a state of the interaction (shown to the user), not a VTK error.
  EXPECT_TRUE(errors.ExpectNone());
  EXPECT_FALSE(src->GetValid());
  EXPECT_NE(src->GetLastError().find("coincident"), std::string::npos);
  EXPECT_EQ(src->GetOutput(0)->GetNumberOfPoints(), 0);
  EXPECT_EQ(src->GetOutput(2)->GetNumberOfPoints(), 0);
}

} // namespace
