// Flow extensions: straight tubes along each end's outward normal, Factor x the end's
// radius long, sharing the rim, blended into a circle, capped and labelled with the end's
// name; on an analytic tube, an elliptic tube and the clipped gmsh aneurysm.

#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "FlowExtensions.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "VesselCenterlines.h"
#include "VesselClip.h"
#include "VesselTestUtilities.h"
#include "vtkBenderCapFilter.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <iostream>

using namespace bender;
using namespace bender::test;

namespace
{
double Dot3(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// An open tube along z, z in [0, length], with an elliptic section (a, b).
vtkSmartPointer<vtkPolyData> EllipticTube(double a, double b, double length, int around, int along)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (int j = 0; j <= along; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const double t = 2 * M_PI * i / around;
      pts->InsertNextPoint(a * std::cos(t), b * std::sin(t), length * j / along);
    }
  }
  vtkNew<vtkCellArray> polys;
  for (int j = 0; j < along; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const vtkIdType p = j * around + i, q = j * around + (i + 1) % around;
      const vtkIdType t1[3] = { p, q, q + around }, t2[3] = { p, q + around, p + around };
      polys->InsertNextCell(3, t1);
      polys->InsertNextCell(3, t2);
    }
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  return pd;
}

vtkSmartPointer<vtkPolyData> CapNamed(vtkPolyData* open,
  const FlowExtensionResult& r,
  const std::vector<FlowExtensionEnd>& ends,
  vtkBenderCapFilter* cap)
{
  for (std::size_t k = 0; k < r.ends.size(); ++k)
  {
    cap->AddCapName(r.ends[k].farCentre.data(),
      ends[k].inlet ? "inlet" : "outlet_" + std::to_string(k),
      ends[k].inlet);
  }
  cap->SetInputData(open);
  cap->Update();
  return cap->GetOutput();
}

class FlowExtensionTest : public ::testing::Test
{
protected:
  void SetUp() override { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
};
} // namespace

TEST_F(FlowExtensionTest, LengthDirectionCircleAndLabels)
{
  // Elliptic tube: radii 2.5 x 1.6, the extensions end on circles of the same area.
  auto tube = EllipticTube(2.5, 1.6, 20.0, 64, 40);
  std::vector<FlowExtensionEnd> ends = OpenEnds(tube);
  ASSERT_EQ(ends.size(), 2u);
  const double r = std::sqrt(2.5 * 1.6);
  int inlets = 0;
  for (const FlowExtensionEnd& e : ends)
  {
    inlets += e.inlet ? 1 : 0;
    EXPECT_NEAR(std::abs(e.normal[2]), 1.0, 1e-9);
    EXPECT_EQ(e.normal[2] > 0, e.centre[2] > 10.0); // outwards
    EXPECT_NEAR(e.radius, r, 0.01 * r);
  }
  ASSERT_EQ(inlets, 1);
  const FlowExtensionResult result = AddFlowExtensions(tube, ends);
  ASSERT_EQ(result.ends.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k)
  {
    const ExtendedEnd& x = result.ends[k];
    const double factor = ends[k].inlet ? 10.0 : 5.0;
    EXPECT_DOUBLE_EQ(x.factor, factor);
    EXPECT_NEAR(x.length, factor * ends[k].radius, 1e-12);
    // Far centre along the outward normal, at Length from the rim's centre.
    const double along = (x.farCentre[2] - ends[k].centre[2]) * ends[k].normal[2];
    EXPECT_NEAR(along, x.length, 1e-9);
    EXPECT_NEAR(x.farCentre[0], 0.0, 1e-9);
    ASSERT_EQ(x.farRim.size(), 64u);
    for (long long v : x.farRim)
    {
      std::array<double, 3> p;
      result.surface->GetPoint(v, p.data());
      EXPECT_NEAR(p[2], x.farCentre[2], 1e-9);                   // on the far plane
      EXPECT_NEAR(std::hypot(p[0], p[1]), ends[k].radius, 1e-9); // on the circle
    }
  }
  // Capped: closed, manifold, consistent, outwards; extension walls are wall, caps the ends.
  vtkNew<vtkBenderCapFilter> cap;
  vtkSmartPointer<vtkPolyData> closed = CapNamed(result.surface, result, ends, cap);
  ASSERT_EQ(cap->GetNumberOfCaps(), 2);
  MeshCheckOptions check;
  check.requireClosed = true;
  const MeshCheckReport report = CheckMesh(closed, nullptr, check);
  EXPECT_TRUE(report.Clean()) << FormatReportText(report, "extended");
  EXPECT_GT(report.volume, 0.0);
  // Volume: the tube plus two extensions of (about) the same section area.
  const double area = M_PI * 2.5 * 1.6;
  EXPECT_NEAR(report.volume, area * (20.0 + 15.0 * r), 0.02 * area * (20.0 + 15.0 * r));
  const std::vector<PatchLabel> labels = ReadPatchLabels(closed);
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0].name, "wall");
  const std::vector<int> ids = CellPatchIds(closed);
  const auto extensionTriangles =
    static_cast<std::size_t>(result.surface->GetNumberOfPolys() - tube->GetNumberOfPolys());
  for (std::size_t t = 0; t < static_cast<std::size_t>(result.surface->GetNumberOfPolys()); ++t)
  {
    ASSERT_EQ(ids[t], kWallEntityId) << "extension triangle " << t;
  }
  EXPECT_GT(extensionTriangles, 0u);
  for (const auto& capInfo : cap->GetCaps())
  {
    EXPECT_EQ(capInfo.inlet, capInfo.name == "inlet");
    EXPECT_GT(std::abs(capInfo.centre[2] - 10.0), 10.0 + 4.9 * r);
  }
}

