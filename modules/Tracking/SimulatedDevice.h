#ifndef bender_SimulatedDevice_h
#define bender_SimulatedDevice_h

#include "SimulationScript.h"
#include "TrackerDevice.h"

#include <atomic>
#include <thread>
#include <vector>

namespace bender
{

/// A tracker that plays a SimulationScript: one pose per station every 1/rateHz seconds of
/// simulated time (TrackerPose::time = sample index / rateHz, so runs are reproducible).
/// With `realtime` the samples are paced by the steady clock, otherwise they come as fast
/// as the consumer takes them (with a blocking pose queue) or as fast as possible.
class SimulatedDevice : public TrackerDevice
{
public:
  struct Options
  {
    std::vector<int> stations{ 1, 2 }; ///< 1..4
    double rateHz = 60.0;              ///< per station, (0, 1000]
    bool realtime = true;
    double duration = 0.0; ///< seconds of simulated time, then EndOfStream; 0: endless
  };

  /// Throws TrackingConfigurationError for bad stations or rate.
  SimulatedDevice(Options options, SimulationScript script = SimulationScript::TwoHandBend());
  ~SimulatedDevice() override;
  SimulatedDevice(const SimulatedDevice&) = delete;
  SimulatedDevice& operator=(const SimulatedDevice&) = delete;

  std::string Name() const override { return "simulator"; }
  void Open() override;
  void Start() override;
  void Stop() override;
  void Close() override;
  bool IsOpen() const override { return this->Opened; }

private:
  void Run();

  Options Opts;
  SimulationScript Script;
  bool Opened = false;
};

} // namespace bender

#endif
