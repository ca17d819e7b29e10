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

// Amount of bend in [0, 1] over the 8-second cycle.
double Bend(double t)
{
  if (t < 1.0)
  {
    return 0.0;
  }
  if (t < 4.0)
  {
    return SmoothStep((t - 1.0) / 3.0);
  }
  if (t < 5.0)
  {
    return 1.0;
  }
  return 1.0 - SmoothStep((t - 5.0) / 2.0);
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
      const double t = std::fmod(std::max(0.0, seconds), 8.0);
      const double u = Bend(t);
      const double tilt = u * Pi / 3.0;
      TrackerPose pose;
      if (station == 1)
      {
        pose.position = { -100.0 + 20.0 * u, 0.0, 0.0 };
        pose.orientation = AxisAngle({ 0, 1, 0 }, -tilt);
        pose.button = t >= 1.0 && t < 5.0;
      }
      else if (station == 2)
      {
        pose.position = { 100.0 - 20.0 * u, 0.0, 0.0 };
        pose.orientation = AxisAngle({ 0, 1, 0 }, tilt) * AxisAngle({ 0, 0, 1 }, Pi) *
          AxisAngle({ 1, 0, 0 }, u * Pi / 4.0);
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
