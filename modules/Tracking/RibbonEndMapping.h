#ifndef bender_RibbonEndMapping_h
#define bender_RibbonEndMapping_h

#include "TrackerCalibration.h"
#include "TrackerPose.h"
#include "WarpPlan.h"

#include <optional>
#include <string>
#include <vector>

namespace bender
{

enum class Hand
{
  Left, ///< holds the ribbon's start
  Right ///< holds the ribbon's end
};

/// Which station is in which hand (configurable; the Fastrak numbers its receivers 1..4).
struct HandMapping
{
  int leftStation = 1;
  int rightStation = 2;

  /// The hand holding `station`, if any.
  std::optional<Hand> HandOf(int station) const;
  int StationOf(Hand hand) const
  {
    return hand == Hand::Left ? this->leftStation : this->rightStation;
  }
};

/// One end of the ribbon from one tracker, in model space (through `calibration`).
///
/// Convention: each hand holds its tracker with the receiver's local +x axis pointing
/// towards the other hand (along the ribbon, into it) and local +z along the ribbon normal.
/// Then
/// - position = calibration.MapPoint(pose.position);
/// - normal   = R(q) * (0, 0, 1)  (both hands);
/// - tangent  = R(q) * (1, 0, 0)  for the left hand (start: travel goes from it into the
///              ribbon, the way its +x points), and -R(q) * (1, 0, 0) for the right hand
///              (end: travel leaves the ribbon there, opposite to where its +x points),
/// where R(q) is the pose's orientation mapped by the calibration's rotation. Two trackers
/// held facing each other thus give a straight, untwisted ribbon.
RibbonEnd RibbonEndFromPose(const TrackerPose& pose,
  Hand hand,
  const TrackerCalibration& calibration);

/// Parses "1,2" into stations; throws TrackingConfigurationError naming the bad item.
std::vector<int> ParseStationList(const std::string& text);

} // namespace bender

#endif
