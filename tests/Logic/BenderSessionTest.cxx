// The application state machine: grab, live moves, release, undo/redo with exact coordinates,
// plan save/load/replay, export, autosave and recovery, and bad input turned into messages.
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "WarpPlanIO.h"

#include <vtkCellData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

using namespace bender;
using bender::test::Bent;
using bender::test::MakeTube;
using bender::test::MaxDifference;
using bender::test::StraightRibbon;

namespace
{

bool HasMessage(const BenderSession& session, MessageSeverity severity, const std::string& part)
{
  for (const auto& message : session.GetMessages())
  {
    if (message.severity == severity && message.text.find(part) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

class BenderSessionTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Tube = MakeTube(0, 60, 3);
    ASSERT_TRUE(this->Session.SetSurface(this->Tube, "tube"));
    WarpParameters parameters;
    parameters.radius = 6.0;
    ASSERT_TRUE(this->Session.SetParameters(parameters));
  }

  // One grab - several moves - release gesture bending the tube's middle.
  void Bend(double degrees)
  {
    const RibbonSpec initial = StraightRibbon(20, 40);
    ASSERT_TRUE(this->Session.Grab(initial));
    for (int step = 1; step <= 4; ++step)
    {
      ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, degrees * step / 4.0)));
    }
    ASSERT_TRUE(this->Session.Release());
  }

  BenderSession Session;
  vtkSmartPointer<vtkPolyData> Tube;
};

}

TEST_F(BenderSessionTest, GrabMoveReleaseMovesOnlyInsideTheRegionOfInfluence)
{
  EXPECT_EQ(this->Session.GetState(), GrabState::Idle);
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  EXPECT_EQ(this->Session.GetState(), GrabState::Grabbed);
  EXPECT_GT(this->Session.GetNumberOfBoundPoints(), 0);
  EXPECT_FALSE(this->Session.CanUndo());

  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 30)));
  // The live display moved, the committed surface did not.
  EXPECT_GT(MaxDifference(this->Session.GetDisplaySurface(), this->Tube), 1.0);
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), this->Tube), 0.0);

  ASSERT_TRUE(this->Session.Release());
  EXPECT_EQ(this->Session.GetState(), GrabState::Released);
  EXPECT_EQ(this->Session.GetHistoryPosition(), 1u);
  ASSERT_EQ(this->Session.GetPlan().warps.size(), 1u);

  vtkPolyData* after = this->Session.GetSurface();
  ASSERT_EQ(after->GetNumberOfPoints(), this->Tube->GetNumberOfPoints());
  int movedInside = 0;
  for (vtkIdType i = 0; i < after->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    this->Tube->GetPoint(i, p);
    after->GetPoint(i, q);
    const double moved = std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
    const double d = test::DistanceToWire(initial, { p[0], p[1], p[2] });
    if (d >= 6.0 * (1 + 1e-6))
    {
      ASSERT_EQ(moved, 0.0) << "point " << i << " at distance " << d << " moved";
    }
    else if (moved > 1e-3)
    {
      ++movedInside;
    }
  }
  EXPECT_GT(movedInside, 100);
  // The committed shape is the exact warp, the display shows it.
  EXPECT_EQ(MaxDifference(this->Session.GetDisplaySurface(), after), 0.0);
}

