#ifndef bender_TrackerStream_h
#define bender_TrackerStream_h

#include "TrackerDevice.h"
#include "TrackerDeviceRegistry.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bender
{

class StreamRecorder;

/// One tracker device from its spec to a clean stop: created from the spec through the device
/// table (`usb`, `serial:PATH`, `replay:FILE`, `sim`, `igtl:HOST:PORT`, registered kinds), opened,
/// started, its poses and events handed to a sink in order (Run), recorded
/// (`TrackerDeviceOptions::recordPath`: the raw bytes of a Fastrak, or, for devices that send no
/// Fastrak bytes, the binary records a Fastrak would have sent for the hands, so that `replay:FILE`
/// plays it back), stopped on a pose count, a duration, the end of a replay, a device failure, a
/// silent device or a cancel, and its statistics.
///
/// `bender-cli tracker` runs it (Run, then Statistics and SummaryLines); the Trackers panel
/// creates it on the GUI thread (Create: a bad spec or option is refused before any thread),
/// opens a live device on a worker (Open may wait for a host) and hands the device to
/// TrackerSession::Connect (TakeDevice). Not thread-safe; the device's own reader thread only
/// fills its pose store.
class TrackerStream
{
public:
  /// When Run stops by itself (besides the end of a replay, a failure or a cancel).
  struct Limits
  {
    std::uint64_t count = 0; ///< poses handed to the sink; 0: no limit
    double duration = 0.0;   ///< seconds of pose time; 0: no limit
    double timeout = 5.0;    ///< a device that sends no pose within this (s) fails (not sim)
  };
  /// Where Run hands what the device sends, on Run's thread.
  struct Sink
  {
    /// Every pose in order; `name` is the device's name for it when the device names its poses
    /// (OpenIGTLink: also poses of no hand, station 0), null otherwise.
    std::function<void(const TrackerPose& pose, const std::string* name)> pose;
    /// The stylus buttons' grab and release events.
    std::function<void(const TrackerEvent& event)> event;
    /// After each batch of poses (e.g. to flush an output).
    std::function<void()> batchDone;
  };
  /// How Run ended.
  struct Result
  {
    std::uint64_t poses = 0;  ///< poses handed to the sink
    bool interrupted = false; ///< the cancel callback said stop
    std::string failure;      ///< one line naming the device and why it failed; empty if not
    std::string noPoses;      ///< a recording that ended without one pose: one line saying so
    bool Ok() const { return this->failure.empty() && this->noPoses.empty(); }
  };

  /// Parses `spec`; throws TrackingConfigurationError naming it. Creates nothing yet.
  TrackerStream(const std::string& spec, TrackerDeviceOptions options = {});
  /// Stops and closes the device it still holds.
  ~TrackerStream();
  TrackerStream(const TrackerStream&) = delete;
  TrackerStream& operator=(const TrackerStream&) = delete;

  const TrackerDeviceSpec& Spec() const { return this->DeviceSpec; }
  /// The spec's row of the device table.
  const TrackerDeviceKind& Kind() const { return this->DeviceKind; }
  /// The spec as the summary names it ("replay:FILE", "igtl:HOST:PORT").
  std::string Name() const { return this->DeviceSpec.ToString(); }
  /// A device that waits on hardware or a network host (USB, serial, OpenIGTLink): opened off
  /// the GUI thread, and keeps the newest poses when the reader falls behind (a replay or the
  /// simulator loses none).
  bool IsLive() const { return this->DeviceKind.live; }

  /// Creates the device (options are checked; nothing is opened). Throws TrackingError (bad
  /// tool names, recording over the recording being replayed, ...). Once only.
  TrackerDevice& Create();
  /// Creates the device if needed and opens it: may wait (a host's connect timeout). Throws
  /// TrackingError naming the device and the problem.
  void Open();
  /// Opens if needed, starts, hands poses and events to `sink` until a limit, the end of a
  /// replay, a device failure, no pose within `limits.timeout` or `cancelled()`, then stops
  /// (Statistics and SummaryLines stay readable; the destructor or Close closes). Throws
  /// TrackingError when the device cannot be created, opened or started, RecordingError when
  /// the recording cannot be written.
  Result Run(const Limits& limits,
    const Sink& sink,
    const std::function<bool()>& cancelled = nullptr);
  /// Stops and closes the device; never throws.
  void Close();

  /// The device's statistics (empty before Create).
  TrackerStatistics Statistics() const;
  /// What this kind of device counts beyond Statistics (TrackerDevice::SummaryLines).
  std::vector<std::string> SummaryLines() const;
  /// Hands the device (created, perhaps opened) over, e.g. to TrackerSession::Connect; null
  /// before Create.
  std::unique_ptr<TrackerDevice> TakeDevice();

private:
  void Record(const TrackerPose& pose);

  TrackerDeviceSpec DeviceSpec;
  TrackerDeviceKind DeviceKind; ///< a copy: registering a kind may move the table's rows
  TrackerDeviceOptions Options;
  std::unique_ptr<TrackerDevice> Device;
  std::unique_ptr<StreamRecorder> PoseRecorder; ///< devices that send no Fastrak bytes
};

} // namespace bender

#endif
