// The Logic workflows bender-cli, the GUI and the headless demo share: ApplyPlan (one rule for
// subdivision), ExportSurface, CheckSurface, RenderToPng (its "no display" contract) and
// RunDemo.

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "CheckSurface.h"
#include "ExportSurface.h"
#include "LogicTestUtilities.h"
#include "MeshIO.h"
#include "RenderToPng.h"
#include "RunDemo.h"
#include "WarpPlanIO.h"
#include "vtkBenderAdaptiveSubdivisionFilter.h"
#include "vtkBenderWarpFilter.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using bender::test::MaxDifference;

namespace
{
const std::string TestData = BENDER_TEST_DATA_DIR;
const std::string External = BENDER_EXTERNAL_DATA_DIR;

vtkSmartPointer<vtkPolyData> Tube()
{
  return bender::ReadMesh(TestData + "/conformance/tube.off");
}

bender::WarpPlan Bend90()
{
  return bender::ReadWarpPlan(TestData + "/conformance/bend90.bender.json");
}

// The tube with float points, as read from an STL file.
vtkSmartPointer<vtkPolyData> FloatTube()
{
  auto tube = Tube();
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(tube);
  vtkNew<vtkPoints> floats;
  floats->SetDataTypeToFloat();
  floats->SetNumberOfPoints(tube->GetNumberOfPoints());
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    floats->SetPoint(i, tube->GetPoint(i));
  }
  copy->SetPoints(floats);
  return copy;
}

class Scratch : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = fs::temp_directory_path() /
      ("bender-workflows-" + std::to_string(::getpid()) + "-" +
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(this->Dir);
    fs::create_directories(this->Dir);
  }
  void TearDown() override
  {
    std::error_code ignored;
    fs::remove_all(this->Dir, ignored);
  }
  std::string Tmp(const std::string& name) const { return (this->Dir / name).string(); }
  fs::path Dir;
};
} // namespace

// --- ApplyPlan ------------------------------------------------------------------------------

TEST(ApplyPlan, WithoutSubdivisionItIsTheWarpFilterInDouble)
{
  const auto tube = FloatTube();
  const bender::WarpPlan plan = Bend90();
  const bender::ApplyPlanResult result = bender::ApplyPlan(tube, plan);
  ASSERT_EQ(result.steps.size(), plan.warps.size());
  ASSERT_EQ(result.info.size(), plan.warps.size());
  EXPECT_EQ(result.output->GetPoints()->GetDataType(), VTK_DOUBLE) << "float input, double out";
  EXPECT_FALSE(result.info[0].subdivided);
  EXPECT_GT(result.info[0].boundPoints, 0);
  EXPECT_EQ(result.output->GetNumberOfPolys(), tube->GetNumberOfPolys());
  EXPECT_EQ(tube->GetPoints()->GetDataType(), VTK_FLOAT) << "the input is not modified";

  // The warp filter itself on the same double points.
  auto doubles = vtkSmartPointer<vtkPolyData>::New();
  doubles->DeepCopy(tube);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->DeepCopy(tube->GetPoints());
  doubles->SetPoints(points);
  vtkNew<vtkBenderWarpFilter> filter;
  filter->SetInputData(doubles);
  filter->SetWarp(plan.warps[0]);
  filter->Update();
  EXPECT_EQ(MaxDifference(result.steps[0], filter->GetOutput()), 0.0);
}

TEST(ApplyPlan, ASubdivisionObjectMeansTheSubdivisionFilterAloneEvenWithZeroPasses)
{
  const auto tube = FloatTube();
  bender::WarpPlan plan = Bend90();
  plan.warps.resize(1);
  plan.warps[0].subdivision = bender::SubdivisionSpec{ 0.01, 0 };
  const auto zeroPasses = bender::ApplyPlan(tube, plan);
  EXPECT_TRUE(zeroPasses.info[0].subdivided);
  EXPECT_EQ(zeroPasses.info[0].passesRun, 0);
  EXPECT_EQ(zeroPasses.output->GetPoints()->GetDataType(), VTK_DOUBLE);

  // Exactly the subdivision filter's output (the warp is evaluated once, by that filter).
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivide;
  auto doubles = vtkSmartPointer<vtkPolyData>::New();
  doubles->DeepCopy(tube);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->DeepCopy(tube->GetPoints());
  doubles->SetPoints(points);
  subdivide->SetInputData(doubles);
  subdivide->SetWarp(plan.warps[0]);
  subdivide->Update();
  EXPECT_EQ(MaxDifference(zeroPasses.output, subdivide->GetOutput()), 0.0);

  plan.warps[0].subdivision = bender::SubdivisionSpec{ 0.01, 4 };
  const auto refined = bender::ApplyPlan(tube, plan);
  EXPECT_GT(refined.info[0].passesRun, 0);
  EXPECT_GT(refined.output->GetNumberOfPolys(), tube->GetNumberOfPolys());
  EXPECT_EQ(refined.info[0].trianglesAfter, refined.output->GetNumberOfPolys());
}