TEST_F(BenderSessionTest, UndoAndRedoRestoreExactCoordinates)
{
  this->Bend(40);
  vtkNew<vtkPolyData> afterFirst;
  afterFirst->DeepCopy(this->Session.GetSurface());
  this->Bend(-25);
  vtkNew<vtkPolyData> afterSecond;
  afterSecond->DeepCopy(this->Session.GetSurface());
  EXPECT_GT(MaxDifference(afterFirst, afterSecond), 0.1);

  ASSERT_TRUE(this->Session.Undo());
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), afterFirst), 0.0);
  EXPECT_EQ(MaxDifference(this->Session.GetDisplaySurface(), afterFirst), 0.0);
  ASSERT_TRUE(this->Session.Undo());
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), this->Tube), 0.0);
  EXPECT_FALSE(this->Session.Undo());
  EXPECT_EQ(this->Session.GetPlan().warps.size(), 0u);

  ASSERT_TRUE(this->Session.Redo());
  ASSERT_TRUE(this->Session.Redo());
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), afterSecond), 0.0);
  EXPECT_FALSE(this->Session.Redo());
  EXPECT_EQ(this->Session.GetPlan().warps.size(), 2u);

  // A new warp after an undo drops the redo step.
  ASSERT_TRUE(this->Session.Undo());
  this->Bend(10);
  EXPECT_FALSE(this->Session.CanRedo());
  EXPECT_EQ(this->Session.GetPlan().warps.size(), 2u);
}

// Issue 25: past the history's memory limit the oldest steps cannot be undone; the session
// says why, and the plan keeps every warp.
TEST_F(BenderSessionTest, UndoPastTheHistoryLimitSaysWhyAndThePlanKeepsEveryWarp)
{
  this->Session.SetHistoryMemoryLimit(0);
  this->Session.SetCommitGuard(false); // the history is tested here, not the bends
  for (const double degrees : { 20.0, -20.0, 20.0, -20.0 })
  {
    this->Bend(degrees);
  }
  ASSERT_TRUE(this->Session.Undo());
  EXPECT_FALSE(this->Session.CanUndo());
  EXPECT_FALSE(this->Session.Undo());
  const std::string said = this->Session.GetMessages().back().text;
  EXPECT_NE(said.find("let go"), std::string::npos) << said;
  EXPECT_NE(said.find("3 older steps"), std::string::npos) << said;
  ASSERT_TRUE(this->Session.Redo());
  EXPECT_EQ(this->Session.GetPlan().warps.size(), 4u);
}

TEST_F(BenderSessionTest, UndoIsRefusedWhileGrabbed)
{
  this->Bend(30);
  ASSERT_TRUE(this->Session.Grab(StraightRibbon(5, 15)));
  EXPECT_FALSE(this->Session.CanUndo());
  EXPECT_FALSE(this->Session.Undo());
  EXPECT_TRUE(HasMessage(this->Session, MessageSeverity::Error, "release or cancel"));
  this->Session.CancelGrab("test");
  EXPECT_EQ(this->Session.GetState(), GrabState::Idle);
  EXPECT_TRUE(this->Session.Undo());
}

TEST_F(BenderSessionTest, InvalidRibbonsAreNeverApplied)
{
  RibbonSpec coincident = StraightRibbon(20, 20);
  EXPECT_FALSE(this->Session.Grab(coincident));
  EXPECT_EQ(this->Session.GetState(), GrabState::Idle);
  EXPECT_TRUE(HasMessage(this->Session, MessageSeverity::Error, "Grab refused"));

  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 20)));
  vtkNew<vtkPolyData> lastValid;
  lastValid->DeepCopy(this->Session.GetDisplaySurface());

  RibbonSpec collapsed = initial;
  collapsed.end.position = collapsed.start.position;
  EXPECT_FALSE(this->Session.MoveFinal(collapsed));
  EXPECT_FALSE(this->Session.GetLiveProblem().empty());
  EXPECT_EQ(MaxDifference(this->Session.GetDisplaySurface(), lastValid), 0.0);

  RibbonSpec notFinite = initial;
  notFinite.end.position.x = std::nan("");
  EXPECT_FALSE(this->Session.MoveFinal(notFinite));
  EXPECT_EQ(MaxDifference(this->Session.GetDisplaySurface(), lastValid), 0.0);

  // The release commits the last valid ribbon.
  ASSERT_TRUE(this->Session.Release());
  EXPECT_LT(MaxDifference(this->Session.GetSurface(), lastValid), 1e-4);
}

