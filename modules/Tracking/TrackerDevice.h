#ifndef bender_TrackerDevice_h
#define bender_TrackerDevice_h

#include "PoseStore.h"
#include "TrackerEvent.h"
#include "TrackerPose.h"
#include "TrackerStatistics.h"

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace bender
{

/// A 6-DoF tracker: a Fastrak over some Transport, or the simulator.
///
/// Life cycle: Open() -> Start() -> (LatestPose/TakeEvents from any thread) -> Stop() ->
/// Close(). After a Disconnected event, Close() and Open() again reconnect without
/// restarting the application. Start() runs a reader thread; Stop() joins it within one read
/// timeout. Open() and Start() throw TrackingError subclasses; Stop() and Close() never
/// throw. The destructor of a concrete device stops and closes it.
class TrackerDevice
{
public:
  virtual ~TrackerDevice() = default;

  virtual std::string Name() const = 0;
  virtual void Open() = 0;
  virtual void Start() = 0;
  virtual void Stop() = 0;
  virtual void Close() = 0;
  virtual bool IsOpen() const = 0;
  virtual bool IsStreaming() const = 0;

  /// Newest pose of station 1..4, never waits on the device (see PoseStore).
  std::optional<TrackerPose> LatestPose(int station) const { return this->Store.Latest(station); }
  std::vector<TrackerEvent> TakeEvents() { return this->Store.TakeEvents(); }
  /// Every pose in order; only after EnablePoseQueue().
  std::vector<TrackerPose> TakePoses() { return this->Store.TakePoses(); }
  void EnablePoseQueue(std::size_t capacity, bool block)
  {
    this->Store.EnableQueue(capacity, block);
  }
  bool WaitForActivity(std::chrono::milliseconds timeout) const
  {
    return this->Store.WaitForActivity(timeout);
  }
  virtual TrackerStatistics Statistics() const { return this->Store.Statistics(); }

  /// A device that names its poses (OpenIGTLink) keeps, once this is called, every pose with
  /// its name (hands or not; bounded, oldest dropped) for TakeNamedPoses, so that a user sees
  /// everything a server sends. False, and nothing kept, for a device without names.
  virtual bool EnableNamedQueue(std::size_t capacity)
  {
    (void)capacity;
    return false;
  }
  virtual std::vector<NamedTrackerPose> TakeNamedPoses() { return {}; }
  /// What this kind of device counts beyond Statistics(), one line each without indentation,
  /// for a summary at the end of a stream (OpenIGTLink: messages, device names, CRC errors,
  /// the last STATUS); empty for a device with nothing more to say.
  virtual std::vector<std::string> SummaryLines() const { return {}; }
  /// The same, short, for a status panel updated while streaming (a few lines); empty when the
  /// device has nothing more to say.
  virtual std::string CountersText() const { return {}; }

protected:
  PoseStore Store;
};

} // namespace bender

#endif
