#include "TwoHandRibbonInput.h"

#include "TrackerDevice.h"
#include "TrackingErrors.h"

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
}

std::optional<RibbonSpec> TwoHandRibbonInput::LiveRibbon() const
{
  if (!this->Left || !this->Right)
  {
    return std::nullopt;
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
      this->GrabStation = 0;
      gesture.kind = Gesture::Kind::Released;
      gesture.initial = *this->Initial;
      gesture.final = this->CurrentRibbon().value_or(*this->Initial);
      this->Initial.reset();
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