TEST_F(BenderSessionTest, TwistIsUnwrappedAcrossHalfTurns)
{
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  // Roll the end normal by 270 degrees in 10-degree steps.
  for (int degrees = 10; degrees <= 270; degrees += 10)
  {
    RibbonSpec rolled = initial;
    rolled.end.normal = Rotate({ 1, 0, 0 }, degrees * 3.14159265358979323846 / 180.0, { 0, 0, 1 });
    ASSERT_TRUE(this->Session.MoveFinal(rolled))
      << degrees << ": " << this->Session.GetLiveProblem();
  }
  EXPECT_EQ(this->Session.GetFinalRibbon().extraTurns, 1);
  ASSERT_TRUE(this->Session.Release());
  EXPECT_EQ(this->Session.GetPlan().warps[0].final.extraTurns, 1);
  EXPECT_EQ(this->Session.GetPlan().warps[0].initial.extraTurns, 0);
}

TEST_F(BenderSessionTest, ReleaseWithoutMotionRecordsNothing)
{
  ASSERT_TRUE(this->Session.Grab(StraightRibbon(20, 40)));
  ASSERT_TRUE(this->Session.Release());
  EXPECT_EQ(this->Session.GetHistoryPosition(), 0u);
  EXPECT_FALSE(this->Session.Release());
}

TEST_F(BenderSessionTest, SubdivisionAtReleaseRefinesTheBend)
{
  WarpParameters parameters = this->Session.GetParameters();
  parameters.subdivide = true;
  parameters.subdivisionTolerance = 0.01;
  ASSERT_TRUE(this->Session.SetParameters(parameters));
  this->Bend(60);
  EXPECT_GT(this->Session.GetSurface()->GetNumberOfPolys(), this->Tube->GetNumberOfPolys());
  ASSERT_TRUE(this->Session.GetPlan().warps[0].subdivision.has_value());
  ASSERT_TRUE(this->Session.Undo());
  EXPECT_EQ(this->Session.GetSurface()->GetNumberOfPolys(), this->Tube->GetNumberOfPolys());
}

TEST_F(BenderSessionTest, BadParametersAreRefused)
{
  WarpParameters parameters;
  parameters.radius = -1;
  EXPECT_FALSE(this->Session.SetParameters(parameters));
  parameters.radius = 5;
  parameters.decay.plateau = 2;
  EXPECT_FALSE(this->Session.SetParameters(parameters));
  EXPECT_EQ(this->Session.GetParameters().radius, 6.0);
}

TEST_F(BenderSessionTest, PlanSaveLoadReplayGivesTheSameSurface)
{
  this->Bend(35);
  this->Bend(-20);
  vtkNew<vtkPolyData> bent;
  bent->DeepCopy(this->Session.GetSurface());
  const std::string folder = test::TemporaryFolder("plan");
  const std::string planPath = folder + "/plan.bender.json";
  ASSERT_TRUE(this->Session.SavePlan(planPath));
  EXPECT_EQ(ReadWarpPlan(planPath).warps.size(), 2u);

  BenderSession other;
  ASSERT_TRUE(other.SetSurface(this->Tube, "tube"));
  ASSERT_TRUE(other.LoadPlan(planPath));
  EXPECT_EQ(other.GetHistoryPosition(), 2u);
  EXPECT_LE(MaxDifference(other.GetSurface(), bent), 1e-12);
  // Each replayed warp is an undo step.
  ASSERT_TRUE(other.Undo());
  ASSERT_TRUE(other.Undo());
  EXPECT_EQ(MaxDifference(other.GetSurface(), this->Tube), 0.0);
}

TEST_F(BenderSessionTest, ReplayIsAllOrNothing)
{
  WarpPlan plan;
  WarpSpec good;
  good.initial = StraightRibbon(20, 40);
  good.final = Bent(good.initial, 30);
  good.radius = 6;
  WarpSpec bad = good;
  bad.final.end.position = bad.final.start.position;
  plan.warps = { good, bad };
  EXPECT_FALSE(this->Session.ReplayPlan(plan, "bad.bender.json"));
  EXPECT_TRUE(HasMessage(this->Session, MessageSeverity::Error, "bad.bender.json: warps[1]"));
  EXPECT_EQ(this->Session.GetHistoryPosition(), 0u);
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), this->Tube), 0.0);
}

