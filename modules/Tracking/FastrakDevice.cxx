#include "FastrakDevice.h"

#include "TrackingErrors.h"

#include <algorithm>

namespace bender
{

FastrakDevice::FastrakDevice(std::string name, TransportFactory factory, FastrakOptions options)
  : DeviceName(std::move(name))
  , Factory(std::move(factory))
  , Opts(std::move(options))
{
  if (this->Opts.stations.empty())
  {
    throw TrackingConfigurationError(this->DeviceName + ": no station to read");
  }
  for (int s : this->Opts.stations)
  {
    if (s < 1 || s > 4)
    {
      throw TrackingConfigurationError(
        this->DeviceName + ": station " + std::to_string(s) + " is outside 1..4");
    }
  }
}

FastrakDevice::~FastrakDevice()
{
  this->Close();
}

void FastrakDevice::Send(const std::string& command)
{
  this->Link->WriteText(command, this->Opts.writeTimeout);
}

void FastrakDevice::Open()
{
  if (this->Link)
  {
    return;
  }
  this->Link = this->Factory();
  try
  {
    this->Link->Flush();
    {
      std::lock_guard<std::mutex> lock(this->StatsMutex);
      this->ParserStats = {};
      this->Filtered = 0;
      this->LatencyMs.reset();
    }
    this->Store.Clear();
    if (this->Opts.configure)
    {
      this->Configure();
    }
  }
  catch (...)
  {
    this->Link->Close();
    this->Link.reset();
    throw;
  }
}

void FastrakDevice::Configure()
{
  // Stop a unit left streaming by a previous session, then drop what it already sent.
  this->Send("c");
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  this->Link->Flush();
  if (this->Opts.reset)
  {
    this->Send("\x19");
    std::this_thread::sleep_for(this->Opts.resetWait);
    this->Link->Flush();
    this->Send("c");
  }
  this->Send("u");
  this->Send(this->Opts.format == FastrakFormat::Binary ? "f" : "F");
  for (int s = 1; s <= 4; ++s)
  {
    const bool active = std::find(this->Opts.stations.begin(), this->Opts.stations.end(), s) !=
      this->Opts.stations.end();
    this->Send("l" + std::to_string(s) + (active ? ",1\r" : ",0\r"));
  }
  for (int s : this->Opts.stations)
  {
    const std::string n = std::to_string(s);
    this->Send("H" + n + "," + std::to_string(this->Opts.hemisphere[0]) + "," +
      std::to_string(this->Opts.hemisphere[1]) + "," + std::to_string(this->Opts.hemisphere[2]) +
      "\r");
    this->Send("O" + n + ",2,11,16,0\r");
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  this->Link->Flush();
  if (this->Opts.measureLatency)
  {
    this->MeasureLatency();
  }
}

void FastrakDevice::MeasureLatency()
{
  FastrakParser::Options parserOptions;
  parserOptions.format = this->Opts.format;
  std::vector<double> samples;
  std::uint8_t buffer[512];
  for (int round = 0; round < 5; ++round)
  {
    FastrakParser parser(parserOptions);
    std::vector<TrackerPose> poses;
    const auto sent = std::chrono::steady_clock::now();
    const auto deadline = sent + this->Opts.replyTimeout;
    this->Send("P");
    // 'P' answers one record per active station; the last one ends the round trip.
    while (poses.size() < this->Opts.stations.size() && std::chrono::steady_clock::now() < deadline)
    {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
      const std::size_t n =
        this->Link->Read(buffer, sizeof buffer, std::max(std::chrono::milliseconds(1), left));
      parser.Feed(buffer, n, 0.0, poses);
    }
    if (poses.empty())
    {
      throw DeviceNotRespondingError(this->DeviceName + ": no reply to a single-record request " +
        "('P') within " + std::to_string(this->Opts.replyTimeout.count()) +
        " ms; is the Fastrak switched on, out of its boot, and at the configured baud rate?");
    }
    samples.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - sent).count());
  }
  std::sort(samples.begin(), samples.end());
  std::lock_guard<std::mutex> lock(this->StatsMutex);
  this->LatencyMs = samples[samples.size() / 2];
}

void FastrakDevice::Start()
{
  if (!this->Link)
  {
    throw TrackingError(this->DeviceName + ": Start() before Open()");
  }
  if (this->ReaderRunning())
  {
    return;
  }
  if (this->Opts.configure)
  {
    this->Send("C");
  }
  this->StartReader([this] { this->ReaderLoop(); });
}

void FastrakDevice::Stop()
{
  this->StopReader();
  if (this->Link && this->Opts.configure)
  {
    try
    {
      this->Send("c");
    }
    catch (const TrackingError&)
    {
      // The unit is gone (that is often why we stop); nothing to switch off.
    }
  }
}

void FastrakDevice::Close()
{
  this->Stop();
  if (this->Link)
  {
    this->Link->Close();
    this->Link.reset();
  }
}

void FastrakDevice::ReaderLoop()
{
  FastrakParser::Options parserOptions;
  parserOptions.format = this->Opts.format;
  FastrakParser parser(parserOptions);
  std::vector<std::uint8_t> buffer(4096);
  std::vector<TrackerPose> poses;
  const auto publishStats = [&](std::uint64_t filtered)
  {
    std::lock_guard<std::mutex> lock(this->StatsMutex);
    this->ParserStats = parser.Statistics();
    this->Filtered += filtered;
  };
  // The stream is over: consumers that see the event also see IsStreaming() == false.
  const auto finish = [this](const TrackerEvent& event)
  {
    this->ReaderEnded();
    this->Store.PublishEvent(event);
  };
  while (!this->StopRequested())
  {
    std::size_t n = 0;
    try
    {
      n = this->Link->Read(buffer.data(), buffer.size(), this->Opts.readTimeout);
    }
    catch (const DeviceDisconnectedError& e)
    {
      finish({ TrackerEventType::Disconnected, 0, this->ReaderTime(), e.what() });
      return;
    }
    catch (const std::exception& e) // the reader thread's boundary: the transport's errors, std's
    {
      finish({ TrackerEventType::ReadError, 0, this->ReaderTime(), e.what() });
      return;
    }
    if (n == 0)
    {
      if (this->Link->AtEnd())
      {
        parser.Finish();
        publishStats(0);
        const double t = this->Link->RecordedTime().value_or(this->ReaderTime());
        finish({ TrackerEventType::EndOfStream, 0, t, {} });
        return;
      }
      continue;
    }
    const double t = this->Link->RecordedTime().value_or(this->ReaderTime());
    poses.clear();
    parser.Feed(buffer.data(), n, t, poses);
    std::uint64_t filtered = 0;
    for (const TrackerPose& pose : poses)
    {
      if (std::find(this->Opts.stations.begin(), this->Opts.stations.end(), pose.station) ==
        this->Opts.stations.end())
      {
        ++filtered;
      }
      else if (!this->Store.Publish(pose))
      {
        break;
      }
    }
    publishStats(filtered);
  }
  this->ReaderEnded();
}

TrackerStatistics FastrakDevice::Statistics() const
{
  TrackerStatistics stats = this->Store.Statistics();
  std::lock_guard<std::mutex> lock(this->StatsMutex);
  stats.parser = this->ParserStats;
  stats.filtered = this->Filtered;
  stats.latencyMs = this->LatencyMs;
  return stats;
}

} // namespace bender
