#ifndef bender_PoseStore_h
#define bender_PoseStore_h

#include "TrackerEvent.h"
#include "TrackerPose.h"
#include "TrackerStatistics.h"

#include <array>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <vector>

namespace bender
{

/// The hand-over point between a device's reader thread (Publish) and its consumers.
///
/// - Latest(station): the newest pose of a station; a copy under a mutex held for
///   microseconds, so a render loop can call it every frame without waiting on I/O.
/// - TakeEvents(): grab/release (edges of the stylus switch, the button starting released),
///   disconnect and end-of-stream events, in order.
/// - TakePoses(): every pose in order, only when EnableQueue() was called (the CLI and the
///   tests use it; the application needs only Latest). A full queue either drops its oldest
///   pose (live devices, counted in queueOverflows) or makes Publish wait (replay, so that
///   nothing is lost); Cancel() releases a waiting Publish.
class PoseStore
{
public:
  static constexpr int MaxStation = 4;

  /// capacity > 0; block: Publish waits for room instead of dropping the oldest pose.
  void EnableQueue(std::size_t capacity, bool block);

  /// Reader side. Returns false when cancelled while waiting for room.
  bool Publish(const TrackerPose& pose);
  void PublishEvent(const TrackerEvent& event);
  /// Wakes and refuses waiting/future publishers until Clear().
  void Cancel();
  /// Accepts publishers again after Cancel(), keeping what is stored.
  void Rearm();
  /// Forgets poses, events, button states and statistics; re-arms after Cancel().
  void Clear();

  /// Consumer side.
  std::optional<TrackerPose> Latest(int station) const;
  std::vector<TrackerEvent> TakeEvents();
  std::vector<TrackerPose> TakePoses();
  /// Waits until a pose is queued or an event is pending, at most `timeout`.
  bool WaitForActivity(std::chrono::milliseconds timeout) const;
  /// Per-station counts and rates plus the queue overflow count (other fields zero).
  TrackerStatistics Statistics() const;

private:
  mutable std::mutex Mutex;
  mutable std::condition_variable Activity;
  std::condition_variable Room;
  std::array<std::optional<TrackerPose>, MaxStation + 1> LatestPoses;
  std::array<bool, MaxStation + 1> Buttons{};
  std::array<StationStatistics, MaxStation + 1> Stations{};
  std::deque<TrackerPose> Queue;
  std::deque<TrackerEvent> Events;
  std::size_t Capacity = 0;
  bool Block = false;
  bool Cancelled = false;
  std::uint64_t Overflows = 0;
};

} // namespace bender

#endif