TEST_F(BenderSessionTest, CorruptFilesGiveMessagesAndKeepTheSurface)
{
  const std::string folder = test::TemporaryFolder("corrupt");
  {
    std::ofstream out(folder + "/broken.stl");
    out << "solid broken\nfacet normal 0 0 1\n outer loop\n vertex 0 0\n";
  }
  EXPECT_FALSE(this->Session.LoadSurface(folder + "/broken.stl"));
  EXPECT_TRUE(HasMessage(this->Session, MessageSeverity::Error, "broken.stl"));
  EXPECT_FALSE(this->Session.LoadSurface(folder + "/missing.vtp"));
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), this->Tube), 0.0);

  {
    std::ofstream out(folder + "/broken.bender.json");
    out << "{\"format\": \"bender-warps\", \"version\": 7, \"warps\": []}";
  }
  EXPECT_FALSE(this->Session.LoadPlan(folder + "/broken.bender.json"));
  EXPECT_TRUE(HasMessage(this->Session, MessageSeverity::Error, "broken.bender.json"));
}

TEST_F(BenderSessionTest, ExportWritesACheckedFileAndNeverTheSource)
{
  this->Bend(30);
  const MeshCheckReport report = this->Session.CheckSurface();
  EXPECT_EQ(report.triangles, this->Tube->GetNumberOfPolys());
  EXPECT_TRUE(report.flipsChecked);
  EXPECT_EQ(report.flippedTriangles, 0);
  EXPECT_EQ(report.nonManifoldEdges, 0);

  const std::string folder = test::TemporaryFolder("export");
  for (const char* name : { "bent.stl", "bent.vtp", "bent.ply", "bent.obj" })
  {
    ASSERT_TRUE(this->Session.Export(folder + "/" + name)) << name;
    auto back = ReadMesh(folder + "/" + name);
    EXPECT_EQ(back->GetNumberOfPolys(), this->Tube->GetNumberOfPolys()) << name;
  }
  ExportSurfaceOptions ascii;
  ascii.stlEncoding = StlEncoding::Ascii;
  ASSERT_TRUE(this->Session.Export(folder + "/ascii.stl", ascii));
  // The frame and unit are stated in the file.
  std::ifstream in(folder + "/ascii.stl");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("frame LPS"), std::string::npos) << text.substr(0, 200);

  // The loaded source is never overwritten.
  BenderSession fromFile;
  WriteMesh(this->Tube, folder + "/source.vtp");
  ASSERT_TRUE(fromFile.LoadSurface(folder + "/source.vtp"));
  EXPECT_FALSE(fromFile.Export(folder + "/source.vtp"));
  EXPECT_TRUE(HasMessage(fromFile, MessageSeverity::Error, "refusing to overwrite"));
  EXPECT_FALSE(fromFile.Export(folder + "/no-such-folder/x.stl"));
}

