// Bending with trackers: the scripted two-hand simulator grabs, bends and releases through the
// session; a stream that ends mid-warp cancels the live warp and keeps the committed shape.
// TrackerStream: every pose in order, its recording replays to the same poses, a cancel, a
// duration and failures end it cleanly.
#include "TrackerSession.h"
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "TrackerStream.h"
#include "TrackerTestUtilities.h"
#include "TrackingErrors.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <thread>

using namespace bender;
using test::PollUntilEnded;
using test::Simulator;

TEST(TrackerSession, SimulatedHandsGrabBendAndRelease)
{
  // The script's hands hold a ribbon from (-100,0,0) to (100,0,0): a tube along it.
  test::TubeSession tubeSession(10, 121, 24, 30);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  const auto& tube = tubeSession.tube;
  TrackerSession trackers(session);
  ASSERT_TRUE(trackers.Connect(Simulator(5.6)));
  EXPECT_NE(trackers.StatusText().find("simulator"), std::string::npos);
  const auto result = PollUntilEnded(trackers, 20);
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
  test::TubeSession tubeSession(10, 121, 24, 30);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  const auto& tube = tubeSession.tube;
  TrackerSession trackers(session);
  // The stream ends at 3 s, in the middle of the 1 s - 5 s grab.
  ASSERT_TRUE(trackers.Connect(Simulator(3.0)));
  const auto result = PollUntilEnded(trackers, 20);
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
  test::TubeSession tubeSession(10, 121, 24, 30);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  const auto& tube = tubeSession.tube;
  TrackerSession trackers(session);
  TrackerDeviceOptions options;
  options.realtime = true;
  ASSERT_TRUE(trackers.Connect(
    std::string("replay:") + BENDER_TEST_DATA_DIR + "/tracking/two-hands.fastrak", options));
  const auto result = PollUntilEnded(trackers, 30);
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
  test::TubeSession tubeSession(10, 121, 24);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  TrackerSession trackers(session);
  EXPECT_FALSE(trackers.AlignTo(RibbonSpec{})); // no hands yet
  ASSERT_TRUE(trackers.Connect(Simulator(5.6)));
  ASSERT_TRUE(test::PollUntil(trackers, [&]() { return trackers.CurrentRibbon().has_value(); }));
  const std::optional<RibbonSpec> hands = trackers.CurrentRibbon();
  // A target ribbon turned by 90 degrees about z and moved: after the alignment the hands
  // hold it (start exactly, the direction of the end exactly, the start normal).
  RibbonSpec target;
  target.start = { { 10, 20, 30 }, { 0, 1, 0 }, { 0, 0, 1 } };
  const double length = Distance(hands->start.position, hands->end.position);
  target.end = { { 10, 20 + length, 30 }, { 0, 1, 0 }, { 0, 0, 1 } };
  ASSERT_TRUE(trackers.AlignTo(target));
  // The new calibration takes effect from the next poses.
  ASSERT_TRUE(test::PollUntil(trackers, [&]() { return trackers.CurrentRibbon().has_value(); }));
  const std::optional<RibbonSpec> aligned = trackers.CurrentRibbon();
  // The simulator's hands keep moving slowly: compare within a few millimetres.
  EXPECT_LT(Distance(aligned->start.position, target.start.position), 5.0);
  const Vec3 direction = Normalized(aligned->end.position - aligned->start.position);
  EXPECT_GT(Dot(direction, Vec3{ 0, 1, 0 }), 0.99);
}

