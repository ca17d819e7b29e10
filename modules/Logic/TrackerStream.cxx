#include "TrackerStream.h"

#include "FastrakEncoding.h"
#include "StreamRecorder.h"
#include "TrackingErrors.h"

#include <chrono>
#include <sstream>

namespace bender
{

TrackerStream::TrackerStream(const std::string& spec, TrackerDeviceOptions options)
  : DeviceSpec(TrackerDeviceSpec::Parse(spec))
  , DeviceKind(FindTrackerDeviceKind(DeviceSpec.kind))
  , Options(std::move(options))
{
}

TrackerStream::~TrackerStream()
{
  this->Close();
}

TrackerDevice& TrackerStream::Create()
{
  if (this->Device)
  {
    return *this->Device;
  }
  TrackerDeviceOptions deviceOptions = this->Options;
  if (!this->DeviceKind.recordsBytes && !this->Options.recordPath.empty())
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
  const std::string& silentHint = this->DeviceKind.silentHint;
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
  if (result.failure.empty() && result.poses == 0 && this->DeviceKind.noPoses)
  {
    result.noPoses = this->DeviceKind.noPoses(this->DeviceSpec, this->Options);
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