TEST_F(BenderSessionTest, ExportCapsTheOpenEndsIntoNamedPatchesForCfd)
{
  this->Bend(30);
  const std::string folder = test::TemporaryFolder("export-cfd");
  ExportSurfaceOptions cfd;
  cfd.cap = true;
  cfd.patches = StlPatchMode::Solids;
  ASSERT_TRUE(this->Session.Export(folder + "/vessel.stl", cfd));
  std::ifstream in(folder + "/vessel.stl");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The patch names of the labels (PatchLabels.h): the wall, the largest end the inlet.
  for (const char* solid : { "solid wall", "solid inlet", "solid outlet_1" })
  {
    EXPECT_NE(text.find(solid), std::string::npos) << solid;
  }
  EXPECT_EQ(text.find("solid outlet_2"), std::string::npos) << "the tube has two open ends";

  // The labelled VTP reassembles into a closed, consistently oriented surface.
  ExportSurfaceOptions vtp;
  vtp.cap = true;
  ASSERT_TRUE(this->Session.Export(folder + "/vessel.vtp", vtp));
  auto capped = ReadMesh(folder + "/vessel.vtp");
  ASSERT_TRUE(HasPatchLabels(capped));
  ASSERT_NE(capped->GetCellData()->GetArray("CellEntityIds"), nullptr);
  MeshCheckOptions closed;
  closed.requireClosed = true;
  const MeshCheckReport report = CheckMesh(capped, nullptr, closed);
  EXPECT_TRUE(report.Clean()) << FormatReportText(report, "vessel.vtp");
  EXPECT_GT(report.volume, 0.0);

  // One file per patch, and RAS coordinates (x and y negated).
  ExportSurfaceOptions files;
  files.cap = true;
  files.patches = StlPatchMode::Files;
  ASSERT_TRUE(this->Session.Export(folder + "/parts.stl", files));
  int parts = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
  {
    parts += entry.path().filename().string().rfind("parts_", 0) == 0 ? 1 : 0;
  }
  EXPECT_EQ(parts, 3);
  ExportSurfaceOptions ras;
  ras.frame = StlFrame::RAS;
  ASSERT_TRUE(this->Session.Export(folder + "/ras.vtp", ras));
  // The file is in RAS and says so; read back, it is in LPS where the session's surface is.
  auto lps = this->Session.GetSurface();
  StatedSpace stated;
  auto back = ReadMesh(folder + "/ras.vtp", stated);
  EXPECT_EQ(stated.frame, "RAS");
  double a[3], b[3];
  lps->GetPoint(5, a);
  back->GetPoint(5, b);
  EXPECT_DOUBLE_EQ(b[0], a[0]);
  EXPECT_DOUBLE_EQ(b[1], a[1]);
  EXPECT_DOUBLE_EQ(b[2], a[2]);
}

TEST_F(BenderSessionTest, AutosaveRecoversAfterACrash)
{
  const std::string folder = test::TemporaryFolder("autosave");
  const std::string autosave = folder + "/autosave.bender-session.json";
  vtkNew<vtkPolyData> bent;
  {
    // A session made from memory (a segmented surface): its source is kept beside the file.
    BenderSession crashed;
    crashed.SetAutosavePath(autosave);
    ASSERT_TRUE(crashed.SetSurface(this->Tube, "segmented"));
    WarpParameters parameters;
    parameters.radius = 6;
    crashed.SetParameters(parameters);
    const RibbonSpec initial = StraightRibbon(20, 40);
    ASSERT_TRUE(crashed.Grab(initial));
    ASSERT_TRUE(crashed.MoveFinal(Bent(initial, 45)));
    ASSERT_TRUE(crashed.Release());
    bent->DeepCopy(crashed.GetSurface());
    ASSERT_TRUE(std::filesystem::exists(autosave));
    // No DiscardAutosave: the process "crashes" here.
  }
  BenderSession recovered;
  recovered.SetAutosavePath(autosave);
  ASSERT_TRUE(recovered.Recover(autosave));
  EXPECT_EQ(recovered.GetHistoryPosition(), 1u);
  EXPECT_LE(MaxDifference(recovered.GetSurface(), bent), 1e-12);
  // Named as before the crash, not after the autosave's copy of the surface.
  EXPECT_EQ(recovered.GetSurfaceName(), "segmented");
  // Recovered warps are in no saved plan.
  EXPECT_TRUE(recovered.HasUnsavedChanges());
  ASSERT_TRUE(recovered.Undo());
  EXPECT_EQ(MaxDifference(recovered.GetSurface(), this->Tube), 0.0);
  recovered.DiscardAutosave();
  EXPECT_FALSE(std::filesystem::exists(autosave));

  // A broken session file gives a message, not a crash.
  {
    std::ofstream out(folder + "/bad.json");
    out << "{\"format\": \"bender-session\", \"version\": 1}";
  }
  BenderSession bad;
  EXPECT_FALSE(bad.Recover(folder + "/bad.json"));
  EXPECT_TRUE(HasMessage(bad, MessageSeverity::Error, "source"));
}

