// Simulator, calibration, pose -> ribbon end mapping, grab/release/clutch, and the
// simulator driving a geometry-core Ribbon end to end.
#include "Ribbon.h"
#include "RibbonEndMapping.h"
#include "SimulatedDevice.h"
#include "TrackerCalibration.h"
#include "TrackingTestUtilities.h"
#include "TwoHandRibbonInput.h"

namespace bender::test
{
namespace
{

constexpr double Pi = 3.14159265358979323846;

void ExpectVecNear(const Vec3& expected, const Vec3& actual, double tol = 1e-9)
{
  EXPECT_NEAR(expected.x, actual.x, tol);
  EXPECT_NEAR(expected.y, actual.y, tol);
  EXPECT_NEAR(expected.z, actual.z, tol);
}

TEST(SimulationScript, TwoHandBendFollowsItsScript)
{
  const SimulationScript script = SimulationScript::TwoHandBend();
  const TrackerPose left0 = script.PoseAt(1, 0.5);
  const TrackerPose right0 = script.PoseAt(2, 0.5);
  EXPECT_EQ(left0.station, 1);
  EXPECT_DOUBLE_EQ(left0.time, 0.5);
  ExpectVecNear({ -100, 0, 0 }, left0.position);
  ExpectVecNear({ 100, 0, 0 }, right0.position);
  EXPECT_FALSE(left0.button);
  EXPECT_TRUE(script.PoseAt(1, 1.0).button);
  EXPECT_TRUE(script.PoseAt(1, 4.99).button);
  EXPECT_FALSE(script.PoseAt(1, 5.0).button);
  EXPECT_FALSE(script.PoseAt(2, 2.0).button);
  // The way back: pressed again over 8-12 s.
  EXPECT_FALSE(script.PoseAt(1, 7.99).button);
  EXPECT_TRUE(script.PoseAt(1, 8.0).button);
  EXPECT_TRUE(script.PoseAt(1, 11.99).button);
  EXPECT_FALSE(script.PoseAt(1, 12.0).button);
  // Periodic (14 s), unit quaternions; the left hand stays put and the right one stays on the
  // arc of length 200 mm leaving the left hand along +x (its chord: 2 (200 / a) sin(a / 2) for
  // the arc's turn a, the angle between the hands' +x axes minus the half turn).
  for (double t = 0.0; t < 14.0; t += 0.37)
  {
    for (int s : { 1, 2 })
    {
      const TrackerPose a = script.PoseAt(s, t);
      const TrackerPose b = script.PoseAt(s, t + 14.0);
      EXPECT_NEAR(std::sqrt(Dot4(a.orientation, a.orientation)), 1.0, 1e-12);
      ExpectVecNear(a.position, b.position, 1e-9);
    }
    const TrackerPose left = script.PoseAt(1, t);
    const TrackerPose right = script.PoseAt(2, t);
    ExpectVecNear({ -100, 0, 0 }, left.position);
    const Vec3 leftX = RotateByQuaternion(left.orientation, { 1, 0, 0 });
    const Vec3 rightX = RotateByQuaternion(right.orientation, { 1, 0, 0 });
    const double turn = Pi - std::acos(std::max(-1.0, std::min(1.0, Dot(leftX, rightX))));
    const double chord = turn > 1e-9 ? 2.0 * (200.0 / turn) * std::sin(turn / 2.0) : 200.0;
    EXPECT_NEAR(Distance(left.position, right.position), chord, 1e-6) << "t = " << t;
    EXPECT_LE(turn, 50.0 * Pi / 180.0 + 1e-9);
  }
  // Fully bent over 4-8 s: the arc turns by 50 degrees.
  const Vec3 bentX = RotateByQuaternion(script.PoseAt(2, 6.0).orientation, { 1, 0, 0 });
  EXPECT_NEAR(std::acos(-bentX.x), 50.0 * Pi / 180.0, 1e-9);
}

TEST(SimulatedDevice, ProducesTimedPosesAndButtonEvents)
{
  SimulatedDevice::Options options;
  options.rateHz = 50.0;
  options.realtime = false;
  options.duration = 6.0;
  SimulatedDevice device(options);
  device.EnablePoseQueue(32, true);
  device.Open();
  device.Start();
  std::vector<TrackerPose> poses;
  std::vector<TrackerEvent> events;
  for (int i = 0; i < 2000; ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(10));
    for (const TrackerEvent& e : device.TakeEvents())
    {
      events.push_back(e);
    }
    for (const TrackerPose& p : device.TakePoses())
    {
      poses.push_back(p);
    }
    if (!events.empty() && events.back().type == TrackerEventType::EndOfStream)
    {
      break;
    }
  }
  ASSERT_EQ(poses.size(), 2u * 301u);
  EXPECT_DOUBLE_EQ(poses[20].time, 10.0 / 50.0);
  EXPECT_EQ(poses[21].station, 2);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].type, TrackerEventType::Grab);
  EXPECT_DOUBLE_EQ(events[0].time, 1.0);
  EXPECT_EQ(events[1].type, TrackerEventType::Release);
  EXPECT_DOUBLE_EQ(events[1].time, 5.0);
  EXPECT_EQ(events[2].type, TrackerEventType::EndOfStream);
  const TrackerStatistics stats = device.Statistics();
  ASSERT_EQ(stats.stations.size(), 2u);
  EXPECT_NEAR(stats.stations[1].RateHz(), 50.0, 1e-9);
  device.Close();
}