TEST(TrackerSession, AlignPutsTheMappedHandsOnTheRibbonEndsAndBendsNothing)
{
  // Hands held still, anchored on connect to a ribbon placed on the tube: they map onto its
  // ends. The right hand then moves 30 mm away (tracker x) and 12 mm aside (tracker y) while
  // the stylus is up: the ribbon stays, the right hand's mapped point drifts off its end by
  // the scaled displacement. Align carries both back onto the ends, to 1e-6 mm, and warps
  // nothing.
  test::TubeSession tubeSession(10, 121, 24, 30);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  const RibbonSpec placed = test::StraightRibbon(-20, 20);
  ASSERT_TRUE(session.PlaceRibbon(placed));
  TrackerSession trackers(session);
  EXPECT_FALSE(trackers.MappedHands()); // not connected
  test::HeldHands hands;
  ASSERT_TRUE(trackers.Connect(hands.Device()));
  ASSERT_TRUE(test::PollUntil(trackers, [&]() { return trackers.MappedHands().has_value(); }));
  ASSERT_TRUE(trackers.IsRelative());
  const auto onEnds = [&](const RibbonSpec& ribbon)
  {
    const std::optional<RibbonSpec> mapped = trackers.MappedHands();
    return mapped && Distance(mapped->start.position, ribbon.start.position) < 1e-6 &&
      Distance(mapped->end.position, ribbon.end.position) < 1e-6;
  };
  EXPECT_TRUE(onEnds(placed));

  *hands.offsetX = 30.0;
  *hands.offsetY = 12.0;
  ASSERT_TRUE(test::PollUntil(trackers,
    [&]()
    {
      const auto mapped = trackers.MappedHands();
      return mapped && Distance(mapped->end.position, placed.end.position) > 1.0;
    }));
  trackers.Poll(); // the newest pose taken by the input too
  std::optional<RibbonSpec> drifted = trackers.MappedHands();
  ASSERT_TRUE(drifted);
  // The hands' frame is the ribbon's (both along x, normal z): the displacement maps as it is,
  // times the automatic scale (ribbon length 40 / hands' span 200).
  const double scale = 40.0 / 200.0;
  EXPECT_LT(Distance(drifted->start.position, placed.start.position), 1e-9);
  EXPECT_LT(Distance(drifted->end.position, placed.end.position + Vec3{ 30, 12, 0 } * scale), 1e-9);
  // The ribbon did not follow (the stylus is up).
  ASSERT_TRUE(trackers.CurrentRibbon());
  EXPECT_LT(Distance(trackers.CurrentRibbon()->end.position, placed.end.position), 1e-12);

  const std::size_t messages = session.GetMessages().size();
  ASSERT_TRUE(trackers.AlignTo(placed));
  EXPECT_TRUE(onEnds(placed));
  ASSERT_GT(session.GetMessages().size(), messages);
  const std::string told = session.GetMessages().back().text;
  EXPECT_NE(told.find("Hands aligned"), std::string::npos) << told;
  EXPECT_NE(told.find("nothing was bent"), std::string::npos) << told;
  // Still on the ends after further polls (the session's ribbon is the one aligned to), and
  // nothing was warped.
  for (int i = 0; i < 5; ++i)
  {
    trackers.Poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(onEnds(placed));
  EXPECT_EQ(session.GetHistoryPosition(), 0u);
  EXPECT_NE(session.GetState(), GrabState::Grabbed);
  EXPECT_EQ(test::MaxDifference(session.GetDisplaySurface(), tubeSession.tube), 0.0);
  EXPECT_EQ(test::MaxDifference(session.GetSurface(), tubeSession.tube), 0.0);

  // A hand motion from there moves the mapped point from the end by the scaled displacement
  // (the new anchor's span is 230 mm: scale 40 / |(230, 12, 0)|).
  *hands.offsetX = 40.0;
  ASSERT_TRUE(test::PollUntil(trackers,
    [&]()
    {
      const auto mapped = trackers.MappedHands();
      return mapped && Distance(mapped->end.position, placed.end.position) > 0.5;
    }));
  trackers.Disconnect();
  EXPECT_FALSE(trackers.MappedHands());
  EXPECT_FALSE(trackers.AlignTo(placed));
  EXPECT_EQ(session.GetMessages().back().text, "Align: connect a tracker first");
}

TEST(TrackerSession, AKeyPressesTheHandsButtonForDevicesWithoutOne)
{
  // Hands that never press a button (an OpenIGTLink server without STRING messages), anchored
  // to a placed ribbon: PressHands grabs from the ribbon as it is, the ribbon's end follows the
  // right hand's displacement (scaled 40 / 200), ReleaseHands commits that warp. A cancel from
  // the window lets go of the hands too.
  test::TubeSession tubeSession(10, 121, 24, 30);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  const RibbonSpec placed = test::StraightRibbon(-20, 20);
  ASSERT_TRUE(session.PlaceRibbon(placed));
  TrackerSession trackers(session);
  EXPECT_FALSE(trackers.PressHands()); // not connected
  test::HeldHands hands;
  ASSERT_TRUE(trackers.Connect(hands.Device()));
  ASSERT_TRUE(test::PollUntil(trackers, [&]() { return trackers.MappedHands().has_value(); }));
  EXPECT_FALSE(trackers.ReleaseHands()); // nothing pressed

  ASSERT_TRUE(trackers.PressHands());
  EXPECT_TRUE(trackers.HandsPressed());
  EXPECT_EQ(session.GetState(), GrabState::Grabbed);
  EXPECT_LT(Distance(session.GetInitialRibbon().end.position, placed.end.position), 1e-9);
  EXPECT_FALSE(trackers.PressHands()); // already grabbing
  *hands.offsetX = -25.0;
  const Vec3 expected = placed.end.position + Vec3{ -25, 0, 0 } * (40.0 / 200.0);
  ASSERT_TRUE(test::PollUntil(
    trackers, [&]() { return Distance(session.GetFinalRibbon().end.position, expected) < 1e-9; }));
  ASSERT_TRUE(trackers.ReleaseHands());
  EXPECT_FALSE(trackers.HandsPressed());
  ASSERT_EQ(session.GetHistoryPosition(), 1u);
  const WarpSpec warp = session.GetPlan().warps.front();
  EXPECT_LT(Distance(warp.initial.end.position, placed.end.position), 1e-9);
  EXPECT_LT(Distance(warp.final.end.position, expected), 1e-9);

  // Pressed again, then the window cancels the grab (Esc): the hands let go, and the next
  // press grabs from the session's ribbon, where the cancel left it.
  ASSERT_TRUE(trackers.PressHands());
  *hands.offsetX = 0.0;
  ASSERT_TRUE(test::PollUntil(
    trackers, [&]() { return Distance(session.GetFinalRibbon().end.position, expected) > 1.0; }));
  session.CancelGrab("cancelled by the user");
  trackers.Poll();
  EXPECT_FALSE(trackers.HandsPressed());
  ASSERT_TRUE(trackers.PressHands());
  EXPECT_LT(Distance(session.GetInitialRibbon().end.position, warp.final.end.position), 1e-9);
  EXPECT_LT(Distance(session.GetFinalRibbon().end.position, warp.final.end.position), 1e-9);
  trackers.Disconnect();
  EXPECT_FALSE(trackers.HandsPressed());
  EXPECT_NE(session.GetState(), GrabState::Grabbed);
}

// TrackerStream: the device lifecycle under `bender-cli tracker` and the Trackers panel.
TEST(TrackerStream, StreamsEveryPoseInOrderAndRecordsWhatReplaysToTheSame)
{
  const std::string recording = ::testing::TempDir() + "/tracker-stream-sim.fastrak";
  TrackerDeviceOptions options;
  options.simulatorRealtime = false;
  options.simulatorDuration = 2.0;
  options.recordPath = recording;
  TrackerStream sim("sim", options);
  EXPECT_FALSE(sim.IsLive());
  EXPECT_EQ(sim.Kind().name, "sim");
  std::vector<TrackerPose> poses;
  int events = 0;
  TrackerStream::Sink sink;
  sink.pose = [&](const TrackerPose& pose, const std::string* name)
  {
    EXPECT_EQ(name, nullptr); // the simulator does not name its poses
    poses.push_back(pose);
  };
  sink.event = [&](const TrackerEvent& event)
  {
    EXPECT_TRUE(event.type == TrackerEventType::Grab || event.type == TrackerEventType::Release);
    ++events;
  };
  const TrackerStream::Result result = sim.Run({}, sink);
  EXPECT_TRUE(result.Ok()) << result.failure << result.noPoses;
  EXPECT_FALSE(result.interrupted);
  ASSERT_EQ(result.poses, poses.size());
  ASSERT_EQ(poses.size(), 2u * 121u); // 60 Hz for 2 s, two stations
  EXPECT_EQ(events, 1);               // the script presses at 1 s
  for (std::size_t i = 1; i < poses.size(); ++i)
  {
    EXPECT_LE(poses[i - 1].time, poses[i].time);
  }
  const TrackerStatistics stats = sim.Statistics();
  ASSERT_EQ(stats.stations.size(), 2u);
  EXPECT_EQ(stats.stations[0].samples + stats.stations[1].samples, poses.size());
  sim.Close();

  // The recording is the hands as Fastrak binary records: a replay gives the same poses (to
  // the record's float32 centimetres).
  TrackerStream replay("replay:" + recording);
  std::vector<TrackerPose> replayed;
  TrackerStream::Sink replaySink;
  replaySink.pose = [&](const TrackerPose& pose, const std::string*) { replayed.push_back(pose); };
  TrackerStream::Limits limits;
  limits.count = 50;
  const TrackerStream::Result again = replay.Run(limits, replaySink);
  EXPECT_TRUE(again.Ok()) << again.failure << again.noPoses;
  ASSERT_EQ(replayed.size(), 50u);
  for (std::size_t i = 0; i < replayed.size(); ++i)
  {
    EXPECT_EQ(replayed[i].station, poses[i].station);
    EXPECT_EQ(replayed[i].button, poses[i].button);
    EXPECT_LT(Distance(replayed[i].position, poses[i].position), 1e-3);
  }
  std::remove(recording.c_str());
  std::remove((recording + ".timestamps").c_str());
}

TEST(TrackerStream, CancelDurationAndFailuresEndTheStreamCleanly)
{
  // An endless simulator: the cancel callback stops it; the device is stopped, not lost.
  TrackerStream endless("sim");
  int polls = 0;
  const TrackerStream::Result cancelled = endless.Run({}, {}, [&polls]() { return ++polls > 3; });
  EXPECT_TRUE(cancelled.interrupted);
  EXPECT_TRUE(cancelled.Ok());
  std::unique_ptr<TrackerDevice> device = endless.TakeDevice();
  ASSERT_TRUE(device);
  EXPECT_TRUE(device->IsOpen());
  EXPECT_FALSE(device->IsStreaming());
  device->Close();

  // A duration in pose time.
  TrackerDeviceOptions fast;
  fast.simulatorRealtime = false;
  TrackerStream timed("sim", fast);
  TrackerStream::Limits limits;
  limits.duration = 0.5;
  double last = 0.0;
  TrackerStream::Sink sink;
  sink.pose = [&last](const TrackerPose& pose, const std::string*) { last = pose.time; };
  const TrackerStream::Result result = timed.Run(limits, sink);
  EXPECT_TRUE(result.Ok());
  EXPECT_GT(result.poses, 0u);
  EXPECT_LE(last, 0.5);

  // A bad spec is refused when parsed; a recording that is not there when opened; a file that
  // decodes nothing is said so.
  EXPECT_THROW(TrackerStream("floppy"), TrackingConfigurationError);
  EXPECT_THROW(TrackerStream("replay:/no/such/recording.fastrak").Run({}, {}), RecordingError);
  const std::string garbage = ::testing::TempDir() + "/tracker-stream-garbage.bin";
  {
    std::FILE* file = std::fopen(garbage.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    std::fputs(std::string(300, 'z').c_str(), file);
    std::fclose(file);
  }
  TrackerStream noise("replay:" + garbage);
  const TrackerStream::Result empty = noise.Run({}, {});
  EXPECT_EQ(empty.poses, 0u);
  EXPECT_NE(empty.noPoses.find("no pose decoded"), std::string::npos) << empty.noPoses;
  EXPECT_EQ(noise.Statistics().parser.garbageBytes, 300u);
  std::remove(garbage.c_str());
}
