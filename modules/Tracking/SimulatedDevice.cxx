#include "SimulatedDevice.h"

#include "TrackingErrors.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace bender
{

SimulatedDevice::SimulatedDevice(Options options, SimulationScript script)
  : Opts(std::move(options))
  , Script(std::move(script))
{
  if (this->Opts.stations.empty())
  {
    throw TrackingConfigurationError("simulator: no station to simulate");
  }
  for (int s : this->Opts.stations)
  {
    if (s < 1 || s > 4)
    {
      throw TrackingConfigurationError(
        "simulator: station " + std::to_string(s) + " is outside 1..4");
    }
  }
  if (!(this->Opts.rateHz > 0.0 && this->Opts.rateHz <= 1000.0) ||
    !(this->Opts.duration >= 0.0 && std::isfinite(this->Opts.duration)))
  {
    throw TrackingConfigurationError("simulator: rate must be in (0, 1000] Hz and duration >= 0");
  }
}

SimulatedDevice::~SimulatedDevice()
{
  this->Close();
}

void SimulatedDevice::Open()
{
  if (!this->Opened)
  {
    this->Store.Clear();
    this->Opened = true;
  }
}

void SimulatedDevice::Start()
{
  if (!this->Opened)
  {
    throw TrackingError("simulator: Start() before Open()");
  }
  if (!this->ReaderRunning())
  {
    this->StartReader([this] { this->Run(); });
  }
}

void SimulatedDevice::Stop()
{
  this->StopReader();
}

void SimulatedDevice::Close()
{
  this->Stop();
  this->Opened = false;
}

void SimulatedDevice::Run()
{
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t k = 0; !this->StopRequested(); ++k)
  {
    const double t = double(k) / this->Opts.rateHz;
    if (this->Opts.duration > 0.0 && t > this->Opts.duration)
    {
      this->ReaderEnded();
      this->Store.PublishEvent({ TrackerEventType::EndOfStream, 0, t, {} });
      return;
    }
    if (this->Opts.realtime)
    {
      // Sleep in short steps so that Stop() is never kept waiting long.
      const auto due = start +
        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(t));
      while (!this->StopRequested() && std::chrono::steady_clock::now() < due)
      {
        std::this_thread::sleep_for(std::min<std::chrono::steady_clock::duration>(
          due - std::chrono::steady_clock::now(), std::chrono::milliseconds(20)));
      }
    }
    for (int station : this->Opts.stations)
    {
      if (this->StopRequested() || !this->Store.Publish(this->Script.PoseAt(station, t)))
      {
        break;
      }
    }
  }
  this->ReaderEnded();
}

} // namespace bender