TEST(SimulatedDevice, StopsPromptlyWhileBlockedOrPaced)
{
  for (bool realtime : { false, true })
  {
    SimulatedDevice::Options options;
    options.realtime = realtime;
    options.rateHz = 1.0; // paced: one sample a second
    SimulatedDevice device(options);
    device.EnablePoseQueue(2, true); // not drained: the worker blocks
    device.Open();
    device.Start();
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    const auto start = std::chrono::steady_clock::now();
    device.Stop();
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(500));
    EXPECT_FALSE(device.IsStreaming());
    // Restart after a stop.
    device.Start();
    EXPECT_TRUE(device.LatestPose(1).has_value() || device.IsStreaming());
    device.Close();
  }
}

TEST(SimulatedDevice, RejectsBadOptions)
{
  SimulatedDevice::Options options;
  options.stations = { 5 };
  EXPECT_THROW(SimulatedDevice{ options }, TrackingConfigurationError);
  options.stations = { 1 };
  options.rateHz = 0.0;
  EXPECT_THROW(SimulatedDevice{ options }, TrackingConfigurationError);
}

TEST(TrackerCalibration, MapsPointsDirectionsAndOrientations)
{
  const Quaternion r = AxisAngle({ 0, 0, 1 }, Pi / 2);
  const TrackerCalibration c(r, { 10, 20, 30 }, 2.0);
  ExpectVecNear({ 10, 22, 30 }, c.MapPoint({ 1, 0, 0 }));  // rotate(2 * x) + t
  ExpectVecNear({ 0, 1, 0 }, c.MapDirection({ 1, 0, 0 })); // not scaled
  const Quaternion q = c.MapOrientation({ 1, 0, 0, 0 });
  ExpectVecNear({ 0, 1, 0 }, RotateByQuaternion(q, { 1, 0, 0 }));
  EXPECT_THROW(TrackerCalibration(r, { 0, 0, 0 }, 0.0), TrackingConfigurationError);
  EXPECT_THROW(TrackerCalibration({ 0, 0, 0, 0 }, { 0, 0, 0 }, 1.0), TrackingConfigurationError);
  EXPECT_THROW(TrackerCalibration(r, { NAN, 0, 0 }, 1.0), TrackingConfigurationError);
}

