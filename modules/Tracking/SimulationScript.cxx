#include "SimulationScript.h"

#include <algorithm>
#include <cmath>

namespace bender
{

namespace
{
constexpr double Pi = 3.14159265358979323846;

Quaternion AxisAngle(const Vec3& axis, double angle)
{
  const Vec3 k = Normalized(axis);
  const double s = std::sin(angle / 2.0);
  return { std::cos(angle / 2.0), k.x * s, k.y * s, k.z * s };
}

double SmoothStep(double x)
{
  x = x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);
  return x * x * (3.0 - 2.0 * x);
}

constexpr double Cycle = 14.0;                  // seconds
constexpr double BendAngle = 50.0 * Pi / 180.0; // the right hand's end turns by this much
constexpr double Span = 200.0;                  // mm between the hands at rest

// Amount of bend in [0, 1] over the cycle: bent over 1-4 s, straightened over 8-11 s.
double Bend(double t)
{
  if (t < 8.0)
  {
    return SmoothStep((t - 1.0) / 3.0);
  }
  return 1.0 - SmoothStep((t - 8.0) / 3.0);
}

// The left stylus: down over 1-5 s (the bend) and 8-12 s (the way back).
bool Pressed(double t)
{
  return (t >= 1.0 && t < 5.0) || (t >= 8.0 && t < 12.0);
}
} // namespace

SimulationScript::SimulationScript(PoseFunction function)
  : Function(std::move(function))
{
}

SimulationScript SimulationScript::TwoHandBend()
{
  return SimulationScript(
    [](int station, double seconds)
    {
      const double t = std::fmod(std::max(0.0, seconds), Cycle);
      const double angle = Bend(t) * BendAngle;
      TrackerPose pose;
      if (station == 1)
      {
        pose.position = { -Span / 2.0, 0.0, 0.0 };
        pose.button = Pressed(t);
      }
      else if (station == 2)
      {
        // On the circular arc of length Span that leaves the left hand along +x and turns by
        // `angle` towards +z: the ribbon between the hands keeps its length.
        const double along = angle > 1e-9 ? Span * std::sin(angle) / angle : Span;
        const double up = angle > 1e-9 ? Span * (1.0 - std::cos(angle)) / angle : 0.0;
        pose.position = { -Span / 2.0 + along, 0.0, up };
        // +x towards the other hand (against the arc's tangent), +z the arc's normal.
        pose.orientation = AxisAngle({ 0, 1, 0 }, -angle) * AxisAngle({ 0, 0, 1 }, Pi);
      }
      else
      {
        pose.position = { 0.0, 200.0, 0.0 };
      }
      return pose;
    });
}

TrackerPose SimulationScript::PoseAt(int station, double seconds) const
{
  TrackerPose pose = this->Function(station, seconds);
  pose.station = station;
  pose.time = seconds;
  return pose;
}

} // namespace bender
