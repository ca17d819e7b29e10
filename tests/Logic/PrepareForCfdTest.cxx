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
  const MeshCheckReport report = CheckMesh(r.surface, nullptr, check);
  EXPECT_TRUE(report.Clean()) << FormatReportText(report, "prepared");
  EXPECT_GT(report.volume, 0.0);
  const std::vector<PatchLabel> labels = ReadPatchLabels(r.surface);
  ASSERT_EQ(labels.size(), ends + 1);
  EXPECT_EQ(labels[0].name, "wall");
  ASSERT_EQ(r.ends.size(), ends);
  int inlets = 0;
  for (std::size_t k = 0; k < ends; ++k)
  {
    EXPECT_EQ(r.ends[k].id, static_cast<int>(k) + 2);
    EXPECT_EQ(labels[k + 1].name, r.ends[k].name);
    EXPECT_EQ(labels[k + 1].type, r.ends[k].type);
    inlets += r.ends[k].type == PatchType::Inlet ? 1 : 0;
    EXPECT_NEAR(
      std::hypot(r.ends[k].normal[0], r.ends[k].normal[1], r.ends[k].normal[2]), 1.0, 1e-9);
    EXPECT_GT(r.ends[k].area, 0.0);
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
  options.inputName = "aneurysm_data.stl";
  const PrepareForCfdResult r = PrepareForCfd(surface, options);
  ExpectReady(r, 3);
  EXPECT_EQ(r.ends[0].name, "inlet"); // the largest end
  EXPECT_EQ(r.ends[1].name, "outlet_1");
  EXPECT_EQ(r.ends[2].name, "outlet_2");
  EXPECT_NEAR(r.ends[0].extensionLength, 10.0 * std::sqrt(r.ends[0].area / M_PI), 0.05 * 44);

  // Labels through a VTP round trip.
  const std::string path =
    (std::filesystem::temp_directory_path() / "bender_prepare_for_cfd.vtp").string();
  WriteMesh(r.surface, path);
  auto back = ReadMesh(path);
  std::remove(path.c_str());
  EXPECT_EQ(CellPatchIds(back), CellPatchIds(r.surface));
  const auto labels = ReadPatchLabels(back);
  ASSERT_EQ(labels.size(), 4u);
  EXPECT_EQ(labels[1].name, "inlet");

  // Through a warp and adaptive subdivision: every triangle keeps its parent's label, so the
  // area of each patch is (nearly) unchanged by the subdivision.
  vtkNew<vtkBenderWarpFilter> warp;
  warp->SetInputData(r.surface);
  warp->Update();
  EXPECT_EQ(CellPatchIds(warp->GetOutput()), CellPatchIds(r.surface));
  ASSERT_EQ(ReadPatchLabels(warp->GetOutput()).size(), 4u);
  EXPECT_EQ(ReadPatchLabels(warp->GetOutput())[1].name, "inlet"); // field data passed too
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivide;
  subdivide->SetInputData(r.surface);
  subdivide->Update();
  vtkPolyData* fine = subdivide->GetOutput();
  ASSERT_GE(fine->GetNumberOfPolys(), r.surface->GetNumberOfPolys());
  EXPECT_EQ(ReadPatchLabels(fine).size(), 4u);
  EXPECT_EQ(ReadPatchLabels(fine)[2].name, "outlet_1");
}

TEST_F(PrepareForCfdTest, NamesByPositionNoExtensionNoCap)
{
  auto surface = ReadMesh(Aneurysm);
  PrepareForCfdOptions first;
  first.inletExtension = first.outletExtension = 0.0;
  const PrepareForCfdResult plain = PrepareForCfd(surface, first);
  ExpectReady(plain, 3);
  for (const CfdEnd& end : plain.ends)
  {
    EXPECT_EQ(end.extensionLength, 0.0);
    EXPECT_LT(std::sqrt(std::pow(end.centre[0] - end.clipCentre[0], 2) +
                std::pow(end.centre[1] - end.clipCentre[1], 2) +
                std::pow(end.centre[2] - end.clipCentre[2], 2)),
      0.05 * end.radius);
  }
  // Name the second outlet as the inlet, by a point near its cap.
  PrepareForCfdOptions named = first;
  named.names.push_back({ plain.ends[2].centre, "ascending_aorta", true });
  named.names.push_back({ plain.ends[0].centre, "side", false });
  const PrepareForCfdResult r = PrepareForCfd(surface, named);
  ExpectReady(r, 3);
  std::map<std::string, PatchType> types;
  for (const CfdEnd& end : r.ends)
  {
    types[end.name] = end.type;
  }
  EXPECT_EQ(types.at("ascending_aorta"), PatchType::Inlet);
  EXPECT_EQ(types.at("side"), PatchType::Outlet);
  EXPECT_EQ(types.count("outlet_1"), 1u);

  PrepareForCfdOptions open = first;
  open.cap = false;
  const PrepareForCfdResult o = PrepareForCfd(surface, open);
  EXPECT_EQ(CheckMesh(o.surface).boundaryLoops.size(), 3u);
  EXPECT_EQ(ReadPatchLabels(o.surface).size(), 1u);
}