TEST(TrackerCalibration, FromThreePointsRecoversARigidAlignment)
{
  const TrackerCalibration truth(AxisAngle({ 1, 2, 3 }, 0.7), { -5, 40, 12 }, 1.5);
  const std::array<Vec3, 3> tracker = { Vec3{ 0, 0, 0 }, Vec3{ 100, 0, 0 }, Vec3{ 30, 80, 5 } };
  const std::array<Vec3, 3> model = {
    truth.MapPoint(tracker[0]), truth.MapPoint(tracker[1]), truth.MapPoint(tracker[2])
  };
  const TrackerCalibration c = TrackerCalibration::FromThreePoints(tracker, model, 1.5);
  for (const Vec3& p : { Vec3{ 1, 2, 3 }, Vec3{ -50, 20, 70 } })
  {
    ExpectVecNear(truth.MapPoint(p), c.MapPoint(p), 1e-9);
  }
  EXPECT_THROW(TrackerCalibration::FromThreePoints(
                 { Vec3{ 0, 0, 0 }, Vec3{ 1, 1, 1 }, Vec3{ 2, 2, 2 } }, model),
    TrackingConfigurationError);
}

TEST(RibbonEndMapping, ConventionForBothHands)
{
  const TrackerCalibration identity;
  // Left tracker: +x along world +x, +z up.
  const TrackerPose left = MakePose(1, { -100, 0, 0 }, { 1, 0, 0, 0 }, false);
  const RibbonEnd start = RibbonEndFromPose(left, Hand::Left, identity);
  ExpectVecNear({ -100, 0, 0 }, start.position);
  ExpectVecNear({ 1, 0, 0 }, start.tangent);
  ExpectVecNear({ 0, 0, 1 }, start.normal);
  // Right tracker facing the left one (+x along world -x): the end tangent still points
  // along the direction of travel, from start to end.
  const TrackerPose right = MakePose(2, { 100, 0, 0 }, AxisAngle({ 0, 0, 1 }, Pi), false);
  const RibbonEnd end = RibbonEndFromPose(right, Hand::Right, identity);
  ExpectVecNear({ 100, 0, 0 }, end.position);
  ExpectVecNear({ 1, 0, 0 }, end.tangent);
  ExpectVecNear({ 0, 0, 1 }, end.normal);
  // Calibration applies to all three.
  const TrackerCalibration c(AxisAngle({ 0, 0, 1 }, Pi / 2), { 0, 0, 5 }, 0.5);
  const RibbonEnd mapped = RibbonEndFromPose(left, Hand::Left, c);
  ExpectVecNear({ 0, -50, 5 }, mapped.position);
  ExpectVecNear({ 0, 1, 0 }, mapped.tangent);
  ExpectVecNear({ 0, 0, 1 }, mapped.normal);
}

TEST(RibbonEndMapping, StationLists)
{
  EXPECT_EQ(ParseStationList("1,2"), (std::vector<int>{ 1, 2 }));
  EXPECT_EQ(ParseStationList("4"), (std::vector<int>{ 4 }));
  for (const char* bad : { "", "0", "5", "1,,2", "1,2,", "12", "1,1", "a" })
  {
    EXPECT_THROW(ParseStationList(bad), TrackingConfigurationError) << bad;
  }
  HandMapping hands{ 3, 1 };
  EXPECT_EQ(hands.HandOf(3), Hand::Left);
  EXPECT_EQ(hands.HandOf(1), Hand::Right);
  EXPECT_FALSE(hands.HandOf(2).has_value());
  EXPECT_THROW(TwoHandRibbonInput(HandMapping{ 2, 2 }), TrackingConfigurationError);
}

