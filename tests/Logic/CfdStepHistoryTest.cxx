// Prepare for CFD as a step of the session's history (issue 22): an undo step between the
// warps, saved in the plan with its ends, names and extension factors, replayed by ApplyPlan
// (what `bender-cli warp` runs) to the very surface the session has; undo gives back the
// surface and the warps before it; the export's check compares with the prepared surface.

#include "ApplyPlan.h"
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "PatchLabels.h"
#include "PolyDataCopy.h"
#include "WarpPlanIO.h"

#include <gtest/gtest.h>

#include <vtkPolyData.h>

#include <string>

using namespace bender;

namespace
{
/// Same points (exactly) and the same cells.
bool SameSurface(vtkPolyData* a, vtkPolyData* b)
{
  return a && b && a->GetNumberOfCells() == b->GetNumberOfCells() &&
    a->GetNumberOfPoints() == b->GetNumberOfPoints() && test::MaxDifference(a, b) == 0.0;
}

/// The open tube's ends as they are (no clip: no centerlines needed), named and extended.
CfdStep TubeStep()
{
  CfdStep step;
  step.clip = false;
  step.inletExtension = 2.0;
  step.outletExtension = 1.0;
  step.names.push_back({ { 20, 0, 0 }, "aorta_out", false });
  step.extensionFactors.push_back({ { 20, 0, 0 }, 0.5 });
  return step;
}
} // namespace

TEST(CfdStepHistory, PrepareIsAnUndoStepSavedAndReplayed)
{
  const vtkSmartPointer<vtkPolyData> tube = test::MakeTube(-20, 20, 5, 41, 32);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(tube, "tube"));
  ASSERT_TRUE(session.ApplyWarp(test::Swing(-15, 0, 15, 8)));
  const vtkSmartPointer<vtkPolyData> bent = DeepCopyOf(session.GetSurface());

  const CfdStep step = TubeStep();
  const PrepareForCfdResult prepared = ApplyCfdStep(session.GetSurface(), step);
  ASSERT_TRUE(session.CommitCfdStep(step, prepared.surface, false));
  EXPECT_TRUE(SameSurface(session.GetSurface(), prepared.surface));
  EXPECT_EQ(ReadPatchLabels(session.GetSurface()).size(), 3u);
  EXPECT_TRUE(session.CanUndo());
  EXPECT_NE(session.GetCurrentCfdStep(), nullptr);
  // The export's check compares with the prepared surface: nothing flipped without a bend.
  const MeshCheckReport check = session.CheckSurface();
  EXPECT_TRUE(check.flipsChecked);
  EXPECT_EQ(check.flippedTriangles, 0);

  // A warp of the prepared surface, after the step.
  ASSERT_TRUE(session.ApplyWarp(test::Swing(0, 15, 10, 8)));
  const WarpPlan plan = session.GetPlan();
  ASSERT_EQ(plan.warps.size(), 2u);
  ASSERT_EQ(plan.cfdSteps.size(), 1u);
  EXPECT_EQ(plan.cfdSteps[0].afterWarps, 1u);
  EXPECT_EQ(plan.cfdSteps[0].names.front().name, "aorta_out");

  // Saved and read back: the same plan; replayed from the first surface (bender-cli warp runs
  // ApplyPlan): the session's surface, point for point.
  const std::string path = test::TemporaryFolder("cfd_step_history") + "/plan.bender.json";
  ASSERT_TRUE(session.SavePlan(path));
  const WarpPlan read = ReadWarpPlan(path);
  EXPECT_EQ(SerializeWarpPlan(read), SerializeWarpPlan(plan));
  const ApplyPlanResult replay = ApplyPlan(tube, read);
  ASSERT_EQ(replay.prepared.size(), 1u);
  EXPECT_TRUE(SameSurface(replay.output, session.GetSurface()));
  EXPECT_TRUE(SameSurface(replay.prepared[0].surface, prepared.surface));
  EXPECT_TRUE(session.IsPlanApplied(read));

  // Undo the warp and the step: the bent surface before the step, exactly, and its warps.
  ASSERT_TRUE(session.Undo());
  ASSERT_TRUE(session.Undo());
  EXPECT_TRUE(SameSurface(session.GetSurface(), bent));
  EXPECT_EQ(session.GetCurrentCfdStep(), nullptr);
  EXPECT_EQ(session.GetPlan().warps.size(), 1u);
  EXPECT_TRUE(session.GetPlan().cfdSteps.empty());
  EXPECT_TRUE(session.CanRedo());
  ASSERT_TRUE(session.Redo());
  EXPECT_TRUE(SameSurface(session.GetSurface(), prepared.surface));
  ASSERT_TRUE(session.Redo());
  EXPECT_TRUE(SameSurface(session.GetSurface(), replay.output));

  // Another session replays the file onto the tube: every step an undo step.
  BenderSession other;
  ASSERT_TRUE(other.SetSurface(tube, "tube"));
  ASSERT_TRUE(other.LoadPlan(path));
  EXPECT_TRUE(SameSurface(other.GetSurface(), session.GetSurface()));
  EXPECT_EQ(other.GetHistoryPosition(), 3u);
  ASSERT_TRUE(other.Undo());
  ASSERT_TRUE(other.Undo());
  EXPECT_TRUE(SameSurface(other.GetSurface(), bent));
}

TEST(CfdStepHistory, PreparedAgainReplacesTheStep)
{
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(test::MakeTube(-20, 20, 5, 41, 32), "tube"));
  CfdStep step = TubeStep();
  ASSERT_TRUE(session.CommitCfdStep(step, ApplyCfdStep(session.GetSurface(), step).surface, false));
  // Again, from the surface before, with other names: the new step takes the old one's place.
  step.names.front().name = "renamed";
  const PrepareForCfdResult again = ApplyCfdStep(session.GetPreviousSurface(), step);
  ASSERT_TRUE(session.CommitCfdStep(step, again.surface, true));
  EXPECT_EQ(session.GetHistoryPosition(), 1u);
  ASSERT_EQ(session.GetPlan().cfdSteps.size(), 1u);
  EXPECT_EQ(session.GetPlan().cfdSteps[0].names.front().name, "renamed");
  EXPECT_FALSE(session.CanRedo());
  // Replacing needs a prepared surface; a bad step names the plan's step.
  ASSERT_TRUE(session.Undo());
  EXPECT_FALSE(session.CommitCfdStep(step, again.surface, true));
  CfdStep bad = step;
  bad.names.front().name = "inlet";
  bad.names.push_back({ { -20, 0, 0 }, "inlet", false });
  try
  {
    ApplyCfdStep(session.GetSurface(), bad);
    ADD_FAILURE() << "no error";
  }
  catch (const InputError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("prepareForCfd: ", 0), 0u) << e.what();
  }
}
