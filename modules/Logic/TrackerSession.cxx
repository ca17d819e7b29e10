#include "TrackerSession.h"

#include "BenderErrors.h"
#include "BenderSession.h"
#include "TrackerDevice.h"
#include "TrackerStream.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <iomanip>
#include <sstream>

namespace bender
{

TrackerSession::TrackerSession(BenderSession& session)
  : Session(session)
{
}

TrackerSession::~TrackerSession()
{
  if (this->Device)
  {
    this->Device->Stop();
    this->Device->Close();
  }
}

bool TrackerSession::Connect(const std::string& deviceSpec,
  const TrackerDeviceOptions& options,
  const HandMapping& hands,
  const TrackerCalibration& calibration)
{
  std::unique_ptr<TrackerDevice> device;
  try
  {
    TrackerStream stream(deviceSpec, options);
    stream.Create();
    device = stream.TakeDevice();
  }
  catch (const std::exception& e) // TrackingErrors, and std::system_error of the reader thread
  {
    this->Session.AddMessage(MessageSeverity::Error, "Tracker " + deviceSpec + ": " + e.what());
    return false;
  }
  return this->Connect(std::move(device), hands, calibration);
}

bool TrackerSession::Connect(std::unique_ptr<TrackerDevice> device,
  const HandMapping& hands,
  const TrackerCalibration& calibration)
{
  this->Disconnect();
  if (!device)
  {
    this->Session.AddMessage(MessageSeverity::Error, "Tracker: no device");
    return false;
  }
  const std::string name = device->Name();
  try
  {
    auto input = std::make_unique<TwoHandRibbonInput>(hands, calibration);
    input->SetRelativeScale(this->RelativeScale);
    if (!device->IsOpen())
    {
      device->Open();
    }
    device->Start();
    this->Input = std::move(input);
  }
  catch (const std::exception& e) // TrackingErrors, and std::system_error of the reader thread
  {
    device->Stop();
    device->Close();
    this->Session.AddMessage(MessageSeverity::Error, "Tracker " + name + ": " + e.what());
    return false;
  }
  this->Device = std::move(device);
  this->DeviceName = name;
  this->Synced.reset();
  this->SyncRibbon();
  if (this->Input->IsRelative())
  {
    this->Session.AddMessage(MessageSeverity::Info,
      "Tracker " + name +
        " connected: the hands hold the ribbon where it is; press the stylus to bend from there");
  }
  else
  {
    this->Session.AddMessage(MessageSeverity::Warning,
      "Tracker " + name +
        " connected without a ribbon: the hands' absolute positions are used; place a ribbon "
        "(P) to bend from where it is");
  }
  return true;
}

void TrackerSession::Disconnect()
{
  if (!this->Device)
  {
    return;
  }
  if (this->Input && this->Input->IsGrabbing())
  {
    this->Session.CancelGrab("the tracker was disconnected");
  }
  this->Device->Stop();
  this->Device->Close();
  this->Device.reset();
  this->Input.reset();
  this->KeyPressed = false;
  this->Session.AddMessage(MessageSeverity::Info, "Tracker " + this->DeviceName + " disconnected");
}

void TrackerSession::Fail(const std::string& reason)
{
  if (this->Session.GetState() == GrabState::Grabbed)
  {
    this->Session.CancelGrab("tracker " + this->DeviceName + ": " + reason);
  }
  else
  {
    this->Session.AddMessage(
      MessageSeverity::Warning, "Tracker " + this->DeviceName + ": " + reason);
  }
  this->Disconnect();
}

void TrackerSession::SyncRibbon()
{
  if (!this->Input || this->Input->IsGrabbing() || this->Session.GetState() == GrabState::Grabbed)
  {
    return;
  }
  const std::optional<RibbonSpec>& ribbon = this->Session.GetRibbon();
  const auto same = [](const RibbonSpec& a, const RibbonSpec& b)
  {
    const auto eq = [](const Vec3& u, const Vec3& v)
    { return u.x == v.x && u.y == v.y && u.z == v.z; };
    const auto end = [&](const RibbonEnd& x, const RibbonEnd& y)
    { return eq(x.position, y.position) && eq(x.tangent, y.tangent) && eq(x.normal, y.normal); };
    return end(a.start, b.start) && end(a.end, b.end);
  };
  if (ribbon && !(this->Synced && same(*ribbon, *this->Synced)))
  {
    this->Input->AnchorTo(*ribbon);
    this->Synced = ribbon;
  }
}

bool TrackerSession::SetRelativeScale(double scale)
{
  if (!(std::isfinite(scale) && scale >= 0.0 && scale <= 1000.0))
  {
    this->Session.AddMessage(MessageSeverity::Error,
      "Tracker: motion scale " + std::to_string(scale) + " is not in [0, 1000] (0: automatic)");
    return false;
  }
  this->RelativeScale = scale;
  if (this->Input)
  {
    this->Input->SetRelativeScale(scale);
  }
  return true;
}

TrackerSession::PollResult TrackerSession::Poll()
{
  PollResult result;
  if (!this->Device || !this->Input)
  {
    return result;
  }
  if (this->KeyPressed && this->Session.GetState() != GrabState::Grabbed)
  {
    // The window ended the grab PressHands started (cancelled it): the hands let go too.
    this->KeyPressed = false;
    this->Input->HandleEvent(
      { TrackerEventType::Release, this->Input->Hands().leftStation, 0.0, {} });
    this->Synced.reset();
  }
  // The ribbon on screen changed between grabs (placed, released, cancelled, undone): the
  // hands hold it from where it is now.
  this->SyncRibbon();
  std::vector<TwoHandRibbonInput::Gesture> gestures;
  try
  {
    gestures = this->Input->Poll(*this->Device);
  }
  catch (const Error& e) // a re-anchoring the hands refuse (TrackingConfigurationError)
  {
    this->Fail(e.what());
    result.cancelled = true;
    result.ended = true;
    return result;
  }
  for (const auto& gesture : gestures)
  {
    this->Apply(gesture, result);
  }
  if (this->Session.GetState() == GrabState::Grabbed && this->Input->IsGrabbing())
  {
    if (auto ribbon = this->Input->CurrentRibbon())
    {
      result.moved = this->Session.MoveFinal(*ribbon);
    }
  }
  // The device's reader thread ended (failure or end of a replay): nothing more will come.
  if (!this->Device->IsStreaming())
  {
    const bool wasGrabbing = this->Session.GetState() == GrabState::Grabbed;
    this->Fail("the stream ended");
    result.cancelled = result.cancelled || wasGrabbing;
    result.ended = true;
  }
  return result;
}

void TrackerSession::Apply(const TwoHandRibbonInput::Gesture& gesture, PollResult& result)
{
  switch (gesture.kind)
  {
    case TwoHandRibbonInput::Gesture::Kind::Grabbed:
      if (this->Session.GetState() != GrabState::Grabbed && this->Session.Grab(gesture.initial))
      {
        result.grabbed = true;
      }
      break;
    case TwoHandRibbonInput::Gesture::Kind::Released:
      this->KeyPressed = false;
      if (this->Session.GetState() == GrabState::Grabbed)
      {
        this->Session.MoveFinal(gesture.final);
        result.released = this->ReleaseHandler ? this->ReleaseHandler() : this->Session.Release();
      }
      break;
    case TwoHandRibbonInput::Gesture::Kind::Cancelled:
      this->KeyPressed = false;
      if (this->Session.GetState() == GrabState::Grabbed)
      {
        this->Session.CancelGrab("tracker " + this->DeviceName + ": " + gesture.reason);
        result.cancelled = true;
      }
      break;
  }
}

void TrackerSession::RefreshHands()
{
  if (!this->Input || !this->Device)
  {
    return;
  }
  for (const int station : { this->Input->Hands().leftStation, this->Input->Hands().rightStation })
  {
    if (const std::optional<TrackerPose> pose = this->Device->LatestPose(station))
    {
      this->Input->UpdatePose(*pose);
    }
  }
}

bool TrackerSession::PressHands()
{
  if (!this->Device || !this->Input)
  {
    this->Session.AddMessage(
      MessageSeverity::Error, "Grab with the hands: connect a tracker first");
    return false;
  }
  if (this->Input->IsGrabbing() || this->Session.GetState() == GrabState::Grabbed)
  {
    this->Session.AddMessage(
      MessageSeverity::Error, "Grab with the hands: release or cancel the grab first");
    return false;
  }
  // From the ribbon on screen, with the hands as they are now.
  this->SyncRibbon();
  this->RefreshHands();
  const int station = this->Input->Hands().leftStation;
  const std::optional<TrackerPose> pose = this->Device->LatestPose(station);
  const std::optional<TwoHandRibbonInput::Gesture> gesture =
    this->Input->HandleEvent({ TrackerEventType::Grab, station, pose ? pose->time : 0.0, {} });
  if (!gesture)
  {
    this->Session.AddMessage(MessageSeverity::Error,
      "Grab with the hands: tracker " + this->DeviceName + " has not sent both hands yet");
    return false;
  }
  PollResult result;
  this->Apply(*gesture, result);
  if (!result.grabbed)
  {
    // The session refused (busy, no surface): the hands let go again, nothing moved.
    this->Input->HandleEvent({ TrackerEventType::Release, station, gesture->time, {} });
    return false;
  }
  this->KeyPressed = true;
  return true;
}

bool TrackerSession::ReleaseHands()
{
  if (!this->HandsPressed())
  {
    this->KeyPressed = false;
    return false;
  }
  this->RefreshHands();
  const int station = this->Input->Hands().leftStation;
  const std::optional<TrackerPose> pose = this->Device->LatestPose(station);
  const std::optional<TwoHandRibbonInput::Gesture> gesture =
    this->Input->HandleEvent({ TrackerEventType::Release, station, pose ? pose->time : 0.0, {} });
  this->KeyPressed = false;
  if (!gesture)
  {
    return false;
  }
  PollResult result;
  this->Apply(*gesture, result);
  return result.released;
}

bool TrackerSession::HandsPressed() const
{
  return this->KeyPressed && this->Input && this->Input->IsGrabbing();
}

std::optional<RibbonSpec> TrackerSession::CurrentRibbon() const
{
  if (!this->Input)
  {
    return std::nullopt;
  }
  return this->Input->CurrentRibbon();
}

void TrackerSession::SetClutch(bool engaged)
{
  if (this->Input)
  {
    this->Input->SetClutch(engaged);
  }
}

TrackerCalibration TrackerSession::GetCalibration() const
{
  return this->Input ? this->Input->Calibration() : TrackerCalibration{};
}

bool TrackerSession::SetCalibration(const TrackerCalibration& calibration)
{
  if (!this->Input)
  {
    return false;
  }
  if (this->Input->IsGrabbing())
  {
    this->Session.AddMessage(MessageSeverity::Error, "Tracker: release before calibrating");
    return false;
  }
  const std::optional<RibbonSpec> anchored =
    this->Input->Anchor() ? std::optional<RibbonSpec>(this->Input->Anchor()->ribbon) : std::nullopt;
  this->Input = std::make_unique<TwoHandRibbonInput>(this->Input->Hands(), calibration);
  this->Input->SetRelativeScale(this->RelativeScale);
  if (anchored)
  {
    this->Input->AnchorTo(*anchored);
  }
  return true;
}

TrackerStatistics TrackerSession::Statistics() const
{
  return this->Device ? this->Device->Statistics() : TrackerStatistics{};
}

std::string TrackerSession::StatusText() const
{
  if (!this->Device)
  {
    return "not connected";
  }
  std::ostringstream out;
  out << this->DeviceName << (this->Device->IsStreaming() ? ": streaming" : ": stopped");
  for (const auto& station : this->Statistics().stations)
  {
    out << ", station " << station.station << " " << std::fixed << std::setprecision(0)
        << station.RateHz() << " Hz";
  }
  if (this->Input && this->Input->IsRelative())
  {
    out << std::defaultfloat << std::setprecision(3) << "; hands anchored to the ribbon";
    if (const auto& anchor = this->Input->Anchor())
    {
      out << " (1 mm of hand motion = " << anchor->scale << " mm)";
    }
    else
    {
      out << " when both are seen";
    }
  }
  else
  {
    out << "; absolute positions (no ribbon placed)";
  }
  if (this->ClutchEngaged())
  {
    out << ", clutch engaged";
  }
  return out.str();
}

std::optional<RibbonSpec> TrackerSession::MappedHands() const
{
  if (!this->Device || !this->Input)
  {
    return std::nullopt;
  }
  const HandMapping& hands = this->Input->Hands();
  const std::optional<TrackerPose> left = this->Device->LatestPose(hands.leftStation);
  const std::optional<TrackerPose> right = this->Device->LatestPose(hands.rightStation);
  if (!left || !right)
  {
    return std::nullopt;
  }
  RibbonSpec mapped;
  if (this->Input->IsRelative())
  {
    const std::optional<RibbonAnchor>& anchor = this->Input->Anchor();
    if (!anchor)
    {
      return std::nullopt;
    }
    mapped.start = RelativeRibbonEnd(*left, Hand::Left, *anchor);
    mapped.end = RelativeRibbonEnd(*right, Hand::Right, *anchor);
  }
  else
  {
    mapped.start = RibbonEndFromPose(*left, Hand::Left, this->Input->Calibration());
    mapped.end = RibbonEndFromPose(*right, Hand::Right, this->Input->Calibration());
  }
  return mapped;
}

bool TrackerSession::AlignTo(const RibbonSpec& target)
{
  // Anchored as the hands are now, not as the last poll saw them.
  this->RefreshHands();
  if (!this->Input || !this->CurrentRibbon())
  {
    this->Session.AddMessage(MessageSeverity::Error,
      this->Input ? "Align: both hands must be seen first" : "Align: connect a tracker first");
    return false;
  }
  if (this->Input->IsGrabbing() || this->Session.GetState() == GrabState::Grabbed)
  {
    this->Session.AddMessage(MessageSeverity::Error, "Align: release or cancel the grab first");
    return false;
  }
  const std::optional<RibbonSpec> before = this->MappedHands();
  try
  {
    this->Input->AnchorTo(target);
  }
  catch (const Error& e) // TrackingConfigurationError
  {
    this->Session.AddMessage(MessageSeverity::Error, std::string("Align: ") + e.what());
    return false;
  }
  // The ribbon the session holds between grabs is the target now (SyncRibbon would otherwise
  // anchor the hands back to the session's ribbon if the two differ).
  this->Synced = this->Session.GetRibbon();
  std::ostringstream text;
  text << std::fixed << std::setprecision(1)
       << "Hands aligned: the left hand now holds the ribbon's start, the right hand its end";
  if (before)
  {
    text << " (their markers moved " << Distance(before->start.position, target.start.position)
         << " mm and " << Distance(before->end.position, target.end.position) << " mm onto them)";
  }
  if (const auto& anchor = this->Input->Anchor())
  {
    text << std::defaultfloat << std::setprecision(3) << "; 1 mm of hand motion moves an end "
         << anchor->scale << " mm; nothing was bent";
  }
  this->Session.AddMessage(MessageSeverity::Info, text.str());
  return true;
}

} // namespace bender