TEST(ApplyPlan, AnInvalidWarpIsATypedErrorNamingItAndNothingIsReturned)
{
  bender::WarpPlan plan = Bend90();
  plan.warps.push_back(plan.warps[0]);
  plan.warps[1].radius = -1.0;
  bender::ApplyPlanOptions options;
  options.planName = "broken.bender.json";
  try
  {
    bender::ApplyPlan(Tube(), plan, options);
    FAIL() << "a negative radius was applied";
  }
  catch (const bender::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("broken.bender.json: warps[1]"), std::string::npos)
      << e.what();
  }
}

TEST(ApplyPlan, CancellationIsATypedException)
{
  std::atomic<bool> cancel{ true };
  bender::ApplyPlanOptions options;
  options.progress.cancel = &cancel;
  EXPECT_THROW(bender::ApplyPlan(Tube(), Bend90(), options), bender::Cancelled);
  EXPECT_THROW(bender::ApplyWarp(Tube(), Bend90().warps[0], options), bender::Cancelled);
  cancel = false;
  EXPECT_NO_THROW(bender::ApplyPlan(Tube(), Bend90(), options));
}

// --- ExportSurface and CheckSurface ---------------------------------------------------------

TEST_F(Scratch, ExportSurfaceWritesTheFrameItIsAskedFor)
{
  const auto tube = Tube();
  bender::ExportSurfaceOptions options;
  options.output = this->Tmp("lps.vtp");
  ASSERT_EQ(bender::ExportSurface(tube, options).written.size(), 1u);
  options.output = this->Tmp("ras.vtp");
  options.frame = bender::StlFrame::RAS;
  bender::ExportSurface(tube, options);
  // The file in RAS says so, and reads back where the LPS one is (negated twice, exactly).
  const auto lps = bender::ReadMesh(this->Tmp("lps.vtp"));
  bender::StatedSpace stated;
  const auto ras = bender::ReadMesh(this->Tmp("ras.vtp"), stated);
  EXPECT_EQ(stated.frame, "RAS");
  ASSERT_EQ(lps->GetNumberOfPoints(), ras->GetNumberOfPoints());
  EXPECT_EQ(MaxDifference(lps, ras), 0.0);
  // STL: the frame is in the 80-byte header, and the file holds x and y negated (the first
  // triangle's first vertex, after the header, the count and the normal).
  options.output = this->Tmp("ras.stl");
  bender::ExportSurface(tube, options);
  std::ifstream stl(options.output, std::ios::binary);
  std::string header(80, '\0');
  stl.read(&header[0], 80);
  EXPECT_NE(header.find("frame RAS, unit mm"), std::string::npos) << header;
  float vertex[3];
  stl.seekg(80 + 4 + 12);
  stl.read(reinterpret_cast<char*>(vertex), sizeof vertex);
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  tube->GetPolys()->InitTraversal();
  ASSERT_TRUE(tube->GetPolys()->GetNextCell(npts, ids));
  double p[3];
  tube->GetPoint(ids[0], p);
  EXPECT_FLOAT_EQ(vertex[0], static_cast<float>(-p[0]));
  EXPECT_FLOAT_EQ(vertex[1], static_cast<float>(-p[1]));
  EXPECT_FLOAT_EQ(vertex[2], static_cast<float>(p[2]));
}

TEST_F(Scratch, ExportSurfaceRefusesTheProtectedInputAndPatchesOutsideStl)
{
  const auto tube = Tube();
  const std::string input = this->Tmp("input.stl");
  bender::WriteMesh(tube, input);
  const auto sizeBefore = fs::file_size(input);
  bender::ExportSurfaceOptions options;
  options.output = input;
  options.protectedPath = input;
  EXPECT_THROW(bender::ExportSurface(tube, options), bender::InputError);
  EXPECT_EQ(fs::file_size(input), sizeBefore);
  // One file per patch: input_wall.stl would be the protected file.
  const std::string wall = this->Tmp("v_wall.stl");
  bender::WriteMesh(tube, wall);
  options.output = this->Tmp("v.stl");
  options.protectedPath = wall;
  options.patches = bender::StlPatchMode::Files;
  EXPECT_THROW(bender::ExportSurface(tube, options), bender::InputError);
  options.output = this->Tmp("v.vtp");
  options.protectedPath.clear();
  EXPECT_THROW(bender::ExportSurface(tube, options), bender::InputError);
  EXPECT_FALSE(fs::exists(this->Tmp("v.vtp")));
}