TEST(TwoHandRibbonInput, GrabReleaseAndCancel)
{
  TwoHandRibbonInput input;
  EXPECT_FALSE(input.CurrentRibbon().has_value());
  // A grab before both hands are seen does nothing.
  EXPECT_FALSE(input.HandleEvent({ TrackerEventType::Grab, 1, 0.0, {} }).has_value());
  input.UpdatePose(MakePose(1, { -100, 0, 0 }, { 1, 0, 0, 0 }, false));
  input.UpdatePose(MakePose(2, { 100, 0, 0 }, AxisAngle({ 0, 0, 1 }, Pi), false));
  input.UpdatePose(MakePose(3, { 999, 0, 0 }, { 1, 0, 0, 0 }, false)); // not a hand
  auto grabbed = input.HandleEvent({ TrackerEventType::Grab, 1, 1.0, {} });
  ASSERT_TRUE(grabbed.has_value());
  EXPECT_EQ(grabbed->kind, TwoHandRibbonInput::Gesture::Kind::Grabbed);
  ExpectVecNear({ 100, 0, 0 }, grabbed->initial.end.position);
  EXPECT_TRUE(input.IsGrabbing());
  // The other hand's button does not start a second grab nor release this one.
  EXPECT_FALSE(input.HandleEvent({ TrackerEventType::Grab, 2, 1.5, {} }).has_value());
  EXPECT_FALSE(input.HandleEvent({ TrackerEventType::Release, 2, 1.6, {} }).has_value());
  input.UpdatePose(MakePose(2, { 80, 0, 20 }, AxisAngle({ 0, 0, 1 }, Pi), false));
  auto released = input.HandleEvent({ TrackerEventType::Release, 1, 2.0, {} });
  ASSERT_TRUE(released.has_value());
  EXPECT_EQ(released->kind, TwoHandRibbonInput::Gesture::Kind::Released);
  ExpectVecNear({ 100, 0, 0 }, released->initial.end.position);
  ExpectVecNear({ 80, 0, 20 }, released->final.end.position);
  EXPECT_FALSE(input.IsGrabbing());

  ASSERT_TRUE(input.HandleEvent({ TrackerEventType::Grab, 2, 3.0, {} }).has_value());
  auto cancelled = input.HandleEvent({ TrackerEventType::Disconnected, 0, 3.5, "USB unplugged" });
  ASSERT_TRUE(cancelled.has_value());
  EXPECT_EQ(cancelled->kind, TwoHandRibbonInput::Gesture::Kind::Cancelled);
  EXPECT_EQ(cancelled->reason, "USB unplugged");
  EXPECT_FALSE(input.IsGrabbing());
  EXPECT_FALSE(input.HandleEvent({ TrackerEventType::Release, 2, 4.0, {} }).has_value());
}

TEST(TwoHandRibbonInput, ClutchFreezesTheRibbonAndReanchorsTheHands)
{
  TwoHandRibbonInput input;
  input.UpdatePose(MakePose(1, { -100, 0, 0 }, { 1, 0, 0, 0 }, false));
  input.UpdatePose(MakePose(2, { 100, 0, 0 }, AxisAngle({ 0, 0, 1 }, Pi), false));
  const RibbonSpec before = *input.CurrentRibbon();
  input.SetClutch(true);
  EXPECT_TRUE(input.ClutchEngaged());
  // Hands move 300 mm to the side while clutched: the ribbon does not follow.
  input.UpdatePose(MakePose(1, { -100, 300, 0 }, { 1, 0, 0, 0 }, false));
  input.UpdatePose(MakePose(2, { 100, 300, 0 }, AxisAngle({ 0, 0, 1 }, Pi), false));
  ExpectVecNear(before.start.position, input.CurrentRibbon()->start.position);
  input.SetClutch(false);
  // After the clutch the ribbon continues from where it was...
  ExpectVecNear(before.start.position, input.CurrentRibbon()->start.position, 1e-9);
  ExpectVecNear(before.end.position, input.CurrentRibbon()->end.position, 1e-9);
  // ...and follows the hands again.
  input.UpdatePose(MakePose(1, { -90, 300, 0 }, { 1, 0, 0, 0 }, false));
  ExpectVecNear(
    before.start.position + Vec3{ 10, 0, 0 }, input.CurrentRibbon()->start.position, 1e-9);
}