// The application's cuts: an end cut where its disc was dragged (an arc length along the
// end's centerline path) is cut exactly there; the result says where each end was cut, and
// asking for those cuts again gives the same ends; the stages are reported and a set cancel
// flag stops the call.
TEST_F(PrepareForCfdTest, CutsWhereAskedAlongTheCenterlineReportsAndCancels)
{
  auto surface = ReadMesh(Aneurysm);
  const CenterlineResult cl = ComputeCenterlines(surface);
  ASSERT_TRUE(cl.ok) << cl.message;
  const std::vector<CenterlineEndPath> paths = FindCenterlineEndPaths(cl.paths);
  ASSERT_EQ(paths.size(), 3u);
  const CenterlineEndPath& path = paths[1];
  const double d = path.defaultDistance + 2.0;
  ASSERT_LT(d, path.maximumDistance);
  PrepareForCfdOptions options;
  options.centerlines = cl.paths;
  options.inletExtension = options.outletExtension = 0.0;
  options.ends.push_back({ path.position, d });
  std::vector<std::string> stages;
  ProgressReporter progress;
  progress.onProgress = [&stages](const std::string& stage, double) { stages.push_back(stage); };
  const PrepareForCfdResult r = PrepareForCfd(surface, options, progress);
  ExpectReady(r, 3);
  EXPECT_EQ(stages, (std::vector<std::string>{ "clip", "flow extensions", "caps" }));
  int found = 0;
  for (const CfdEnd& end : r.ends)
  {
    ASSERT_GE(end.clipDistance, 0.0);
    if (end.centerlineEnd != path.position)
    {
      continue;
    }
    ++found;
    EXPECT_NEAR(end.clipDistance, d, 1e-12);
    const ClipPlane plane = ClipPlaneAt(path, d);
    const double off = (end.clipCentre[0] - plane.centre[0]) * plane.normal[0] +
      (end.clipCentre[1] - plane.centre[1]) * plane.normal[1] +
      (end.clipCentre[2] - plane.centre[2]) * plane.normal[2];
    EXPECT_LT(std::abs(off), 1e-6 * plane.radius);
    // The cap (no extension) is the cut.
    EXPECT_LT(std::hypot(end.centre[0] - end.clipCentre[0],
                end.centre[1] - end.clipCentre[1],
                end.centre[2] - end.clipCentre[2]),
      0.05 * end.radius);
  }
  EXPECT_EQ(found, 1);
  // The cuts as the result says, asked again: the same ends.
  PrepareForCfdOptions again = options;
  again.ends.clear();
  for (const CfdEnd& end : r.ends)
  {
    again.ends.push_back({ end.centerlineEnd, end.clipDistance });
  }
  const PrepareForCfdResult same = PrepareForCfd(surface, again);
  ASSERT_EQ(same.ends.size(), r.ends.size());
  for (std::size_t k = 0; k < r.ends.size(); ++k)
  {
    EXPECT_EQ(same.ends[k].name, r.ends[k].name);
    for (int e = 0; e < 3; ++e)
    {
      EXPECT_NEAR(same.ends[k].clipCentre[e], r.ends[k].clipCentre[e], 1e-9);
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
  open.clip = false;
  open.inletExtension = open.outletExtension = 0.0;
  for (const CfdEnd& end : PrepareForCfd(surface, open).ends)
  {
    EXPECT_EQ(end.clipDistance, -1.0);
  }
}

TEST_F(PrepareForCfdTest, DemoSegmentationGetsThreeEnds)
{
  const DemoVessel demo = SegmentDemoVessel(DemoVesselPath());
  ASSERT_TRUE(CheckMesh(demo.surface).closed);
  PrepareForCfdOptions options;
  options.inputName = "demo segmentation";
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
  options.inputName = "in.stl";
  vtkNew<vtkPolyData> empty;
  expectError(empty, options, "no triangles");
  // --cap without clipping on a closed surface: no open end.
  const DemoVessel demo = SegmentDemoVessel(DemoVesselPath());
  PrepareForCfdOptions noClip = options;
  noClip.clip = false;
  expectError(demo.surface, noClip, "no open end to cap");
  // A clip position far from every vessel.
  auto surface = ReadMesh(Aneurysm);
  PrepareForCfdOptions far = options;
  far.ends.push_back({ { { 500, 500, 500 } }, -1.0 });
  expectError(surface, far, "is not on a vessel");
  // A single open end: a tube closed at one end has one end only.
  PrepareForCfdOptions names = options;
  names.names.push_back({ { { 0, 0, 0 } }, "bad name", false });
  expectError(surface, names, "invalid end name");
  PrepareForCfdOptions factor = options;
  factor.inletExtension = -1;
  expectError(surface, factor, "not in [0, 100]");
}

// Labels through the application's bend: a labelled tube bent with subdivision at release keeps
// its patches (children inherit their parent's label, the names stay), and undo gives back the
// labels of the unbent surface exactly.
TEST_F(PrepareForCfdTest, LabelsSurviveABendWithSubdivisionUndoAndRedo)
{
  PrepareForCfdOptions options;
  options.clip = false; // the tube's open ends as they are
  options.inletExtension = options.outletExtension = 0.0;
  const PrepareForCfdResult prepared = PrepareForCfd(test::MakeTube(0, 60, 3), options);
  ExpectReady(prepared, 2);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(prepared.surface, "tube"));
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
  ASSERT_GT(after->GetNumberOfPolys(), prepared.surface->GetNumberOfPolys()); // subdivided
  const auto labels = ReadPatchLabels(after);
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[1].name, prepared.ends[0].name);
  EXPECT_EQ(labels[2].name, prepared.ends[1].name);
  // The caps are far from the bend: their triangles are the same in number.
  std::map<int, int> before, now;
  for (int id : CellPatchIds(prepared.surface))
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
  EXPECT_EQ(CellPatchIds(session.GetSurface()), CellPatchIds(prepared.surface));
  EXPECT_EQ(ReadPatchLabels(session.GetSurface()).size(), 3u);
  ASSERT_TRUE(session.Redo());
  EXPECT_EQ(CellPatchIds(session.GetSurface()), CellPatchIds(after));
  EXPECT_EQ(ReadPatchLabels(session.GetSurface())[1].name, prepared.ends[0].name);
}