TEST_F(FlowExtensionTest, PerEndFactorsAndErrors)
{
  auto tube = EllipticTube(2.0, 2.0, 10.0, 48, 20);
  std::vector<FlowExtensionEnd> ends = OpenEnds(tube);
  ASSERT_EQ(ends.size(), 2u);
  ends[0].factor = 0.0; // no extension
  ends[1].factor = 3.0;
  const FlowExtensionResult r = AddFlowExtensions(tube, ends);
  EXPECT_EQ(r.ends[0].length, 0.0);
  EXPECT_EQ(r.ends[0].farRim, ends[0].rim);
  EXPECT_NEAR(r.ends[1].length, 3.0 * ends[1].radius, 1e-12);
  ends[1].factor = 1000.0;
  EXPECT_THROW(AddFlowExtensions(tube, ends), InputError);
  ends[1].factor = 3.0;
  FlowExtensionOptions bad;
  bad.inletFactor = std::nan("");
  EXPECT_THROW(AddFlowExtensions(tube, ends, bad), InputError);
  ends[1].rim = { 0, 1 };
  EXPECT_THROW(AddFlowExtensions(tube, ends), InputError);
}

TEST_F(FlowExtensionTest, ClippedAneurysmExtendedAndCappedIsClosedAndClean)
{
  auto surface = ReadMesh(std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl");
  const CenterlineResult cl = ComputeCenterlines(surface);
  ASSERT_TRUE(cl.ok) << cl.message;
  const ClipResult clipped = ClipVesselEnds(surface, cl.paths);
  ASSERT_EQ(clipped.ends.size(), 3u);
  std::vector<FlowExtensionEnd> ends;
  std::size_t largest = 0;
  for (std::size_t k = 0; k < clipped.ends.size(); ++k)
  {
    const ClippedEnd& c = clipped.ends[k];
    ends.push_back({ c.rim, c.centre, c.normal, c.radius, -1.0, false });
    if (c.area > clipped.ends[largest].area)
    {
      largest = k;
    }
  }
  ends[largest].inlet = true;
  const FlowExtensionResult result = AddFlowExtensions(clipped.surface, ends);
  // The two outlets of this model point towards each other: their extensions are shortened
  // (with a warning each) so that they do not collide; the inlet's is full length.
  std::size_t shortened = 0;
  for (std::size_t k = 0; k < ends.size(); ++k)
  {
    const double requested = (ends[k].inlet ? 10.0 : 5.0) * ends[k].radius;
    EXPECT_NEAR(result.ends[k].requestedLength, requested, 1e-9);
    EXPECT_LE(result.ends[k].length, requested);
    EXPECT_GE(result.ends[k].length, 0.0);
    if (ends[k].inlet)
    {
      EXPECT_NEAR(result.ends[k].length, requested, 1e-9);
    }
    shortened += result.ends[k].length < requested ? 1 : 0;
    const double expected = result.ends[k].length;
    // Direction: the far centre is along the clip normal (the centerline's tangent).
    const std::array<double, 3> d{ { result.ends[k].farCentre[0] - ends[k].centre[0],
      result.ends[k].farCentre[1] - ends[k].centre[1],
      result.ends[k].farCentre[2] - ends[k].centre[2] } };
    EXPECT_NEAR(Dot3(d, ends[k].normal), expected, 1e-9);
  }
  EXPECT_EQ(result.warnings.size(), shortened);
  vtkNew<vtkBenderCapFilter> cap;
  vtkSmartPointer<vtkPolyData> closed = CapNamed(result.surface, result, ends, cap);
  ASSERT_EQ(cap->GetNumberOfCaps(), 3);
  MeshCheckOptions check;
  check.requireClosed = true;
  // Self-intersections included: the extensions that really collided before their lengths
  // were cleared gave 384 pairs.
  const MeshCheckReport report = CheckMesh(closed, nullptr, check);
  EXPECT_TRUE(report.Clean()) << FormatReportText(report, "aneurysm");
  EXPECT_EQ(report.selfIntersections, 0);
  EXPECT_GT(report.volume, 0.0);
  for (const auto& info : cap->GetCaps())
  {
    EXPECT_GE(info.minInteriorAngle, 20.0) << info.name;
    EXPECT_LE(info.maxRimDistance, 1e-9 * info.radius) << info.name;
  }
}