TEST_F(BenderSessionTest, SpaceInversionRiskIsReportedAndRadiusChangesRebind)
{
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  EXPECT_FALSE(this->Session.GetSpaceInversionRisk());
  const long long boundAt6 = this->Session.GetNumberOfBoundPoints();
  // A sharp final bend: its wire's r_min falls below R.
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 150)));
  EXPECT_TRUE(this->Session.GetSpaceInversionRisk());
  EXPECT_FALSE(this->Session.GetSpaceInversionWarning().empty());
  EXPECT_TRUE(HasMessage(this->Session, MessageSeverity::Warning, ""));
  // A larger R while grabbed rebinds at once: more points inside the region.
  WarpParameters parameters = this->Session.GetParameters();
  parameters.radius = 12;
  ASSERT_TRUE(this->Session.SetParameters(parameters));
  EXPECT_GT(this->Session.GetNumberOfBoundPoints(), boundAt6);
  // The commit guard (with the rule on) holds the risky warp; the user keeps it.
  this->Session.SetCommitGuardRule(true);
  EXPECT_FALSE(this->Session.Release());
  ASSERT_TRUE(this->Session.IsCommitHeld());
  EXPECT_TRUE(this->Session.GetHeldCheck().spaceInversionRisk);
  ASSERT_TRUE(this->Session.KeepHeldCommit());
  EXPECT_EQ(this->Session.GetPlan().warps[0].radius, 12.0);
}

// Issue 9: the live warp is a pipeline, History.Current() -> warp filter -> output port. A drag
// builds the warp once per move (in the session, shared with the filter), never copies the
// surface, and the committed surface is passed through untouched when nothing is grabbed.
TEST_F(BenderSessionTest, ADragCopiesNoSurfaceAndBuildsTheWarpOncePerMove)
{
  vtkPolyData* committed = this->Session.GetSurface();
  vtkPoints* committedPoints = committed->GetPoints();
  const vtkMTimeType committedTime = committedPoints->GetMTime();
  // Nothing grabbed: the output shares the committed points.
  EXPECT_EQ(this->Session.GetDisplaySurface()->GetPoints(), committedPoints);
  ASSERT_NE(this->Session.GetOutputPort(), nullptr);

  vtkBenderWarpFilter* filter = this->Session.GetLiveFilter();
  const long long buildsBefore = this->Session.GetWarpBuildCount();
  const vtkIdType copiesBefore = filter->GetPointsCopyCount();
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  EXPECT_EQ(this->Session.GetWarpBuildCount(), buildsBefore + 1);
  vtkPoints* livePoints = this->Session.GetDisplaySurface()->GetPoints();
  ASSERT_NE(livePoints, committedPoints);
  const int moves = 12;
  for (int step = 1; step <= moves; ++step)
  {
    ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 3.0 * step)));
    vtkPolyData* live = this->Session.GetDisplaySurface();
    // Same output points array, written in place; the committed surface is not touched.
    EXPECT_EQ(live->GetPoints(), livePoints);
    EXPECT_EQ(this->Session.GetSurface(), committed);
    EXPECT_EQ(committed->GetPoints(), committedPoints);
    EXPECT_EQ(committedPoints->GetMTime(), committedTime);
  }
  // One warp built per move (plus the grab's), none by the filter itself.
  EXPECT_EQ(this->Session.GetWarpBuildCount(), buildsBefore + 1 + moves);
  EXPECT_EQ(filter->GetWarpBuildCount(), 0);
  // The points were copied into the output once, at the grab's binding, not per move.
  EXPECT_EQ(filter->GetPointsCopyCount(), copiesBefore + 1);
  EXPECT_EQ(filter->GetBindingCount(), 1);
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), this->Tube), 0.0);
  EXPECT_GT(MaxDifference(this->Session.GetDisplaySurface(), this->Tube), 1.0);

  // A refused move builds at most once (to validate) and changes nothing.
  RibbonSpec bad = Bent(initial, 36.0);
  bad.end.position = bad.start.position;
  vtkNew<vtkPolyData> lastValid;
  lastValid->DeepCopy(this->Session.GetDisplaySurface());
  EXPECT_FALSE(this->Session.MoveFinal(bad));
  EXPECT_LE(this->Session.GetWarpBuildCount(), buildsBefore + 2 + moves);
  EXPECT_FALSE(this->Session.GetLiveProblem().empty());
  EXPECT_EQ(MaxDifference(this->Session.GetDisplaySurface(), lastValid), 0.0);

  ASSERT_TRUE(this->Session.Release());
  // Committed: passed through again, the new step's own points.
  EXPECT_EQ(
    this->Session.GetDisplaySurface()->GetPoints(), this->Session.GetSurface()->GetPoints());
}

