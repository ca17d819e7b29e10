#include "TrackerStream.h"

#include "FastrakEncoding.h"
#include "FileIdentity.h"
#include "StreamRecorder.h"
#include "TrackingErrors.h"

#include <chrono>
#include <sstream>

namespace bender
{

namespace
{
bool RecordsBytes(TrackerDeviceSpec::Kind kind)
{
  return kind == TrackerDeviceSpec::Kind::Usb || kind == TrackerDeviceSpec::Kind::Serial ||
    kind == TrackerDeviceSpec::Kind::Replay;
}

// What a device that sends no pose within the timeout is told to check; empty: never silent.
std::string SilentHint(TrackerDeviceSpec::Kind kind)
{
  switch (kind)
  {
    case TrackerDeviceSpec::Kind::Simulator:
      return {};
    case TrackerDeviceSpec::Kind::Igtl:
      return "does the server stream TRANSFORM, POSITION, QTDATA or TDATA messages?";
    default:
      return "is the Fastrak switched on, its receivers plugged in and streaming?";
  }
}
} // namespace

TrackerStream::TrackerStream(const std::string& spec, TrackerDeviceOptions options)
  : DeviceSpec(TrackerDeviceSpec::Parse(spec))
  , Options(std::move(options))
{
}

TrackerStream::~TrackerStream()
{
  this->Close();
}

bool TrackerStream::IsLive() const
{
  const TrackerDeviceSpec::Kind kind = this->DeviceSpec.kind;
  return kind == TrackerDeviceSpec::Kind::Usb || kind == TrackerDeviceSpec::Kind::Serial ||
    kind == TrackerDeviceSpec::Kind::Igtl;
}

TrackerDevice& TrackerStream::Create()
{
  if (this->Device)
  {
    return *this->Device;
  }
  // Recording over the file being replayed would truncate it before it is read.
  if (this->DeviceSpec.kind == TrackerDeviceSpec::Kind::Replay &&
    !this->Options.recordPath.empty() && SameFile(this->DeviceSpec.path, this->Options.recordPath))
  {
    throw RecordingError(
      this->Options.recordPath + ": refusing to record over the recording being replayed");
  }
  TrackerDeviceOptions deviceOptions = this->Options;
  if (!RecordsBytes(this->DeviceSpec.kind) && !this->Options.recordPath.empty())
  {
    this->PoseRecorder = std::make_unique<StreamRecorder>(this->Options.recordPath);
    deviceOptions.recordPath.clear();
  }
  this->Device = CreateTrackerDevice(this->DeviceSpec, deviceOptions);
  return *this->Device;
}

void TrackerStream::Open()
{
  TrackerDevice& device = this->Create();
  if (!device.IsOpen())
  {
    device.Open();
  }
}

void TrackerStream::Record(const TrackerPose& pose)
{
  if (this->PoseRecorder && pose.station >= 1)
  {
    const std::vector<std::uint8_t> record = EncodeFastrakRecord(pose, FastrakFormat::Binary);
    this->PoseRecorder->Append(record.data(), record.size(), pose.time);
  }
}

TrackerStream::Result TrackerStream::Run(const Limits& limits,
  const Sink& sink,
  const std::function<bool()>& cancelled)
{
  Result result;
  TrackerDevice& device = this->Create();
  // A recording or the simulator: lose nothing (the reader waits for us); live: keep the newest.
  device.EnablePoseQueue(4096, !this->IsLive());
  // A device that names its poses hands out every pose with its name, hands or not.
  const bool named = device.EnableNamedQueue(4096);
  this->Open();
  device.Start();
  const std::string silentHint = SilentHint(this->DeviceSpec.kind);
  const auto started = std::chrono::steady_clock::now();
  bool done = false;
  while (!done)
  {
    if (cancelled && cancelled())
    {
      result.interrupted = true;
      break;
    }
    device.WaitForActivity(std::chrono::milliseconds(100));
    const std::vector<TrackerEvent> events = device.TakeEvents();
    std::vector<NamedTrackerPose> poses;
    if (named)
    {
      poses = device.TakeNamedPoses();
    }
    else
    {
      for (const TrackerPose& pose : device.TakePoses())
      {
        poses.push_back({ {}, pose });
      }
    }
    for (const NamedTrackerPose& item : poses)
    {
      if (limits.duration > 0.0 && item.pose.time > limits.duration)
      {
        done = true;
        break;
      }
      if (sink.pose)
      {
        sink.pose(item.pose, named ? &item.name : nullptr);
      }
      this->Record(item.pose);
      ++result.poses;
      if (limits.count > 0 && result.poses >= limits.count)
      {
        done = true;
        break;
      }
    }
    if (sink.batchDone)
    {
      sink.batchDone();
    }
    for (const TrackerEvent& event : events)
    {
      if (event.type == TrackerEventType::Grab || event.type == TrackerEventType::Release)
      {
        if (sink.event)
        {
          sink.event(event);
        }
      }
      else if (event.type == TrackerEventType::EndOfStream)
      {
        done = true;
      }
      else if (!done)
      {
        result.failure = device.Name() + ": " + event.message;
        done = true;
      }
    }
    if (!done && result.poses == 0 && !silentHint.empty() &&
      std::chrono::steady_clock::now() - started > std::chrono::duration<double>(limits.timeout))
    {
      std::ostringstream text;
      text << device.Name() << ": no pose within " << limits.timeout << " s; " << silentHint;
      result.failure = text.str();
      done = true;
    }
  }
  device.Stop();
  if (result.failure.empty() && result.poses == 0 &&
    this->DeviceSpec.kind == TrackerDeviceSpec::Kind::Replay)
  {
    result.noPoses = this->DeviceSpec.path + ": no pose decoded (not a Fastrak " +
      (this->Options.format == FastrakFormat::Binary ? "binary" : "ASCII") +
      " recording with the output list 2,11,16,0?)";
  }
  return result;
}

void TrackerStream::Close()
{
  if (this->Device)
  {
    this->Device->Stop();
    this->Device->Close();
  }
  this->PoseRecorder.reset();
}

TrackerStatistics TrackerStream::Statistics() const
{
  return this->Device ? this->Device->Statistics() : TrackerStatistics{};
}

std::vector<std::string> TrackerStream::SummaryLines() const
{
  return this->Device ? this->Device->SummaryLines() : std::vector<std::string>{};
}

std::unique_ptr<TrackerDevice> TrackerStream::TakeDevice()
{
  return std::move(this->Device);
}

} // namespace bender
