#ifndef bender_TrackerDeviceFactory_h
#define bender_TrackerDeviceFactory_h

#include "FastrakParser.h"
#include "SerialTransport.h"
#include "TrackerDevice.h"
#include "UsbBackend.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace bender
{

/// Which device to use, as written on the command line:
/// `usb` (first Fastrak on USB), `usb:N` (the N-th, from 0), `serial:PATH` or
/// `serial:PATH@BAUD[,8N1]`, `replay:FILE`, `sim`, `igtl:HOST:PORT` (an OpenIGTLink server
/// such as PLUS or 3D Slicer; see IgtlDevice).
struct TrackerDeviceSpec
{
  enum class Kind
  {
    Usb,
    Serial,
    Replay,
    Simulator,
    Igtl
  };
  Kind kind = Kind::Simulator;
  std::string path;      ///< serial port or recording
  int usbIndex = 0;      ///< usb:N
  SerialSettings serial; ///< serial line settings
  std::string host;      ///< igtl:HOST:PORT
  int port = 0;

  /// Throws TrackingConfigurationError naming the spec and what is wrong.
  static TrackerDeviceSpec Parse(const std::string& text);
  std::string ToString() const;
};

struct TrackerDeviceOptions
{
  std::vector<int> stations{ 1, 2 };
  FastrakFormat format = FastrakFormat::Binary;
  std::string recordPath; ///< non-empty: record the received bytes (usb, serial, replay)
  bool realtime = false;  ///< replay paced by its recorded times
  bool reset = false;     ///< send ^Y at Open (takes ~10 s)
  double simulatorRate = 60.0;
  double simulatorDuration = 0.0;
  bool simulatorRealtime = true;
  /// OpenIGTLink device names of the first and second hand (igtl only).
  std::array<std::string, 2> igtlToolNames{ "StylusToTracker", "Stylus2ToTracker" };
  /// USB backend; empty: libusb-1.0, created at the first Open().
  std::shared_ptr<UsbBackend> usbBackend;
};

/// Builds the device for `spec` (not opened yet). A replay is a FastrakDevice that sends no
/// commands, so it runs exactly the decoding and threading code of a live unit.
std::unique_ptr<TrackerDevice> CreateTrackerDevice(const TrackerDeviceSpec& spec,
  const TrackerDeviceOptions& options);

} // namespace bender

#endif
