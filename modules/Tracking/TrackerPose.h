#ifndef bender_TrackerPose_h
#define bender_TrackerPose_h

#include "Quaternion.h"
#include "Vec3.h"

#include <string>

namespace bender
{

/// One decoded sample of one tracker station.
///
/// Frame: the tracker (transmitter) frame of the Fastrak, right-handed, origin at the
/// transmitter, as configured by the hemisphere command. Units: millimetres.
/// `orientation` is a unit quaternion in the order (w, x, y, z); it rotates vectors given in
/// the receiver's local frame into the transmitter frame (so the receiver's local x axis in
/// tracker space is RotateByQuaternion(orientation, {1, 0, 0})).
struct TrackerPose
{
  int station = 0;        ///< 1..4
  Vec3 position;          ///< mm, tracker frame
  Quaternion orientation; ///< unit, (w, x, y, z), receiver -> tracker frame
  bool button = false;    ///< stylus switch pressed
  char status = ' ';      ///< Fastrak status byte: ' ' when fine, a letter for a warning
  /// Seconds since the device started streaming (steady clock), or the receive time stored
  /// in a recording when replaying one.
  double time = 0.0;
};

/// A pose as received from a device that names its poses (OpenIGTLink device names), with
/// that name; `pose.station` is the hand's station, 0 for a name that is no hand's.
struct NamedTrackerPose
{
  std::string name;
  TrackerPose pose;
};

} // namespace bender

#endif