// The simulator drives the ribbon: grab at 1 s on a straight ribbon, release at 5 s on one
// bent up into a circular arc of the same length; both build valid geometry-core Ribbons.
TEST(TwoHandRibbonInput, SimulatorDrivesARibbonEndToEnd)
{
  SimulatedDevice::Options options;
  options.rateHz = 20.0;
  options.realtime = false;
  options.duration = 6.0;
  SimulatedDevice device(options);
  device.EnablePoseQueue(1, true); // step the simulation one pose at a time
  TwoHandRibbonInput input;
  device.Open();
  device.Start();
  std::vector<TwoHandRibbonInput::Gesture> gestures;
  bool ended = false;
  for (int i = 0; i < 5000 && !ended; ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(10));
    const std::vector<TrackerEvent> events = device.TakeEvents();
    for (const TrackerPose& p : device.TakePoses())
    {
      input.UpdatePose(p);
    }
    for (const TrackerEvent& e : events)
    {
      ended = ended || e.type == TrackerEventType::EndOfStream;
      if (auto g = input.HandleEvent(e))
      {
        gestures.push_back(*g);
      }
    }
  }
  device.Close();
  ASSERT_TRUE(ended);
  ASSERT_EQ(gestures.size(), 2u);
  ASSERT_EQ(gestures[0].kind, TwoHandRibbonInput::Gesture::Kind::Grabbed);
  ASSERT_EQ(gestures[1].kind, TwoHandRibbonInput::Gesture::Kind::Released);
  const RibbonSpec& initial = gestures[1].initial;
  const RibbonSpec& final = gestures[1].final;
  // At the grab: a straight, untwisted ribbon between the hands.
  ExpectVecNear({ -100, 0, 0 }, initial.start.position, 1e-9);
  ExpectVecNear({ 100, 0, 0 }, initial.end.position, 1e-9);
  ExpectVecNear({ 1, 0, 0 }, initial.start.tangent, 1e-9);
  ExpectVecNear({ 1, 0, 0 }, initial.end.tangent, 1e-9);
  ExpectVecNear({ 0, 0, 1 }, initial.start.normal, 1e-9);
  ExpectVecNear({ 0, 0, 1 }, initial.end.normal, 1e-9);
  // At the release (fully bent): the start where it was, the end on the arc of radius 200 / a
  // that turns by a = 50 degrees up, its tangent and normal turned with it, no twist.
  const double a = 50.0 * Pi / 180.0, rho = 200.0 / a;
  const double c = std::cos(a), s = std::sin(a);
  ExpectVecNear(initial.start.position, final.start.position, 1e-9);
  ExpectVecNear({ 1, 0, 0 }, final.start.tangent, 1e-9);
  ExpectVecNear({ -100 + rho * s, 0, rho * (1 - c) }, final.end.position, 1e-9);
  ExpectVecNear({ c, 0, s }, final.end.tangent, 1e-9);
  ExpectVecNear({ -s, 0, c }, final.end.normal, 1e-9);

  const Ribbon straight(initial);
  const Ribbon arc(final);
  ExpectVecNear({ 0, 0, 0 }, straight.FrameAt(0.5).origin, 1e-6);
  // The wire is that arc: same length as the straight ribbon, one radius, rising in the
  // middle by rho (1 - cos(a / 2)).
  EXPECT_NEAR(arc.Wire().Length(), straight.Wire().Length(), 1e-6);
  EXPECT_NEAR(arc.Wire().MinimumRadius(), rho, 1e-6);
  EXPECT_NEAR(arc.FrameAt(0.5).origin.z, rho * (1 - std::cos(a / 2)), 1e-6);
  EXPECT_NEAR(std::fabs(straight.Twist()), 0.0, 1e-9);
  EXPECT_NEAR(std::fabs(arc.Twist()), 0.0, 1e-9);
}

} // namespace
} // namespace bender::test
