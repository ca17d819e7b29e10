#ifndef bender_TwoHandRibbonInput_h
#define bender_TwoHandRibbonInput_h

#include "RibbonEndMapping.h"
#include "TrackerCalibration.h"
#include "TrackerEvent.h"
#include "TrackerPose.h"
#include "WarpPlan.h"

#include <optional>
#include <string>
#include <vector>

namespace bender
{

class TrackerDevice;

/// Turns two trackers into the ribbon of the paper: the left hand's pose sets the start,
/// the right hand's the end (RibbonEndFromPose), the stylus button grabs and releases.
///
/// - Grab: a Grab event from either hand's station, while idle and with both hands seen,
///   captures the initial ribbon. Release of that same station commits the final ribbon.
/// - Disconnected/ReadError while grabbing cancels the gesture (the application keeps the
///   last committed shape). EndOfStream while grabbing cancels too.
/// - Mapping: absolute (through the calibration) until AnchorTo() gives a ribbon; from then on
///   relative (RibbonAnchor): the hands are anchored to that ribbon as soon as both are seen,
///   the ribbon stays where it is between grabs (the hands move freely: the stylus button is
///   the clutch), each grab re-anchors the hands to the ribbon as it is, and while grabbing
///   the ends move by the hands' displacements and turn by their rotations (RelativeRibbonEnd).
///   Nothing jumps: anchoring reproduces the ribbon exactly.
/// - Clutch: while engaged the ribbon stays where it is and the hands move freely. On release,
///   relative: the hands are re-anchored to the frozen ribbon; absolute: the calibration's
///   translation is shifted so that the midpoint of the two hands maps to where it was when
///   the clutch engaged (orientations stay absolute).
/// extraTurns of the ribbons is 0.
class TwoHandRibbonInput
{
public:
  struct Gesture
  {
    enum class Kind
    {
      Grabbed,  ///< `initial` is the ribbon at the press
      Released, ///< `initial` and `final` make one warp
      Cancelled ///< `reason` says why; no warp
    };
    Kind kind = Kind::Grabbed;
    int station = 0;
    double time = 0.0;
    RibbonSpec initial;
    RibbonSpec final;
    std::string reason;
  };

  /// Throws TrackingConfigurationError when both hands use the same station or one is
  /// outside 1..4.
  explicit TwoHandRibbonInput(HandMapping hands = {}, TrackerCalibration calibration = {});

  /// Feeds one pose (other stations are ignored).
  void UpdatePose(const TrackerPose& pose);
  /// Feeds one event; returns the gesture step it makes, if any.
  std::optional<Gesture> HandleEvent(const TrackerEvent& event);
  /// Takes the latest poses of both hands and the pending events from `device`.
  std::vector<Gesture> Poll(TrackerDevice& device);

  /// The ribbon the hands hold now (frozen while the clutch is engaged); empty until both
  /// hands have been seen.
  std::optional<RibbonSpec> CurrentRibbon() const;
  bool IsGrabbing() const { return this->GrabStation != 0; }

  void SetClutch(bool engaged);
  bool ClutchEngaged() const { return this->Frozen.has_value(); }

  /// Switches to the relative mapping and anchors the hands to `ribbon` (model space) now, or
  /// when both hands are first seen. While grabbing, the gesture goes on from `ribbon`.
  void AnchorTo(const RibbonSpec& ribbon);
  bool IsRelative() const { return this->Target.has_value(); }
  /// The anchor in use (relative mapping, both hands seen).
  const std::optional<RibbonAnchor>& Anchor() const { return this->Anchored; }
  /// Motion scale of the relative mapping: > 0 model mm per hand mm, 0 (the default) automatic:
  /// the hands' span is the ribbon's length at each anchoring. Throws
  /// TrackingConfigurationError outside [0, 1000].
  void SetRelativeScale(double scale);
  double RelativeScale() const { return this->Scale; }

  const TrackerCalibration& Calibration() const { return this->Calib; }
  const HandMapping& Hands() const { return this->Mapping; }

private:
  std::optional<RibbonSpec> LiveRibbon() const;
  void Reanchor(const RibbonSpec& ribbon);

  HandMapping Mapping;
  TrackerCalibration Calib;
  std::optional<TrackerPose> Left;
  std::optional<TrackerPose> Right;
  std::optional<RibbonSpec> Frozen;
  std::optional<RibbonSpec> Initial;
  std::optional<RibbonSpec> Target; // relative mapping: the ribbon to anchor to
  std::optional<RibbonAnchor> Anchored;
  double Scale = 0.0;
  int GrabStation = 0;
};

} // namespace bender

#endif
