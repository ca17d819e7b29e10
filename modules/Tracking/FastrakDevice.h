#ifndef bender_FastrakDevice_h
#define bender_FastrakDevice_h

#include "FastrakParser.h"
#include "TrackerDevice.h"
#include "Transport.h"

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace bender
{

/// Settings of a Fastrak session.
struct FastrakOptions
{
  FastrakFormat format = FastrakFormat::Binary; ///< 'f' binary or 'F' ASCII records
  std::vector<int> stations{ 1, 2 };            ///< stations to activate and pass on, 1..4
  /// Send the set-up commands and 'C'/'c' (false for a replay, which cannot be commanded).
  bool configure = true;
  /// Send ^Y (reset to factory state) first and wait `resetWait` for the unit to reboot.
  bool reset = false;
  std::chrono::milliseconds resetWait{ 10000 };
  /// Hemisphere vector sent as `H n,x,y,z` for every station (+X: in front of the transmitter).
  int hemisphere[3] = { 1, 0, 0 };
  /// Measure the latency with single-record requests ('P') at Open(); this also checks
  /// that the unit answers at all (DeviceNotRespondingError otherwise).
  bool measureLatency = true;
  std::chrono::milliseconds replyTimeout{ 1000 }; ///< wait for the answer to 'P'
  std::chrono::milliseconds readTimeout{ 50 };    ///< reader thread poll; bounds Stop()
  std::chrono::milliseconds writeTimeout{ 500 };
};

/// A Polhemus Fastrak over any Transport (USB, serial, replay).
///
/// Open() creates the transport with the factory, flushes it and, when `configure`, sends:
/// `c` (continuous off), optionally `^Y` + wait, `u` (centimetres), `f`/`F`, `l n,1|0`
/// for stations 1..4, then per active station `H n,x,y,z` and `O n,2,11,16,0`, and measures
/// the latency with `P`. Start() sends `C` and runs the reader thread; Stop() sends `c`.
/// The reader thread parses what arrives (FastrakParser), publishes the poses of the asked
/// stations, and turns a DeviceDisconnectedError into a Disconnected event, any other
/// read failure into a ReadError event, and the end of a replay into EndOfStream.
class FastrakDevice : public TrackerDevice
{
public:
  using TransportFactory = std::function<std::unique_ptr<Transport>()>;

  /// `name` is used in messages ("usb", "serial:/dev/ttyS0", ...). Throws
  /// TrackingConfigurationError for a station outside 1..4 or an empty station list.
  FastrakDevice(std::string name, TransportFactory factory, FastrakOptions options = {});
  ~FastrakDevice() override;
  FastrakDevice(const FastrakDevice&) = delete;
  FastrakDevice& operator=(const FastrakDevice&) = delete;

  std::string Name() const override { return this->DeviceName; }
  void Open() override;
  void Start() override;
  void Stop() override;
  void Close() override;
  bool IsOpen() const override { return this->Link != nullptr; }
  TrackerStatistics Statistics() const override;

  const FastrakOptions& Options() const { return this->Opts; }

private:
  void Configure();
  void MeasureLatency();
  void Send(const std::string& command);
  void ReaderLoop();

  std::string DeviceName;
  TransportFactory Factory;
  FastrakOptions Opts;
  std::unique_ptr<Transport> Link;
  mutable std::mutex StatsMutex;
  FastrakParserStatistics ParserStats;
  std::uint64_t Filtered = 0;
  std::optional<double> LatencyMs;
};

} // namespace bender

#endif
