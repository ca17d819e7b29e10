#ifndef bender_TrackerTestUtilities_h
#define bender_TrackerTestUtilities_h

// Pieces shared by the tracker session suites (TrackerSessionTest, RelativeTrackingTest) and
// the window's tracker tests: the scripted simulator, hands held still (and moved on demand),
// polling until the device stops, and a session on a tube.

#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "SimulatedDevice.h"
#include "TrackerSession.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <thread>

namespace bender
{
namespace test
{

/// The scripted two-hand simulator (SimulationScript::TwoHandBend) at 60 Hz, paced by the
/// clock, ending after `duration` seconds.
inline std::unique_ptr<TrackerDevice> Simulator(double duration)
{
  SimulatedDevice::Options options;
  options.rateHz = 60;
  options.realtime = true;
  options.duration = duration;
  return std::make_unique<SimulatedDevice>(options);
}

/// Two hands held still, 200 mm apart along tracker x (left at (-100, 0, 0), right at
/// (100, 0, 0)), each with +x towards the other and +z up, the stylus up; the right hand is
/// displaced by `rightOffset` (settable while streaming). Endless, 100 Hz.
struct HeldHands
{
  std::shared_ptr<std::atomic<double>> offsetX = std::make_shared<std::atomic<double>>(0.0);
  std::shared_ptr<std::atomic<double>> offsetY = std::make_shared<std::atomic<double>>(0.0);

  std::unique_ptr<TrackerDevice> Device() const
  {
    SimulatedDevice::Options options;
    options.rateHz = 100;
    options.realtime = true;
    auto x = this->offsetX;
    auto y = this->offsetY;
    return std::make_unique<SimulatedDevice>(options,
      SimulationScript(
        [x, y](int station, double)
        {
          TrackerPose pose;
          if (station == 2)
          {
            pose.position = { 100.0 + x->load(), y->load(), 0.0 };
            pose.orientation = { 0.0, 0.0, 0.0, 1.0 }; // half a turn about z: +x towards -x
          }
          else
          {
            pose.position = { -100.0, 0.0, 0.0 };
          }
          return pose;
        }));
  }
};

/// Polls at about 100 Hz until the device stops (a failure is recorded when it does not within
/// `maxSeconds`), calling `check` after each poll; returns what happened overall.
inline TrackerSession::PollResult PollUntilEnded(TrackerSession& trackers,
  double maxSeconds,
  const std::function<void(const TrackerSession::PollResult&)>& check = {})
{
  TrackerSession::PollResult total;
  const auto start = std::chrono::steady_clock::now();
  while (
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < maxSeconds)
  {
    const auto r = trackers.Poll();
    if (check)
    {
      check(r);
    }
    total.grabbed |= r.grabbed;
    total.released |= r.released;
    total.cancelled |= r.cancelled;
    total.moved |= r.moved;
    if (r.ended)
    {
      total.ended = true;
      return total;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ADD_FAILURE() << "the tracker device did not stop within " << maxSeconds << " s";
  return total;
}

/// Polls (up to 2 s) until `ready` holds; false if it never did.
inline bool PollUntil(TrackerSession& trackers, const std::function<bool()>& ready)
{
  for (int i = 0; i < 400; ++i)
  {
    trackers.Poll();
    if (ready())
    {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

/// A session holding a tube along x from -150 to 150 mm (MakeTube), with warp radius R
/// `warpRadius` when it is positive.
struct TubeSession
{
  vtkSmartPointer<vtkPolyData> tube;
  BenderSession session;
  bool ready = false;

  TubeSession(double radius, int rings, int sides, double warpRadius = 0.0)
    : tube(MakeTube(-150, 150, radius, rings, sides))
  {
    this->ready = this->session.SetSurface(this->tube, "tube");
    if (this->ready && warpRadius > 0.0)
    {
      WarpParameters parameters;
      parameters.radius = warpRadius;
      this->ready = this->session.SetParameters(parameters);
    }
  }
};

} // namespace test
} // namespace bender

#endif
