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

  /// Two hands bending a ribbon and straightening it again, repeating every 14 s. Station 1
  /// is the left hand, station 2 the right (other stations rest at (0, 200, 0) mm). Both
  /// trackers hold their +x axis towards the other hand and +z up (see docs/tracking.md):
  /// - 0-1 s: at rest, left at (-100, 0, 0), right at (100, 0, 0), a straight ribbon;
  /// - 1 s: the left stylus button goes down (grab); the left hand stays where it is;
  /// - 1-4 s: the right hand moves along the circular arc of length 200 mm that leaves the
  ///   left hand along +x, and turns with it, until the arc turns by 50 degrees towards +z:
  ///   the ribbon's end bends up and the ribbon keeps its length;
  /// - 5 s: release (one warp: the bend); 5-8 s: the hands hold still;
  /// - 8 s: grab again; 8-11 s: the right hand goes back along the arc; 12 s: release (the
  ///   warp back to straight); 12-14 s: rest.
  static SimulationScript TwoHandBend();

  TrackerPose PoseAt(int station, double seconds) const;

private:
  PoseFunction Function;
};

} // namespace bender

#endif
