// PrepareForCfd: the gmsh aneurysm (open) and the demo segmentation (closed) become closed,
// clean, outward, labelled surfaces with an inlet and two outlets, flat caps and flow
// extensions; labels survive a VTP round trip, a warp and adaptive subdivision; every bad input
// is one InputError line naming the surface.

#include "PrepareForCfd.h"
#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "BenderSession.h"
#include "DemoPipeline.h"
#include "LogicTestUtilities.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "VesselCenterlines.h"
#include "vtkBenderAdaptiveSubdivisionFilter.h"
#include "vtkBenderWarpFilter.h"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

using namespace bender;

namespace
{
const std::string Aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";

/// Checks a prepared surface: closed, manifold, consistent, outwards, the labels and ends.
void ExpectReady(const PrepareForCfdResult& r, std::size_t ends)
{
  MeshCheckOptions check;
  check.requireClosed = true;
  const MeshCheckReport report = CheckMesh(r.Surface, nullptr, check);
  EXPECT_TRUE(report.Clean()) << FormatReportText(report, "prepared");
  EXPECT_GT(report.volume, 0.0);
  const std::vector<PatchLabel> labels = ReadPatchLabels(r.Surface);
  ASSERT_EQ(labels.size(), ends + 1);
  EXPECT_EQ(labels[0].name, "wall");
  ASSERT_EQ(r.Ends.size(), ends);
  int inlets = 0;
  for (std::size_t k = 0; k < ends; ++k)
  {
    EXPECT_EQ(r.Ends[k].Id, static_cast<int>(k) + 2);
    EXPECT_EQ(labels[k + 1].name, r.Ends[k].Name);
    EXPECT_EQ(labels[k + 1].type, r.Ends[k].Type);
    inlets += r.Ends[k].Type == PatchType::Inlet ? 1 : 0;
    EXPECT_NEAR(
      std::hypot(r.Ends[k].Normal[0], r.Ends[k].Normal[1], r.Ends[k].Normal[2]), 1.0, 1e-9);
    EXPECT_GT(r.Ends[k].Area, 0.0);
  }
  EXPECT_EQ(inlets, 1);
}

class PrepareForCfdTest : public ::testing::Test
{
protected:
  void SetUp() override { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
};
} // namespace

TEST_F(PrepareForCfdTest, AneurysmIsClippedExtendedCappedAndLabelled)
{
  auto surface = ReadMesh(Aneurysm);
  PrepareForCfdOptions options;
  options.InputName = "aneurysm_data.stl";
  const PrepareForCfdResult r = PrepareForCfd(surface, options);
  ExpectReady(r, 3);
  EXPECT_EQ(r.Ends[0].Name, "inlet"); // the largest end
  EXPECT_EQ(r.Ends[1].Name, "outlet_1");
  EXPECT_EQ(r.Ends[2].Name, "outlet_2");
  EXPECT_NEAR(r.Ends[0].ExtensionLength, 10.0 * std::sqrt(r.Ends[0].Area / M_PI), 0.05 * 44);

  // Labels through a VTP round trip.
  const std::string path =
    (std::filesystem::temp_directory_path() / "bender_prepare_for_cfd.vtp").string();
  WriteMesh(r.Surface, path);
  auto back = ReadMesh(path);
  std::remove(path.c_str());
  EXPECT_EQ(CellPatchIds(back), CellPatchIds(r.Surface));
  const auto labels = ReadPatchLabels(back);
  ASSERT_EQ(labels.size(), 4u);
  EXPECT_EQ(labels[1].name, "inlet");

  // Through a warp and adaptive subdivision: every triangle keeps its parent's label, so the
  // area of each patch is (nearly) unchanged by the subdivision.
  vtkNew<vtkBenderWarpFilter> warp;
  warp->SetInputData(r.Surface);
  warp->Update();
  EXPECT_EQ(CellPatchIds(warp->GetOutput()), CellPatchIds(r.Surface));
  ASSERT_EQ(ReadPatchLabels(warp->GetOutput()).size(), 4u);
  EXPECT_EQ(ReadPatchLabels(warp->GetOutput())[1].name, "inlet"); // field data passed too
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivide;
  subdivide->SetInputData(r.Surface);
  subdivide->Update();
  vtkPolyData* fine = subdivide->GetOutput();
  ASSERT_GE(fine->GetNumberOfPolys(), r.Surface->GetNumberOfPolys());
  EXPECT_EQ(ReadPatchLabels(fine).size(), 4u);
  EXPECT_EQ(ReadPatchLabels(fine)[2].name, "outlet_1");
}

TEST_F(PrepareForCfdTest, NamesByPositionNoExtensionNoCap)
{
  auto surface = ReadMesh(Aneurysm);
  PrepareForCfdOptions first;
  first.InletExtension = first.OutletExtension = 0.0;
  const PrepareForCfdResult plain = PrepareForCfd(surface, first);
  ExpectReady(plain, 3);
  for (const CfdEnd& end : plain.Ends)
  {
    EXPECT_EQ(end.ExtensionLength, 0.0);
    EXPECT_LT(std::sqrt(std::pow(end.Centre[0] - end.ClipCentre[0], 2) +
                std::pow(end.Centre[1] - end.ClipCentre[1], 2) +
                std::pow(end.Centre[2] - end.ClipCentre[2], 2)),
      0.05 * end.Radius);
  }
  // Name the second outlet as the inlet, by a point near its cap.
  PrepareForCfdOptions named = first;
  named.Names.push_back({ plain.Ends[2].Centre, "ascending_aorta", true });
  named.Names.push_back({ plain.Ends[0].Centre, "side", false });
  const PrepareForCfdResult r = PrepareForCfd(surface, named);
  ExpectReady(r, 3);
  std::map<std::string, PatchType> types;
  for (const CfdEnd& end : r.Ends)
  {
    types[end.Name] = end.Type;
  }
  EXPECT_EQ(types.at("ascending_aorta"), PatchType::Inlet);
  EXPECT_EQ(types.at("side"), PatchType::Outlet);
  EXPECT_EQ(types.count("outlet_1"), 1u);

  PrepareForCfdOptions open = first;
  open.Cap = false;
  const PrepareForCfdResult o = PrepareForCfd(surface, open);
  EXPECT_EQ(CheckMesh(o.Surface).boundaryLoops.size(), 3u);
  EXPECT_EQ(ReadPatchLabels(o.Surface).size(), 1u);
}

// The application's cuts: an end cut where its disc was dragged (an arc length along the
// end's centerline path) is cut exactly there; the result says where each end was cut, and
// asking for those cuts again gives the same ends; the stages are reported and a set cancel
// flag stops the call.
TEST_F(PrepareForCfdTest, CutsWhereAskedAlongTheCenterlineReportsAndCancels)
{
  auto surface = ReadMesh(Aneurysm);
  const CenterlineResult cl = ComputeCenterlines(surface);
  ASSERT_TRUE(cl.Ok) << cl.Message;
  const std::vector<CenterlineEndPath> paths = FindCenterlineEndPaths(cl.Paths);
  ASSERT_EQ(paths.size(), 3u);
  const CenterlineEndPath& path = paths[1];
  const double d = path.DefaultDistance + 2.0;
  ASSERT_LT(d, path.MaximumDistance);
  PrepareForCfdOptions options;
  options.Centerlines = cl.Paths;
  options.InletExtension = options.OutletExtension = 0.0;
  options.Ends.push_back({ path.Position, d });
  std::vector<std::string> stages;
  ProgressReporter progress;
  progress.onProgress = [&stages](const std::string& stage, double) { stages.push_back(stage); };
  const PrepareForCfdResult r = PrepareForCfd(surface, options, progress);
  ExpectReady(r, 3);
  EXPECT_EQ(stages, (std::vector<std::string>{ "clip", "flow extensions", "caps" }));
  int found = 0;
  for (const CfdEnd& end : r.Ends)
  {
    ASSERT_GE(end.ClipDistance, 0.0);
    if (end.CenterlineEnd != path.Position)
    {
      continue;
    }
    ++found;
    EXPECT_NEAR(end.ClipDistance, d, 1e-12);
    const ClipPlane plane = ClipPlaneAt(path, d);
    const double off = (end.ClipCentre[0] - plane.Centre[0]) * plane.Normal[0] +
      (end.ClipCentre[1] - plane.Centre[1]) * plane.Normal[1] +
      (end.ClipCentre[2] - plane.Centre[2]) * plane.Normal[2];
    EXPECT_LT(std::abs(off), 1e-6 * plane.Radius);
    // The cap (no extension) is the cut.
    EXPECT_LT(std::hypot(end.Centre[0] - end.ClipCentre[0],
                end.Centre[1] - end.ClipCentre[1],
                end.Centre[2] - end.ClipCentre[2]),
      0.05 * end.Radius);
  }
  EXPECT_EQ(found, 1);
  // The cuts as the result says, asked again: the same ends.
  PrepareForCfdOptions again = options;
  again.Ends.clear();
  for (const CfdEnd& end : r.Ends)
  {
    again.Ends.push_back({ end.CenterlineEnd, end.ClipDistance });
  }
  const PrepareForCfdResult same = PrepareForCfd(surface, again);
  ASSERT_EQ(same.Ends.size(), r.Ends.size());
  for (std::size_t k = 0; k < r.Ends.size(); ++k)
  {
    EXPECT_EQ(same.Ends[k].Name, r.Ends[k].Name);
    for (int e = 0; e < 3; ++e)
    {
      EXPECT_NEAR(same.Ends[k].ClipCentre[e], r.Ends[k].ClipCentre[e], 1e-9);
    }
  }
  // Cancelled: nothing returned, the input untouched.
  const vtkIdType points = surface->GetNumberOfPoints();
  std::atomic<bool> cancel{ true };
  ProgressReporter cancelled;
  cancelled.cancel = &cancel;
  EXPECT_THROW(PrepareForCfd(surface, options, cancelled), Cancelled);
  EXPECT_EQ(surface->GetNumberOfPoints(), points);
  // Without Clip no end is cut.
  PrepareForCfdOptions open;
  open.Clip = false;
  open.InletExtension = open.OutletExtension = 0.0;
  for (const CfdEnd& end : PrepareForCfd(surface, open).Ends)
  {
    EXPECT_EQ(end.ClipDistance, -1.0);
  }
}

TEST_F(PrepareForCfdTest, DemoSegmentationGetsThreeEnds)
{
  const DemoVessel demo = SegmentDemoVessel(DemoVesselPath());
  ASSERT_TRUE(CheckMesh(demo.surface).closed);
  PrepareForCfdOptions options;
  options.InputName = "demo segmentation";
  const PrepareForCfdResult r = PrepareForCfd(demo.surface, options);
  ExpectReady(r, 3);
}

TEST_F(PrepareForCfdTest, BadInputsAreOneLineErrors)
{
  auto expectError = [](vtkPolyData* s, const PrepareForCfdOptions& o, const std::string& part)
  {
    try
    {
      PrepareForCfd(s, o);
      ADD_FAILURE() << "no exception for " << part;
    }
    catch (const InputError& e)
    {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("in.stl: ", 0), 0u) << what;
      EXPECT_NE(what.find(part), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  PrepareForCfdOptions options;
  options.InputName = "in.stl";
  vtkNew<vtkPolyData> empty;
  expectError(empty, options, "no triangles");
  // --cap without clipping on a closed surface: no open end.
  const DemoVessel demo = SegmentDemoVessel(DemoVesselPath());
  PrepareForCfdOptions noClip = options;
  noClip.Clip = false;
  expectError(demo.surface, noClip, "no open end to cap");
  // A clip position far from every vessel.
  auto surface = ReadMesh(Aneurysm);
  PrepareForCfdOptions far = options;
  far.Ends.push_back({ { { 500, 500, 500 } }, -1.0 });
  expectError(surface, far, "is not on a vessel");
  // A single open end: a tube closed at one end has one end only.
  PrepareForCfdOptions names = options;
  names.Names.push_back({ { { 0, 0, 0 } }, "bad name", false });
  expectError(surface, names, "invalid end name");
  PrepareForCfdOptions factor = options;
  factor.InletExtension = -1;
  expectError(surface, factor, "not in [0, 100]");
}

// Labels through the application's bend: a labelled tube bent with subdivision at release keeps
// its patches (children inherit their parent's label, the names stay), and undo gives back the
// labels of the unbent surface exactly.
TEST_F(PrepareForCfdTest, LabelsSurviveABendWithSubdivisionUndoAndRedo)
{
  PrepareForCfdOptions options;
  options.Clip = false; // the tube's open ends as they are
  options.InletExtension = options.OutletExtension = 0.0;
  const PrepareForCfdResult prepared = PrepareForCfd(test::MakeTube(0, 60, 3), options);
  ExpectReady(prepared, 2);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(prepared.Surface, "tube"));
  WarpParameters parameters;
  parameters.radius = 6.0;
  parameters.subdivide = true;
  parameters.subdivisionTolerance = 0.01;
  ASSERT_TRUE(session.SetParameters(parameters));
  const RibbonSpec initial = test::StraightRibbon(20, 40);
  ASSERT_TRUE(session.Grab(initial));
  RibbonSpec bent = initial;
  const double a = 40.0 * M_PI / 180.0;
  const Vec3 arm = initial.end.position - initial.start.position;
  bent.end.position = initial.start.position + Rotate({ 0, 0, 1 }, a, arm);
  bent.end.tangent = Rotate({ 0, 0, 1 }, a, initial.end.tangent);
  ASSERT_TRUE(session.MoveFinal(bent));
  ASSERT_TRUE(session.Release());
  vtkPolyData* after = session.GetSurface();
  ASSERT_GT(after->GetNumberOfPolys(), prepared.Surface->GetNumberOfPolys()); // subdivided
  const auto labels = ReadPatchLabels(after);
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[1].name, prepared.Ends[0].Name);
  EXPECT_EQ(labels[2].name, prepared.Ends[1].Name);
  // The caps are far from the bend: their triangles are the same in number.
  std::map<int, int> before, now;
  for (int id : CellPatchIds(prepared.Surface))
  {
    ++before[id];
  }
  for (int id : CellPatchIds(after))
  {
    ++now[id];
  }
  EXPECT_EQ(now[2], before[2]);
  EXPECT_EQ(now[3], before[3]);
  EXPECT_GT(now[1], before[1]);
  MeshCheckOptions check;
  check.requireClosed = true;
  EXPECT_TRUE(CheckMesh(after, nullptr, check).closed);
  ASSERT_TRUE(session.Undo());
  EXPECT_EQ(CellPatchIds(session.GetSurface()), CellPatchIds(prepared.Surface));
  EXPECT_EQ(ReadPatchLabels(session.GetSurface()).size(), 3u);
  ASSERT_TRUE(session.Redo());
  EXPECT_EQ(CellPatchIds(session.GetSurface()), CellPatchIds(after));
  EXPECT_EQ(ReadPatchLabels(session.GetSurface())[1].name, prepared.Ends[0].Name);
}
