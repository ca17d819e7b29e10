// Bending with trackers: the scripted two-hand simulator grabs, bends and releases through the
// session; a stream that ends mid-warp cancels the live warp and keeps the committed shape.
#include "TrackerSession.h"
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "SimulatedDevice.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

using namespace bender;

namespace
{

// Polls at about 100 Hz until the device stops; returns what happened overall.
TrackerSession::PollResult RunUntilEnded(TrackerSession& trackers, double maxSeconds)
{
  TrackerSession::PollResult total;
  const auto start = std::chrono::steady_clock::now();
  while (
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < maxSeconds)
  {
    const auto r = trackers.Poll();
    total.grabbed |= r.grabbed;
    total.released |= r.released;
    total.cancelled |= r.cancelled;
    total.moved |= r.moved;
    if (r.ended)
    {
      total.ended = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return total;
}

std::unique_ptr<TrackerDevice> Simulator(double duration)
{
  SimulatedDevice::Options options;
  options.rateHz = 60;
  options.realtime = true;
  options.duration = duration;
  return std::make_unique<SimulatedDevice>(options);
}

}

TEST(TrackerSession, SimulatedHandsGrabBendAndRelease)
{
  // The script's hands hold a ribbon from (-100,0,0) to (100,0,0): a tube along it.
  auto tube = test::MakeTube(-150, 150, 10, 121, 24);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(tube, "tube"));
  WarpParameters parameters;
  parameters.radius = 30;
  ASSERT_TRUE(session.SetParameters(parameters));
  TrackerSession trackers(session);
  ASSERT_TRUE(trackers.Connect(Simulator(5.6)));
  EXPECT_NE(trackers.StatusText().find("simulator"), std::string::npos);
  const auto result = RunUntilEnded(trackers, 20);
  EXPECT_TRUE(result.grabbed);
  EXPECT_TRUE(result.moved);
  EXPECT_TRUE(result.released);
  EXPECT_TRUE(result.ended);
  EXPECT_FALSE(trackers.IsConnected());
  ASSERT_EQ(session.GetHistoryPosition(), 1u);
  EXPECT_GT(test::MaxDifference(session.GetSurface(), tube), 5.0);
  EXPECT_NE(session.GetState(), GrabState::Grabbed);
}

TEST(TrackerSession, DeviceFailureMidWarpCancelsAndKeepsTheCommittedShape)
{
  auto tube = test::MakeTube(-150, 150, 10, 121, 24);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(tube, "tube"));
  WarpParameters parameters;
  parameters.radius = 30;
  ASSERT_TRUE(session.SetParameters(parameters));
  TrackerSession trackers(session);
  // The stream ends at 3 s, in the middle of the 1 s - 5 s grab.
  ASSERT_TRUE(trackers.Connect(Simulator(3.0)));
  const auto result = RunUntilEnded(trackers, 20);
  EXPECT_TRUE(result.grabbed);
  EXPECT_TRUE(result.cancelled);
  EXPECT_FALSE(result.released);
  EXPECT_EQ(session.GetHistoryPosition(), 0u);
  EXPECT_EQ(session.GetState(), GrabState::Idle);
  EXPECT_EQ(test::MaxDifference(session.GetDisplaySurface(), tube), 0.0);
  bool told = false;
  for (const auto& message : session.GetMessages())
  {
    told |= message.severity == MessageSeverity::Warning &&
      message.text.find("cancelled") != std::string::npos;
  }
  EXPECT_TRUE(told);
}

TEST(TrackerSession, BadDeviceSpecGivesAMessage)
{
  BenderSession session;
  TrackerSession trackers(session);
  EXPECT_FALSE(trackers.Connect("bogus:device"));
  EXPECT_FALSE(trackers.Connect("replay:/no/such/recording.fastrak"));
  ASSERT_GE(session.GetMessages().size(), 2u);
  EXPECT_EQ(session.GetMessages().back().severity, MessageSeverity::Error);
}

TEST(TrackerSession, ReplayedRecordingGrabsBendsAndReleases)
{
  // The committed recording of the simulator's two hands (10 Hz, 6 s: grab at 1 s, release
  // at 5 s), replayed at its recorded pace through the real Fastrak decoding.
  auto tube = test::MakeTube(-150, 150, 10, 121, 24);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(tube, "tube"));
  WarpParameters parameters;
  parameters.radius = 30;
  ASSERT_TRUE(session.SetParameters(parameters));
  TrackerSession trackers(session);
  TrackerDeviceOptions options;
  options.realtime = true;
  ASSERT_TRUE(trackers.Connect(
    std::string("replay:") + BENDER_TEST_DATA_DIR + "/tracking/two-hands.fastrak", options));
  const auto result = RunUntilEnded(trackers, 30);
  EXPECT_TRUE(result.grabbed);
  EXPECT_TRUE(result.released);
  EXPECT_TRUE(result.ended);
  ASSERT_EQ(session.GetHistoryPosition(), 1u);
  EXPECT_GT(test::MaxDifference(session.GetSurface(), tube), 5.0);
  // The committed warp is the recorded gesture: a straight initial ribbon between the hands.
  const WarpSpec warp = session.GetPlan().warps.front();
  EXPECT_NEAR(warp.initial.start.position.x, -100.0, 1.0);
  EXPECT_NEAR(warp.initial.end.position.x, 100.0, 1.0);
}

TEST(TrackerSession, AlignCarriesTheHandsOntoTheRibbonOnScreen)
{
  auto tube = test::MakeTube(-150, 150, 10, 121, 24);
  BenderSession session;
  ASSERT_TRUE(session.SetSurface(tube, "tube"));
  TrackerSession trackers(session);
  EXPECT_FALSE(trackers.AlignTo(RibbonSpec{})); // no hands yet
  ASSERT_TRUE(trackers.Connect(Simulator(5.6)));
  std::optional<RibbonSpec> hands;
  for (int i = 0; i < 400 && !hands; ++i)
  {
    trackers.Poll();
    hands = trackers.CurrentRibbon();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(hands);
  // A target ribbon turned by 90 degrees about z and moved: after the alignment the hands
  // hold it (start exactly, the direction of the end exactly, the start normal).
  RibbonSpec target;
  target.start = { { 10, 20, 30 }, { 0, 1, 0 }, { 0, 0, 1 } };
  const double length = Distance(hands->start.position, hands->end.position);
  target.end = { { 10, 20 + length, 30 }, { 0, 1, 0 }, { 0, 0, 1 } };
  ASSERT_TRUE(trackers.AlignTo(target));
  // The new calibration takes effect from the next poses.
  std::optional<RibbonSpec> aligned;
  for (int i = 0; i < 400 && !aligned; ++i)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    trackers.Poll();
    aligned = trackers.CurrentRibbon();
  }
  ASSERT_TRUE(aligned);
  // The simulator's hands keep moving slowly: compare within a few millimetres.
  EXPECT_LT(Distance(aligned->start.position, target.start.position), 5.0);
  const Vec3 direction = Normalized(aligned->end.position - aligned->start.position);
  EXPECT_GT(Dot(direction, Vec3{ 0, 1, 0 }), 0.99);
}