// Release, replay and export as jobs: begun on the session's thread, run on another, finished
// back; the session refuses changes meanwhile; the same result as the synchronous calls.
TEST_F(BenderSessionTest, JobsRunOffTheSessionThreadWithTheSameResult)
{
  BenderSession reference;
  ASSERT_TRUE(reference.SetSurface(this->Tube, "tube"));
  ASSERT_TRUE(reference.SetParameters(this->Session.GetParameters()));
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(reference.Grab(initial));
  ASSERT_TRUE(reference.MoveFinal(Bent(initial, 35)));
  ASSERT_TRUE(reference.Release());

  ASSERT_TRUE(this->Session.Grab(initial));
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 35)));
  std::shared_ptr<SessionJob> job = this->Session.BeginRelease();
  ASSERT_TRUE(job);
  EXPECT_TRUE(this->Session.IsBusy());
  EXPECT_FALSE(this->Session.Undo());
  EXPECT_TRUE(HasMessage(this->Session, MessageSeverity::Error, "busy"));
  EXPECT_FALSE(this->Session.BeginRelease());
  std::thread worker([job]() { job->Run({}); });
  worker.join();
  EXPECT_EQ(job->GetOutcome(), SessionJob::Outcome::Done);
  ASSERT_TRUE(this->Session.Finish(*job));
  EXPECT_FALSE(this->Session.IsBusy());
  EXPECT_EQ(this->Session.GetHistoryPosition(), 1u);
  EXPECT_EQ(MaxDifference(this->Session.GetSurface(), reference.GetSurface()), 0.0);

  // A cancelled replay commits nothing; the cancellation is typed, not a message text.
  std::shared_ptr<SessionJob> replay = this->Session.BeginReplay(reference.GetPlan(), "plan");
  ASSERT_TRUE(replay);
  std::atomic<bool> cancel{ true };
  ProgressReporter progress;
  progress.cancel = &cancel;
  std::thread canceller([replay, progress]() { replay->Run(progress); });
  canceller.join();
  EXPECT_EQ(replay->GetOutcome(), SessionJob::Outcome::Cancelled);
  EXPECT_FALSE(this->Session.Finish(*replay));
  EXPECT_EQ(this->Session.GetHistoryPosition(), 1u);

  // Export on another thread writes the file the synchronous export writes.
  const std::string folder = test::TemporaryFolder("session-jobs");
  std::shared_ptr<SessionJob> exportJob =
    this->Session.BeginExport(folder + "/bent.vtp", ExportSurfaceOptions{}, true);
  ASSERT_TRUE(exportJob);
  std::thread exporter([exportJob]() { exportJob->Run({}); });
  exporter.join();
  ASSERT_TRUE(this->Session.Finish(*exportJob));
  ASSERT_EQ(exportJob->GetWrittenFiles().size(), 1u);
  EXPECT_EQ(MaxDifference(ReadMesh(folder + "/bent.vtp"), this->Session.GetSurface()), 0.0);
}

