#ifndef bender_SimulationScript_h
#define bender_SimulationScript_h

#include "TrackerPose.h"

#include <functional>

namespace bender
{

/// Scripted tracker motion: the pose of each station as a function of time, for demos
/// without hardware and for tests. Poses are in the tracker frame (mm), like a Fastrak's.
class SimulationScript
{
public:
  /// f(station, seconds) -> pose; the station and time fields are filled in by PoseAt.
  using PoseFunction = std::function<TrackerPose(int station, double seconds)>;

  explicit SimulationScript(PoseFunction function);

  /// Two hands bending and twisting a ribbon, repeating every 8 s. Station 1 is the left
  /// hand, station 2 the right (other stations rest at (0, 200, 0) mm). Both trackers hold
  /// their +x axis towards the other hand and +z up (see docs/tracking.md):
  /// - 0-1 s: at rest, left at (-100, 0, 0), right at (100, 0, 0), a straight ribbon;
  /// - 1 s: the left stylus button goes down (grab) and stays down until 5 s (release);
  /// - 1-4 s: both hands tilt their +x axis up by up to 60 degrees (an arch), move 20 mm
  ///   inwards, and the right hand rolls by up to 45 degrees about its +x axis (a twist);
  /// - 4-5 s: hold; 5-7 s: back to rest; 7-8 s: rest.
  static SimulationScript TwoHandBend();

  TrackerPose PoseAt(int station, double seconds) const;

private:
  PoseFunction Function;
};

} // namespace bender

#endif
