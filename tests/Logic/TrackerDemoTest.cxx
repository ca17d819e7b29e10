// The bundled demos bend the demo vessel cleanly (issue 22, item 3). On the window's demo (the
// segmented demo vessel, the demo plan's ribbon, R and decay placed on it), the mouse demo plan,
// the simulator run to the end of its cycle and the bundled recording replayed to its end commit
// every warp through the session's commit path with the commit guard and the lumen guard on:
// every commit passes both (no branch's minimal inscribed radius narrows by more than 5 %),
// none changes the ribbon's length by more than NotableRibbonLengthChange, and the
// simulator's way back leaves the vessel where it was, so that its endless repetition stays
// clean. A commit that shortens the ribbon a lot says so in its message.
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "LumenGuard.h"
#include "RibbonLengthChange.h"
#include "SegmentationSession.h"
#include "TrackerDevice.h"
#include "TrackerSession.h"
#include "TrackerStream.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

using namespace bender;

namespace
{

const std::string Recording = std::string(BENDER_TEST_DATA_DIR) + "/tracking/two-hands.fastrak";

// One release of the gesture and what the session's commit path made of it.
struct Commit
{
  WarpSpec warp;
  CommitCheck check;
  bool committed = false;
  std::string message;
};

std::string Describe(const Commit& commit)
{
  std::ostringstream text;
  text << (commit.committed ? "committed" : "not committed") << ": " << commit.check.Summary()
       << "; lumen: " << commit.check.lumen.Summary() << "; ribbon length change "
       << RibbonLengthChange(commit.warp) * 100.0 << " %; " << commit.message;
  return text.str();
}

class TrackerDemoTest : public ::testing::Test
{
protected:
  // The window's demo job, once for the suite: the segmented demo vessel and the demo plan.
  static void SetUpTestSuite()
  {
    Demo = std::make_unique<SegmentationSession::DemoJob>();
    Demo->Run({});
  }
  static void TearDownTestSuite() { Demo.reset(); }

  // As the window leaves the demo: the surface, and the plan's first ribbon placed with its R
  // and decay, ready to grab (FileOpener::startDemo).
  void SetUp() override
  {
    ASSERT_TRUE(Demo && Demo->surface);
    ASSERT_FALSE(Demo->plan.warps.empty());
    ASSERT_TRUE(this->Session.SetSurface(Demo->surface, "demo vessel"));
    const WarpSpec& warp = Demo->plan.warps.front();
    WarpParameters parameters = this->Session.GetParameters();
    parameters.radius = warp.radius;
    parameters.decay = warp.decay;
    ASSERT_TRUE(this->Session.SetParameters(parameters));
    ASSERT_TRUE(this->Session.PlaceRibbon(warp.initial));
    ASSERT_TRUE(this->Session.GetCommitGuard());
    this->Session.SetLumenGuard(LumenGuardOptions{}); // on, 5 %, as in the window
    this->Original = vtkSmartPointer<vtkPolyData>::New();
    this->Original->DeepCopy(this->Session.GetSurface());
  }

  // The release as the window's G does it: a job, run, finished by the session.
  Commit Release()
  {
    Commit commit;
    commit.warp.initial = this->Session.GetInitialRibbon();
    commit.warp.final = this->Session.GetFinalRibbon();
    const std::shared_ptr<SessionJob> job = this->Session.BeginRelease();
    if (!job)
    {
      return commit;
    }
    job->Run({});
    commit.committed = this->Session.Finish(*job);
    commit.check = job->GetCommitCheck();
    commit.message = this->Session.GetMessages().back().text;
    return commit;
  }

  // Runs `device` to its end with the hands on the demo, in lock-step (the device may run at
  // most one sample ahead of the polls, whatever the machine's load), each release committed
  // through Release().
  std::vector<Commit> RunToTheEnd(std::unique_ptr<TrackerDevice> device)
  {
    std::vector<Commit> commits;
    TrackerSession trackers(this->Session);
    trackers.SetReleaseHandler(
      [&]()
      {
        commits.push_back(this->Release());
        return commits.back().committed;
      });
    TrackerDevice* polled = device.get();
    polled->EnablePoseQueue(2, true);
    EXPECT_TRUE(trackers.Connect(std::move(device)));
    EXPECT_TRUE(trackers.IsRelative());
    const auto start = std::chrono::steady_clock::now();
    while (
      trackers.IsConnected() && std::chrono::steady_clock::now() - start < std::chrono::minutes(5))
    {
      polled->WaitForActivity(std::chrono::milliseconds(20));
      polled->TakePoses();
      const TrackerSession::PollResult result = trackers.Poll();
      EXPECT_FALSE(result.cancelled && !result.ended) << "a grab was cancelled";
    }
    EXPECT_FALSE(trackers.IsConnected()) << "the device did not end";
    EXPECT_NE(this->Session.GetState(), GrabState::Grabbed) << "the stream ended mid-grab";
    return commits;
  }

