#include "PoseStore.h"

namespace bender
{

void PoseStore::EnableQueue(std::size_t capacity, bool block)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Capacity = capacity;
  this->Block = block;
}

bool PoseStore::Publish(const TrackerPose& pose)
{
  if (pose.station < 1 || pose.station > MaxStation)
  {
    return true;
  }
  std::unique_lock<std::mutex> lock(this->Mutex);
  if (this->Capacity > 0 && this->Block)
  {
    this->Room.wait(
      lock, [this] { return this->Cancelled || this->Queue.size() < this->Capacity; });
  }
  if (this->Cancelled)
  {
    return false;
  }
  const std::size_t s = std::size_t(pose.station);
  this->LatestPoses[s] = pose;
  StationStatistics& stats = this->Stations[s];
  if (stats.samples == 0)
  {
    stats.station = pose.station;
    stats.firstTime = pose.time;
  }
  ++stats.samples;
  stats.lastTime = pose.time;
  if (pose.button != this->Buttons[s])
  {
    this->Buttons[s] = pose.button;
    this->Events.push_back(
      TrackerEvent{ pose.button ? TrackerEventType::Grab : TrackerEventType::Release,
        pose.station,
        pose.time,
        {} });
  }
  if (this->Capacity > 0)
  {
    if (this->Queue.size() >= this->Capacity)
    {
      this->Queue.pop_front();
      ++this->Overflows;
    }
    this->Queue.push_back(pose);
  }
  lock.unlock();
  this->Activity.notify_all();
  return true;
}

void PoseStore::PublishEvent(const TrackerEvent& event)
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Events.push_back(event);
  }
  this->Activity.notify_all();
}

void PoseStore::Cancel()
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Cancelled = true;
  }
  this->Room.notify_all();
  this->Activity.notify_all();
}

void PoseStore::Rearm()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Cancelled = false;
}

void PoseStore::Clear()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->LatestPoses = {};
  this->Buttons = {};
  this->Stations = {};
  this->Queue.clear();
  this->Events.clear();
  this->Cancelled = false;
  this->Overflows = 0;
}

std::optional<TrackerPose> PoseStore::Latest(int station) const
{
  if (station < 1 || station > MaxStation)
  {
    return std::nullopt;
  }
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->LatestPoses[std::size_t(station)];
}

std::vector<TrackerEvent> PoseStore::TakeEvents()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  std::vector<TrackerEvent> events(this->Events.begin(), this->Events.end());
  this->Events.clear();
  return events;
}

std::vector<TrackerPose> PoseStore::TakePoses()
{
  std::vector<TrackerPose> poses;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    poses.assign(this->Queue.begin(), this->Queue.end());
    this->Queue.clear();
  }
  this->Room.notify_all();
  return poses;
}

bool PoseStore::WaitForActivity(std::chrono::milliseconds timeout) const
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  return this->Activity.wait_for(lock,
    timeout,
    [this] { return this->Cancelled || !this->Queue.empty() || !this->Events.empty(); });
}

TrackerStatistics PoseStore::Statistics() const
{
  TrackerStatistics stats;
  std::lock_guard<std::mutex> lock(this->Mutex);
  for (const StationStatistics& s : this->Stations)
  {
    if (s.samples > 0)
    {
      stats.stations.push_back(s);
    }
  }
  stats.queueOverflows = this->Overflows;
  return stats;
}

} // namespace bender
