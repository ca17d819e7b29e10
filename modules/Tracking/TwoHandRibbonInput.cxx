#include "TwoHandRibbonInput.h"

#include "TrackerDevice.h"
#include "TrackingErrors.h"

#include <cmath>
#include <string>

namespace bender
{

TwoHandRibbonInput::TwoHandRibbonInput(HandMapping hands, TrackerCalibration calibration)
  : Mapping(hands)
  , Calib(calibration)
{
  if (hands.leftStation == hands.rightStation || hands.leftStation < 1 || hands.leftStation > 4 ||
    hands.rightStation < 1 || hands.rightStation > 4)
  {
    throw TrackingConfigurationError("two-hand input: left station " +
      std::to_string(hands.leftStation) + " and right station " +
      std::to_string(hands.rightStation) + " must be different stations in 1..4");
  }
}

void TwoHandRibbonInput::UpdatePose(const TrackerPose& pose)
{
  const std::optional<Hand> hand = this->Mapping.HandOf(pose.station);
  if (hand == Hand::Left)
  {
    this->Left = pose;
  }
  else if (hand == Hand::Right)
  {
    this->Right = pose;
  }
  if (this->Target && !this->Anchored && this->Left && this->Right)
  {
    this->Reanchor(*this->Target);
  }
}

void TwoHandRibbonInput::Reanchor(const RibbonSpec& ribbon)
{
  this->Target = ribbon;
  if (this->Left && this->Right)
  {
    this->Anchored =
      AnchorHandsToRibbon(*this->Left, *this->Right, ribbon, this->Scale, this->Calib.Rotation());
  }
  else
  {
    this->Anchored.reset();
  }
}

void TwoHandRibbonInput::AnchorTo(const RibbonSpec& ribbon)
{
  this->Reanchor(ribbon);
  if (this->Frozen)
  {
    this->Frozen = ribbon;
  }
}

void TwoHandRibbonInput::SetRelativeScale(double scale)
{
  if (!(std::isfinite(scale) && scale >= 0.0 && scale <= 1000.0))
  {
    throw TrackingConfigurationError("relative tracking: motion scale " + std::to_string(scale) +
      " is not in [0, 1000] (0: automatic)");
  }
  this->Scale = scale;
  if (this->Target)
  {
    this->Reanchor(this->Anchored ? this->Anchored->ribbon : *this->Target);
  }
}

std::optional<RibbonSpec> TwoHandRibbonInput::LiveRibbon() const
{
  if (!this->Left || !this->Right)
  {
    return std::nullopt;
  }
  if (this->Target)
  {
    if (!this->Anchored)
    {
      return std::nullopt;
    }
    if (this->GrabStation == 0)
    {
      return this->Anchored->ribbon; // between grabs the ribbon stays where it is
    }
    RibbonSpec spec;
    spec.start = RelativeRibbonEnd(*this->Left, Hand::Left, *this->Anchored);
    spec.end = RelativeRibbonEnd(*this->Right, Hand::Right, *this->Anchored);
    return spec;
  }
  RibbonSpec spec;
  spec.start = RibbonEndFromPose(*this->Left, Hand::Left, this->Calib);
  spec.end = RibbonEndFromPose(*this->Right, Hand::Right, this->Calib);
  return spec;
}

std::optional<RibbonSpec> TwoHandRibbonInput::CurrentRibbon() const
{
  return this->Frozen ? this->Frozen : this->LiveRibbon();
}

void TwoHandRibbonInput::SetClutch(bool engaged)
{
  if (engaged && !this->Frozen)
  {
    this->Frozen = this->LiveRibbon();
  }
  else if (!engaged && this->Frozen && this->Target)
  {
    this->Reanchor(*this->Frozen);
    this->Frozen.reset();
  }
  else if (!engaged && this->Frozen)
  {
    const std::optional<RibbonSpec> live = this->LiveRibbon();
    if (live)
    {
      const Vec3 was = (this->Frozen->start.position + this->Frozen->end.position) * 0.5;
      const Vec3 now = (live->start.position + live->end.position) * 0.5;
      this->Calib.Translate(was - now);
    }
    this->Frozen.reset();
  }
}

std::optional<TwoHandRibbonInput::Gesture> TwoHandRibbonInput::HandleEvent(
  const TrackerEvent& event)
{
  Gesture gesture;
  gesture.station = event.station;
  gesture.time = event.time;
  switch (event.type)
  {
    case TrackerEventType::Grab:
    {
      const std::optional<RibbonSpec> ribbon = this->CurrentRibbon();
      if (this->GrabStation != 0 || !this->Mapping.HandOf(event.station) || !ribbon)
      {
        return std::nullopt;
      }
      if (this->Target && !this->Frozen)
      {
        // The hands now hold the ribbon as it is: anchored again, nothing moves.
        this->Reanchor(*ribbon);
      }
      this->GrabStation = event.station;
      this->Initial = ribbon;
      gesture.kind = Gesture::Kind::Grabbed;
      gesture.initial = *ribbon;
      return gesture;
    }
    case TrackerEventType::Release:
    {
      if (event.station != this->GrabStation)
      {
        return std::nullopt;
      }
      gesture.kind = Gesture::Kind::Released;
      gesture.initial = *this->Initial;
      // Before the grab ends: relative, the ribbon held is the one of the grab.
      gesture.final = this->CurrentRibbon().value_or(*this->Initial);
      this->GrabStation = 0;
      this->Initial.reset();
      if (this->Target)
      {
        this->Reanchor(gesture.final); // the ribbon stays where the hands left it
        if (this->Frozen)
        {
          this->Frozen = gesture.final;
        }
      }
      return gesture;
    }
    case TrackerEventType::Disconnected:
    case TrackerEventType::ReadError:
    case TrackerEventType::EndOfStream:
    {
      if (this->GrabStation == 0)
      {
        return std::nullopt;
      }
      gesture.kind = Gesture::Kind::Cancelled;
      gesture.initial = *this->Initial;
      gesture.reason = event.message.empty() ? ToString(event.type) : event.message;
      this->GrabStation = 0;
      if (this->Target)
      {
        this->Reanchor(*this->Initial); // the ribbon goes back where it was grabbed
      }
      this->Initial.reset();
      return gesture;
    }
  }
  return std::nullopt;
}

std::vector<TwoHandRibbonInput::Gesture> TwoHandRibbonInput::Poll(TrackerDevice& device)
{
  std::vector<Gesture> gestures;
  if (!this->Left || !this->Right)
  {
    for (Hand hand : { Hand::Left, Hand::Right })
    {
      if (auto pose = device.LatestPose(this->Mapping.StationOf(hand)))
      {
        this->UpdatePose(*pose);
      }
    }
  }
  // Events first, against the poses the hands had when they happened as closely as the
  // latest-pose model allows: the press captures the ribbon before this frame's motion.
  const std::vector<TrackerEvent> events = device.TakeEvents();
  for (const TrackerEvent& event : events)
  {
    if (event.type == TrackerEventType::Release)
    {
      for (Hand hand : { Hand::Left, Hand::Right })
      {
        if (auto pose = device.LatestPose(this->Mapping.StationOf(hand)))
        {
          this->UpdatePose(*pose);
        }
      }
    }
    if (auto gesture = this->HandleEvent(event))
    {
      gestures.push_back(*gesture);
    }
  }
  for (Hand hand : { Hand::Left, Hand::Right })
  {
    if (auto pose = device.LatestPose(this->Mapping.StationOf(hand)))
    {
      this->UpdatePose(*pose);
    }
  }
  return gestures;
}

} // namespace bender