  // Every commit passed the guard and kept the ribbon's length.
  void ExpectClean(const std::vector<Commit>& commits)
  {
    for (const Commit& commit : commits)
    {
      EXPECT_TRUE(commit.committed) << Describe(commit);
      EXPECT_TRUE(commit.check.checked) << Describe(commit);
      EXPECT_TRUE(commit.check.Passed()) << Describe(commit);
      EXPECT_TRUE(commit.check.lumen.checked) << commit.check.lumen.notMeasured;
      EXPECT_TRUE(commit.check.lumen.Passed()) << Describe(commit);
      EXPECT_LT(std::abs(RibbonLengthChange(commit.warp)), NotableRibbonLengthChange)
        << Describe(commit);
      EXPECT_EQ(commit.message.find("shorter"), std::string::npos) << commit.message;
    }
    EXPECT_FALSE(this->Session.IsCommitHeld());
  }

  static std::unique_ptr<SegmentationSession::DemoJob> Demo;
  BenderSession Session;
  vtkSmartPointer<vtkPolyData> Original;
};

std::unique_ptr<SegmentationSession::DemoJob> TrackerDemoTest::Demo;

} // namespace

TEST_F(TrackerDemoTest, TheMouseDemoPlanCommitsCleanly)
{
  // Grab the placed ribbon, move it to the plan's final ribbon, release: G, drag, G.
  for (const WarpSpec& warp : Demo->plan.warps)
  {
    ASSERT_TRUE(this->Session.Grab(warp.initial));
    ASSERT_TRUE(this->Session.MoveFinal(warp.final));
    const Commit commit = this->Release();
    ExpectClean({ commit });
  }
  EXPECT_EQ(this->Session.GetHistoryPosition(), Demo->plan.warps.size());
  EXPECT_GT(test::MaxDifference(this->Session.GetSurface(), this->Original), 2.0);
}

TEST_F(TrackerDemoTest, TheSimulatorBendsTheBranchAndBringsItBack)
{
  // One whole cycle of the script (14 s): the bend (commit 1), the way back (commit 2).
  TrackerDeviceOptions options;
  options.simulatorRealtime = false;
  options.simulatorRate = 30.0;
  options.simulatorDuration = 14.0;
  TrackerStream stream("sim", options);
  stream.Create();
  const std::vector<Commit> commits = this->RunToTheEnd(stream.TakeDevice());
  ASSERT_EQ(commits.size(), 2u);
  ExpectClean(commits);
  ASSERT_EQ(this->Session.GetHistoryPosition(), 2u);
  // Visibly: the first commit moved the branch by millimetres.
  ASSERT_TRUE(this->Session.Undo());
  EXPECT_GT(test::MaxDifference(this->Session.GetSurface(), this->Original), 4.0);
  ASSERT_TRUE(this->Session.Redo());
  // Back where it was (the warp back is the bend's inverse up to the kernel's accuracy): the
  // next cycle starts from the same vessel, so the endless simulator never accumulates.
  EXPECT_LT(test::MaxDifference(this->Session.GetSurface(), this->Original), 0.05);
}

TEST_F(TrackerDemoTest, TheBundledRecordingBendsTheBranchOnce)
{
  TrackerDeviceOptions options;
  options.realtime = false;
  TrackerStream stream("replay:" + Recording, options);
  stream.Create();
  const std::vector<Commit> commits = this->RunToTheEnd(stream.TakeDevice());
  ASSERT_EQ(commits.size(), 1u);
  ExpectClean(commits);
  EXPECT_EQ(this->Session.GetHistoryPosition(), 1u);
  EXPECT_GT(test::MaxDifference(this->Session.GetSurface(), this->Original), 4.0);
}

TEST_F(TrackerDemoTest, ACommitThatShortensTheRibbonSaysSo)
{
  // The old script's gesture: the ribbon 20 % shorter, the vessel compressed along it. No
  // triangle flips or crosses, so the guard passes it; the commit's message may not stay
  // silent about it.
  RibbonSpec shorter = *this->Session.GetRibbon();
  shorter.end.position =
    shorter.start.position + (shorter.end.position - shorter.start.position) * 0.8;
  ASSERT_TRUE(this->Session.Grab(*this->Session.GetRibbon()));
  ASSERT_TRUE(this->Session.MoveFinal(shorter));
  const Commit commit = this->Release();
  EXPECT_LT(RibbonLengthChange(commit.warp), -NotableRibbonLengthChange);
  ASSERT_TRUE(commit.committed) << commit.message;
  EXPECT_NE(commit.message.find("Warp 1 committed; the ribbon is"), std::string::npos)
    << commit.message;
  EXPECT_NE(commit.message.find("% shorter"), std::string::npos) << commit.message;
  EXPECT_NE(commit.message.find("compressed"), std::string::npos) << commit.message;
  EXPECT_EQ(this->Session.GetMessages().back().severity, MessageSeverity::Warning);
}
