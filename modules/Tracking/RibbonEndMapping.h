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

/// The hands anchored to a ribbon (the relative mapping, the default): where both hands were
/// and which ribbon they held at that moment. From then on each ribbon end moves by its hand's
/// displacement and turns by its hand's rotation since the anchor, both expressed in the
/// ribbon's frame, so that anchoring moves nothing and the ribbon never jumps.
///
/// The hands' frame at the anchor (x: from the left hand to the right one; z: the left hand's
/// +z axis made perpendicular to x) is carried onto the ribbon's frame (x: from its start to
/// its end; z: the start normal made perpendicular to x) by `rotation`: bringing the hands
/// together shortens the ribbon, tilting them arches it in its own plane, whatever the
/// ribbon's direction in the model. `scale` is model mm per tracker mm.
struct RibbonAnchor
{
  TrackerPose left;
  TrackerPose right;
  RibbonSpec ribbon;
  Quaternion rotation; ///< tracker frame -> model frame for displacements and turns
  double scale = 1.0;  ///< model mm per tracker mm, > 0
};

/// Anchors the hands at `left` and `right` to `ribbon` (model space). `motionScale` > 0 is
/// used as it is; 0 (auto) makes the hands' span the ribbon's length (scale = ribbon length /
/// distance between the hands). When the hands are closer than 1 mm, or their frame is
/// degenerate, the rotation falls back to `fallback` (the calibration's) and an auto scale to
/// 1. Throws TrackingConfigurationError for a negative or non-finite scale.
RibbonAnchor AnchorHandsToRibbon(const TrackerPose& left,
  const TrackerPose& right,
  const RibbonSpec& ribbon,
  double motionScale,
  const Quaternion& fallback = {});

/// The ribbon end a hand's current pose gives relative to `anchor`: the anchored end moved by
/// rotation * (scale * (position - anchored position)) and turned by
/// rotation * (orientation * conj(anchored orientation)) * conj(rotation).
RibbonEnd RelativeRibbonEnd(const TrackerPose& pose, Hand hand, const RibbonAnchor& anchor);

/// Parses "1,2" into stations; throws TrackingConfigurationError naming the bad item.
std::vector<int> ParseStationList(const std::string& text);

} // namespace bender

#endif
