#ifndef bender_TrackerDevice_h
#define bender_TrackerDevice_h

#include "PoseStore.h"
#include "TrackerEvent.h"
#include "TrackerPose.h"
#include "TrackerStatistics.h"

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace bender
{

/// A 6-DoF tracker: a Fastrak over some Transport, or the simulator.
///
/// Life cycle: Open() -> Start() -> (LatestPose/TakeEvents from any thread) -> Stop() ->
/// Close(). After a Disconnected event, Close() and Open() again reconnect without
/// restarting the application. Start() runs a reader thread (StartReader); Stop() joins it
/// within one read timeout (StopReader). Open() and Start() throw TrackingError subclasses; Stop()
/// and Close() never throw. The destructor of a concrete device stops and closes it.
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
  /// Whether the reader thread runs (devices that use StartReader); false once it ended.
  virtual bool IsStreaming() const { return this->Streaming.load(); }

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
  /// For Start(): true while the reader thread still runs (nothing to start); otherwise an
  /// ended reader is joined and false returned.
  bool ReaderRunning();
  /// Starts `loop` on the reader thread, with the pose store rearmed, IsStreaming() true and
  /// ReaderTime() counting from now.
  void StartReader(std::function<void()> loop);
  /// For Stop(): asks the reader to stop, wakes the store's waits and joins the thread.
  void StopReader();
  /// The reader's loop condition.
  bool StopRequested() const { return this->StopFlag.load(); }
  /// The reader ends by itself (end of a stream, a failure): IsStreaming() is false from now.
  void ReaderEnded() { this->Streaming = false; }
  /// Seconds since StartReader (steady clock).
  double ReaderTime() const;

  PoseStore Store;

private:
  std::thread Reader;
  std::atomic<bool> StopFlag{ false };
  std::atomic<bool> Streaming{ false };
  std::chrono::steady_clock::time_point ReaderStart;
};

} // namespace bender

#endif
