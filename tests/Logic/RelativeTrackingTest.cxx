// Trackers that start where the ribbon is (issue 12, item 6): the hands are anchored to the
// ribbon on screen, so connecting and grabbing move nothing; while the stylus is held the ends
// move by the hands' displacements (times the motion scale) in the ribbon's frame and turn by
// the hands' rotations; between grabs the ribbon stays.
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "Ribbon.h"
#include "TrackerSession.h"
#include "TrackerTestUtilities.h"
#include "TwoHandRibbonInput.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

using namespace bender;

namespace
{

constexpr double Pi = 3.14159265358979323846;

Quaternion AxisAngle(const Vec3& axis, double angle)
{
  const Vec3 k = Normalized(axis);
  const double s = std::sin(angle / 2.0);
  return { std::cos(angle / 2.0), k.x * s, k.y * s, k.z * s };
}

TrackerPose Pose(int station, const Vec3& position, const Quaternion& orientation = {})
{
  TrackerPose pose;
  pose.station = station;
  pose.position = position;
  pose.orientation = orientation;
  return pose;
}

TrackerEvent Event(TrackerEventType type, int station)
{
  TrackerEvent event;
  event.type = type;
  event.station = station;
  return event;
}

// The hands as the simulator holds them at rest: 200 mm apart along x, +x of each towards
// the other hand, +z up.
const Quaternion Facing = AxisAngle({ 0, 0, 1 }, Pi);

bool HasWarning(const BenderSession& session, const std::string& part)
{
  for (const auto& message : session.GetMessages())
  {
    if (message.severity == MessageSeverity::Warning &&
      message.text.find(part) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

double EndDistance(const RibbonEnd& a, const RibbonEnd& b)
{
  return std::max({ Distance(a.position, b.position),
    Distance(Normalized(a.tangent), Normalized(b.tangent)),
    Distance(Normalized(a.normal), Normalized(b.normal)) });
}

double RibbonDistance(const RibbonSpec& a, const RibbonSpec& b)
{
  return std::max(EndDistance(a.start, b.start), EndDistance(a.end, b.end));
}

// A ribbon somewhere else, along another direction than the hands: from (10, 20, 30) along
// +y, 40 mm long, normal +x.
RibbonSpec Elsewhere()
{
  RibbonSpec ribbon;
  ribbon.start = { { 10, 20, 30 }, { 0, 1, 0 }, { 1, 0, 0 } };
  ribbon.end = { { 10, 60, 30 }, { 0, 1, 0 }, { 1, 0, 0 } };
  return ribbon;
}

}

TEST(RelativeTracking, AnchoringMovesNothingAndTheRibbonStaysBetweenGrabs)
{
  TwoHandRibbonInput input;
  input.AnchorTo(Elsewhere());
  EXPECT_TRUE(input.IsRelative());
  EXPECT_FALSE(input.CurrentRibbon()); // the hands are not seen yet
  input.UpdatePose(Pose(1, { -100, 0, 0 }));
  input.UpdatePose(Pose(2, { 100, 0, 0 }, Facing));
  ASSERT_TRUE(input.CurrentRibbon());
  EXPECT_LT(RibbonDistance(*input.CurrentRibbon(), Elsewhere()), 1e-12);
  // Free hands between grabs: the ribbon does not follow.
  input.UpdatePose(Pose(1, { -300, 50, 70 }, AxisAngle({ 1, 2, 3 }, 1.0)));
  EXPECT_LT(RibbonDistance(*input.CurrentRibbon(), Elsewhere()), 1e-12);
  // The grab starts from the ribbon as it is, wherever the hands are.
  const auto grabbed = input.HandleEvent(Event(TrackerEventType::Grab, 1));
  ASSERT_TRUE(grabbed);
  EXPECT_LT(RibbonDistance(grabbed->initial, Elsewhere()), 1e-6);
  EXPECT_LT(RibbonDistance(*input.CurrentRibbon(), Elsewhere()), 1e-6);
}

TEST(RelativeTracking, AHandDisplacementMovesItsEndByTheScaledDisplacement)
{
  // A ribbon along x with normal z: the hands' frame is the ribbon's, so the displacement
  // maps as it is, times the scale.
  const RibbonSpec ribbon = test::StraightRibbon(-20, 20);
  for (const double scale : { 0.0, 0.5, 2.0 })
  {
    TwoHandRibbonInput input;
    input.SetRelativeScale(scale);
    input.UpdatePose(Pose(1, { -100, 0, 0 }));
    input.UpdatePose(Pose(2, { 100, 0, 0 }, Facing));
    input.AnchorTo(ribbon);
    ASSERT_TRUE(input.HandleEvent(Event(TrackerEventType::Grab, 1)));
    const Vec3 d{ 3, -4, 5 };
    input.UpdatePose(Pose(2, Vec3{ 100, 0, 0 } + d, Facing));
    const RibbonSpec moved = *input.CurrentRibbon();
    const double expected = scale > 0 ? scale : 40.0 / 200.0; // auto: ribbon length / span
    EXPECT_NEAR(input.Anchor()->scale, expected, 1e-12);
    EXPECT_LT(Distance(moved.end.position, ribbon.end.position + d * expected), 1e-9) << scale;
    EXPECT_LT(EndDistance(moved.start, ribbon.start), 1e-9);
    EXPECT_LT(Distance(moved.end.tangent, ribbon.end.tangent), 1e-9); // no turn, no change
    const auto released = input.HandleEvent(Event(TrackerEventType::Release, 1));
    ASSERT_TRUE(released);
    EXPECT_LT(RibbonDistance(released->final, moved), 1e-12);
    // The ribbon stays where the hands left it; the next grab goes on from there.
    input.UpdatePose(Pose(2, { 100, 0, 0 }, Facing));
    EXPECT_LT(RibbonDistance(*input.CurrentRibbon(), moved), 1e-12);
    ASSERT_TRUE(input.HandleEvent(Event(TrackerEventType::Grab, 1)));
    EXPECT_LT(RibbonDistance(*input.CurrentRibbon(), moved), 1e-9);
    // Anchored again to the ribbon as it is (its chord turned a little): the same hand motion
    // moves the end by as much, times the new scale.
    input.UpdatePose(Pose(2, Vec3{ 100, 0, 0 } + d, Facing));
    EXPECT_NEAR(Distance(input.CurrentRibbon()->end.position, moved.end.position),
      Norm(d) * input.Anchor()->scale,
      1e-9);
  }
}

TEST(RelativeTracking, DisplacementsAndTurnsAreExpressedInTheRibbonsFrame)
{
  // The hands lie along tracker x, the ribbon along model y (normal x): bringing the right
  // hand 10 mm towards the left one shortens the ribbon by 10 mm (scale 1), and rolling the
  // right hand about its own x axis twists the end about the ribbon's tangent.
  TwoHandRibbonInput input;
  input.SetRelativeScale(1.0);
  input.UpdatePose(Pose(1, { -100, 0, 0 }));
  input.UpdatePose(Pose(2, { 100, 0, 0 }, Facing));
  input.AnchorTo(Elsewhere());
  ASSERT_TRUE(input.HandleEvent(Event(TrackerEventType::Grab, 2)));
  const double roll = 30.0 * Pi / 180.0;
  input.UpdatePose(Pose(2, { 90, 0, 0 }, Facing * AxisAngle({ 1, 0, 0 }, roll)));
  const RibbonSpec moved = *input.CurrentRibbon();
  EXPECT_LT(Distance(moved.end.position, { 10, 50, 30 }), 1e-9);
  EXPECT_LT(Distance(moved.end.tangent, { 0, 1, 0 }), 1e-9);
  // The normal turned by 30 degrees about the tangent (+y or -y: the sense of the hand's
  // roll seen along the ribbon), staying perpendicular to it.
  EXPECT_NEAR(Dot(moved.end.normal, { 1, 0, 0 }), std::cos(roll), 1e-9);
  EXPECT_NEAR(std::abs(Dot(moved.end.normal, { 0, 0, 1 })), std::sin(roll), 1e-9);
  EXPECT_NEAR(Dot(moved.end.normal, { 0, 1, 0 }), 0.0, 1e-9);
}

TEST(RelativeTracking, TheClutchReanchorsWithoutAJump)
{
  TwoHandRibbonInput input;
  input.SetRelativeScale(1.0);
  input.UpdatePose(Pose(1, { -100, 0, 0 }));
  input.UpdatePose(Pose(2, { 100, 0, 0 }, Facing));
  input.AnchorTo(test::StraightRibbon(-20, 20));
  ASSERT_TRUE(input.HandleEvent(Event(TrackerEventType::Grab, 1)));
  input.UpdatePose(Pose(2, { 105, 0, 0 }, Facing));
  const RibbonSpec before = *input.CurrentRibbon();
  input.SetClutch(true);
  input.UpdatePose(Pose(2, { 150, 40, 0 }, Facing)); // the hand moves back, freely
  EXPECT_LT(RibbonDistance(*input.CurrentRibbon(), before), 1e-12);
  input.SetClutch(false);
  EXPECT_LT(RibbonDistance(*input.CurrentRibbon(), before), 1e-9);
  input.UpdatePose(Pose(2, { 152, 40, 0 }, Facing));
  EXPECT_NEAR(Distance(input.CurrentRibbon()->end.position, before.end.position), 2.0, 1e-9);
}

using test::PollUntilEnded;
using test::Simulator;

TEST(RelativeTracking, ConnectingTheSimulatorMovesNoPointAndNotTheRibbon)
{
  // The simulator's hands rest 200 mm apart at x = -100 and 100 and press the stylus at 1 s;
  // the ribbon on screen is 40 mm long elsewhere. Until the press nothing may move.
  test::TubeSession tubeSession(10, 121, 24);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  const auto& tube = tubeSession.tube;
  const RibbonSpec placed = test::StraightRibbon(10, 50);
  ASSERT_TRUE(session.PlaceRibbon(placed));
  TrackerSession trackers(session);
  ASSERT_TRUE(trackers.Connect(Simulator(0.8)));
  EXPECT_TRUE(trackers.IsRelative());
  int seen = 0;
  PollUntilEnded(trackers,
    20,
    [&](const TrackerSession::PollResult& result)
    {
      EXPECT_FALSE(result.grabbed);
      if (const auto ribbon = trackers.CurrentRibbon())
      {
        ++seen;
        EXPECT_LT(RibbonDistance(*ribbon, placed), 1e-6);
      }
    });
  EXPECT_GT(seen, 0);
  EXPECT_EQ(session.GetHistoryPosition(), 0u);
  EXPECT_EQ(test::MaxDifference(session.GetDisplaySurface(), tube), 0.0);
  EXPECT_EQ(test::MaxDifference(session.GetSurface(), tube), 0.0);
}

TEST(RelativeTracking, TheSimulatorBendsTheRibbonFromWhereItIs)
{
  // The script's bend: grab at 1 s, the left hand still, the right one along the arc of the
  // hands' span turning 50 degrees up, release at 5 s. Anchored to a 40 mm ribbon that ends at
  // the open end of a tube of radius 4, as the demo's ribbon ends at its branch's open end
  // (automatic scale 40 / 200), the ribbon's end moves onto the arc of length 40 mm that turns
  // 50 degrees up: the start stays, the length too.
  test::TubeSession tubeSession(4, 301, 24);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  WarpParameters parameters;
  // As the window places a ribbon on a vessel: R = 2.2 radii, a plateau reaching 1.2 radii;
  // R stays below the arc's radius (40 mm / 50 degrees = 45.8 mm).
  parameters.radius = 8.8;
  parameters.decay.shape = DecayShape::Plateau;
  parameters.decay.plateau = 1.2 / 2.2;
  ASSERT_TRUE(session.SetParameters(parameters));
  const RibbonSpec placed = test::StraightRibbon(110, 150);
  ASSERT_TRUE(session.PlaceRibbon(placed));
  TrackerSession trackers(session);
  ASSERT_TRUE(trackers.Connect(Simulator(5.6)));
  int grabs = 0;
  PollUntilEnded(
    trackers, 30, [&](const TrackerSession::PollResult& result) { grabs += result.grabbed; });
  EXPECT_EQ(grabs, 1);
  // The commit guard found nothing to hold: no flipped or crossing triangles.
  ASSERT_FALSE(session.IsCommitHeld()) << session.GetHeldCheck().Summary();
  EXPECT_FALSE(HasWarning(session, "Commit held"));
  ASSERT_EQ(session.GetHistoryPosition(), 1u);
  const WarpSpec warp = session.GetPlan().warps.front();
  // No jump: the warp starts from the ribbon on screen.
  EXPECT_LT(RibbonDistance(warp.initial, placed), 1e-6);
  const double a = 50.0 * 3.14159265358979323846 / 180.0;
  EXPECT_LT(Distance(warp.final.start.position, placed.start.position), 1e-6);
  EXPECT_NEAR(warp.final.end.position.x, 110.0 + 40.0 * std::sin(a) / a, 0.2);
  EXPECT_NEAR(warp.final.end.position.z, 40.0 * (1.0 - std::cos(a)) / a, 0.2);
  // The arc stays in the ribbon's plane (x, z), bends the tube up, not flat, and keeps the
  // ribbon's length.
  EXPECT_NEAR(warp.final.end.position.y, 0.0, 1e-6);
  EXPECT_NEAR(Dot(Normalized(warp.final.end.tangent), { 0, 0, 1 }), std::sin(a), 0.01);
  EXPECT_NEAR(Ribbon(warp.final).Wire().Length(), 40.0, 0.2);
  // The ribbon on the session is the committed one.
  ASSERT_TRUE(session.GetRibbon());
  EXPECT_LT(RibbonDistance(*session.GetRibbon(), warp.final), 1e-12);
}

TEST(RelativeTracking, AlignReanchorsTheHandsToTheGivenRibbon)
{
  test::TubeSession tubeSession(10, 61, 16);
  ASSERT_TRUE(tubeSession.ready);
  BenderSession& session = tubeSession.session;
  const auto& tube = tubeSession.tube;
  TrackerSession trackers(session);
  ASSERT_TRUE(trackers.Connect(Simulator(0.9)));
  EXPECT_FALSE(trackers.IsRelative()); // no ribbon on the session: absolute
  ASSERT_TRUE(test::PollUntil(trackers, [&]() { return trackers.CurrentRibbon().has_value(); }));
  ASSERT_TRUE(trackers.AlignTo(Elsewhere()));
  EXPECT_TRUE(trackers.IsRelative());
  EXPECT_LT(RibbonDistance(*trackers.CurrentRibbon(), Elsewhere()), 1e-6);
  trackers.Poll();
  EXPECT_LT(RibbonDistance(*trackers.CurrentRibbon(), Elsewhere()), 1e-6);
  EXPECT_EQ(test::MaxDifference(session.GetDisplaySurface(), tube), 0.0);
}
