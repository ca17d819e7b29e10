// Bending with trackers: the scripted two-hand simulator grabs, bends and releases through the
// session; a stream that ends mid-warp cancels the live warp and keeps the committed shape.
#include "TrackerSession.h"
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "TrackerTestUtilities.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <chrono>
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