TEST_F(Scratch, CheckSurfaceReadsAndReportsOrNamesTheFile)
{
  bender::CheckSurfaceOptions options;
  options.input = TestData + "/conformance/tube.off";
  const bender::MeshCheckReport report = bender::CheckSurface(options);
  EXPECT_EQ(report.triangles, Tube()->GetNumberOfPolys());
  options.input = this->Tmp("missing.stl");
  try
  {
    bender::CheckSurface(options);
    FAIL() << "a missing file was checked";
  }
  catch (const bender::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("missing.stl"), std::string::npos) << e.what();
  }
}

// --- RenderToPng: one clear line when it cannot render ----------------------------------------

TEST_F(Scratch, RenderWithoutDisplayIsAnEnvironmentErrorAndWritesNothing)
{
  // The modules never start an X server (the application does: HeadlessDisplay).
  const char* before = std::getenv("DISPLAY");
  const std::string display = before ? before : "";
  ::unsetenv("DISPLAY");
  bender::RenderToPngOptions options;
  options.output = this->Tmp("out.png");
  try
  {
    bender::RenderToPng(Tube(), options);
    FAIL() << "rendered without a display";
  }
  catch (const bender::EnvironmentError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("DISPLAY"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
  }
  EXPECT_TRUE(fs::is_empty(this->Dir));
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr) << "no server was started, DISPLAY stays unset";
  if (!display.empty())
  {
    ::setenv("DISPLAY", display.c_str(), 1);
  }
}

TEST(RenderToPng, BadOptionsAreInputErrors)
{
  bender::RenderToPngOptions options;
  options.output = "/tmp/never.png";
  options.width = 4;
  EXPECT_THROW(bender::RenderToPng(Tube(), options), bender::InputError);
  options.width = 64;
  EXPECT_THROW(bender::RenderToPng(vtkNew<vtkPolyData>(), options), bender::InputError);
  bender::RenderView view;
  EXPECT_TRUE(bender::ParseRenderView("top", view));
  EXPECT_EQ(view, bender::RenderView::Top);
  EXPECT_FALSE(bender::ParseRenderView("sideways", view));
}

// --- RunDemo --------------------------------------------------------------------------------

TEST_F(Scratch, TheDemoJobBendsTheVesselAndWritesItsFiles)
{
  const std::string vessel = External + "/aneurysm_data.stl";
  ASSERT_TRUE(fs::exists(vessel)) << vessel << " missing: run scripts/fetch-data";
  bender::RunDemoOptions options;
  options.outputDirectory = this->Tmp("demo");
  options.segment = false; // the segmentation has its own tests; this is the job around it
  options.screenshot = false;
  options.vesselPath = vessel;
  options.planPath = std::string(BENDER_SOURCE_DIR) + "/data/demo/demo.bender.json";
  int lines = 0;
  options.onMessage = [&lines](const std::string&, bool) { ++lines; };
  const bender::RunDemoResult result = bender::RunDemo(options);
  EXPECT_GT(lines, 0);
  for (const char* name :
    { "demo-bent.stl", "demo-bent.vtp", "demo-plan.bender.json", "demo-check.txt" })
  {
    EXPECT_TRUE(fs::exists(this->Tmp(std::string("demo/") + name))) << name;
  }
  // The exported surface is the plan applied to the vessel, exactly (VTP keeps doubles).
  const auto bent = bender::ReadMesh(this->Tmp("demo/demo-bent.vtp"));
  const auto expected =
    bender::ApplyPlan(bender::ReadMesh(vessel), bender::ReadWarpPlan(options.planPath)).output;
  EXPECT_EQ(MaxDifference(bent, expected), 0.0);
  EXPECT_GT(MaxDifference(bent, bender::ReadMesh(vessel)), 0.0) << "the demo plan bends the vessel";
  // The saved plan is the demo plan.
  EXPECT_EQ(bender::ReadWarpPlan(this->Tmp("demo/demo-plan.bender.json")).warps.size(),
    bender::ReadWarpPlan(options.planPath).warps.size());

  options.planPath = this->Tmp("missing.bender.json");
  EXPECT_THROW(bender::RunDemo(options), bender::InputError);
}
