#include "TrackerSession.h"

#include "BenderErrors.h"
#include "BenderSession.h"
#include "TrackerDevice.h"

#include <algorithm>
#include <array>
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
    device = CreateTrackerDevice(TrackerDeviceSpec::Parse(deviceSpec), options);
  }
  catch (const std::exception& e)
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
    if (!device->IsOpen())
    {
      device->Open();
    }
    device->Start();
    this->Input = std::move(input);
  }
  catch (const std::exception& e)
  {
    device->Stop();
    device->Close();
    this->Session.AddMessage(MessageSeverity::Error, "Tracker " + name + ": " + e.what());
    return false;
  }
  this->Device = std::move(device);
  this->DeviceName = name;
  this->Session.AddMessage(MessageSeverity::Info, "Tracker " + name + " connected");
  return true;
}

std::unique_ptr<TrackerDevice> TrackerSession::OpenDevice(const std::string& deviceSpec,
  const TrackerDeviceOptions& options)
{
  std::unique_ptr<TrackerDevice> device;
  try
  {
    device = CreateTrackerDevice(TrackerDeviceSpec::Parse(deviceSpec), options);
    device->Open();
  }
  catch (const std::exception& e)
  {
    if (device)
    {
      device->Close();
    }
    throw Error("Tracker " + deviceSpec + ": " + e.what());
  }
  return device;
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

TrackerSession::PollResult TrackerSession::Poll()
{
  PollResult result;
  if (!this->Device || !this->Input)
  {
    return result;
  }
  std::vector<TwoHandRibbonInput::Gesture> gestures;
  try
  {
    gestures = this->Input->Poll(*this->Device);
  }
  catch (const std::exception& e)
  {
    this->Fail(e.what());
    result.cancelled = true;
    result.ended = true;
    return result;
  }
  for (const auto& gesture : gestures)
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
        if (this->Session.GetState() == GrabState::Grabbed)
        {
          this->Session.MoveFinal(gesture.final);
          result.released = this->ReleaseHandler ? this->ReleaseHandler() : this->Session.Release();
        }
        break;
      case TwoHandRibbonInput::Gesture::Kind::Cancelled:
        if (this->Session.GetState() == GrabState::Grabbed)
        {
          this->Session.CancelGrab("tracker " + this->DeviceName + ": " + gesture.reason);
          result.cancelled = true;
        }
        break;
    }
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
  this->Input = std::make_unique<TwoHandRibbonInput>(this->Input->Hands(), calibration);
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
  if (this->ClutchEngaged())
  {
    out << ", clutch engaged";
  }
  return out.str();
}

bool TrackerSession::AlignTo(const RibbonSpec& target)
{
  const std::optional<RibbonSpec> hands = this->CurrentRibbon();
  if (!hands)
  {
    this->Session.AddMessage(MessageSeverity::Error, "Align: both hands must be seen first");
    return false;
  }
  auto landmarks = [](const RibbonSpec& r)
  {
    const double arm = std::max(1.0, 0.5 * Distance(r.start.position, r.end.position));
    const Vec3 t = Normalized(r.start.tangent);
    const Vec3 n = Normalized(r.start.normal - t * Dot(r.start.normal, t));
    return std::array<Vec3, 3>{ { r.start.position, r.end.position, r.start.position + n * arm } };
  };
  const TrackerCalibration current = this->GetCalibration();
  try
  {
    const TrackerCalibration align =
      TrackerCalibration::FromThreePoints(landmarks(*hands), landmarks(target), 1.0);
    // align(current(x)) = Ra (Rc s x + tc) + ta
    const TrackerCalibration composed(align.Rotation() * current.Rotation(),
      align.MapPoint(current.Translation()),
      current.MotionScale());
    if (!this->SetCalibration(composed))
    {
      return false;
    }
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(MessageSeverity::Error,
      std::string("Align: ") + e.what() + " (hold the hands apart, as the ribbon's ends)");
    return false;
  }
  this->Session.AddMessage(
    MessageSeverity::Info, "Trackers aligned to the ribbon (position and orientation)");
  return true;
}

} // namespace bender