// The ghost of the original needs only the part of it the surface may differ from: the
// triangles with a point the grab binds (while grabbed) or the committed warps moved.
TEST_F(BenderSessionTest, OriginalInPlayIsWhereTheSurfaceMayDiffer)
{
  const auto touches = [](vtkPolyData* mesh, vtkIdType cell, const std::vector<bool>& marked)
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    mesh->GetCellPoints(cell, n, ids);
    for (vtkIdType k = 0; k < n; ++k)
    {
      if (marked[static_cast<std::size_t>(ids[k])])
      {
        return true;
      }
    }
    return false;
  };
  vtkPolyData* original = this->Session.GetOriginalSurface();
  const vtkIdType cells = original->GetNumberOfPolys();
  // Nothing grabbed or moved: nothing in play.
  vtkPolyData* idle = this->Session.GetOriginalInPlay();
  ASSERT_NE(idle, nullptr);
  EXPECT_EQ(idle->GetNumberOfPolys(), 0);

  // Grabbed: exactly the triangles with a bound point, on the original's own points.
  const RibbonSpec initial = StraightRibbon(20, 40);
  ASSERT_TRUE(this->Session.Grab(initial));
  std::vector<bool> bound(static_cast<std::size_t>(original->GetNumberOfPoints()), false);
  for (const std::int64_t id : this->Session.GetLiveFilter()->GetBoundPointIds())
  {
    bound[static_cast<std::size_t>(id)] = true;
  }
  vtkIdType expected = 0;
  for (vtkIdType c = 0; c < cells; ++c)
  {
    expected += touches(original, c, bound) ? 1 : 0;
  }
  vtkPolyData* grabbed = this->Session.GetOriginalInPlay();
  ASSERT_NE(grabbed, nullptr);
  EXPECT_EQ(grabbed->GetPoints(), original->GetPoints());
  EXPECT_EQ(grabbed->GetNumberOfPolys(), expected);
  EXPECT_GT(expected, 0);
  EXPECT_LT(expected, cells * 3 / 4); // the ribbon holds 20..40 of the 60 mm tube, R 6
  for (vtkIdType c = 0; c < grabbed->GetNumberOfPolys(); ++c)
  {
    EXPECT_TRUE(touches(grabbed, c, bound)) << c;
  }
  // Moves keep the same object (the view uploads it once per grab).
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 30)));
  EXPECT_EQ(this->Session.GetOriginalInPlay(), grabbed);
  ASSERT_TRUE(this->Session.MoveFinal(Bent(initial, 60)));
  EXPECT_EQ(this->Session.GetOriginalInPlay(), grabbed);
  ASSERT_TRUE(this->Session.Release());

  // Committed: every triangle the warp moved is in play, and only those.
  vtkPolyData* surface = this->Session.GetSurface();
  std::vector<bool> moved(static_cast<std::size_t>(original->GetNumberOfPoints()), false);
  for (vtkIdType i = 0; i < original->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    original->GetPoint(i, p);
    surface->GetPoint(i, q);
    moved[static_cast<std::size_t>(i)] = p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
  }
  expected = 0;
  for (vtkIdType c = 0; c < cells; ++c)
  {
    expected += touches(original, c, moved) ? 1 : 0;
  }
  vtkPolyData* committed = this->Session.GetOriginalInPlay();
  ASSERT_NE(committed, nullptr);
  EXPECT_GT(expected, 0);
  EXPECT_EQ(committed->GetNumberOfPolys(), expected);
  // Undo: the surface is the original again, nothing in play.
  ASSERT_TRUE(this->Session.Undo());
  EXPECT_EQ(this->Session.GetOriginalInPlay()->GetNumberOfPolys(), 0);
}

TEST_F(BenderSessionTest, OriginalInPlayIsAllOfItAfterASubdividedCommit)
{
  WarpParameters parameters = this->Session.GetParameters();
  parameters.subdivide = true;
  parameters.subdivisionTolerance = 0.01;
  ASSERT_TRUE(this->Session.SetParameters(parameters));
  this->Bend(60);
  ASSERT_GT(this->Session.GetSurface()->GetNumberOfPolys(), this->Tube->GetNumberOfPolys());
  EXPECT_EQ(this->Session.GetOriginalInPlay(), nullptr);
}
