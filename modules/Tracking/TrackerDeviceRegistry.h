#ifndef bender_TrackerDeviceRegistry_h
#define bender_TrackerDeviceRegistry_h

#include "FastrakParser.h"
#include "SerialTransport.h"
#include "TrackerDevice.h"
#include "UsbBackend.h"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bender
{

/// Which device to use, as written on the command line and in the Trackers panel: the name of
/// a kind in the device table (TrackerDeviceKinds), alone or followed by ':' and an argument
/// (`usb`, `usb:N`, `serial:PATH[@BAUD[,8N1]]`, `replay:FILE`, `sim`, `igtl:HOST:PORT`).
struct TrackerDeviceSpec
{
  std::string kind = "sim"; ///< the kind's name in the table ("usb", "serial", "igtl", ...)
  std::string argument;     ///< the text after "kind:" as written; empty without one
  std::string path;         ///< serial port or recording
  int usbIndex = 0;         ///< usb:N
  SerialSettings serial;    ///< serial line settings
  std::string host;         ///< igtl:HOST:PORT
  int port = 0;

  /// Parses through the table; throws TrackingConfigurationError naming the spec, what is
  /// wrong and the forms every kind accepts.
  static TrackerDeviceSpec Parse(const std::string& text);
  /// The spec as the kind writes it back ("usb", "serial:/dev/ttyS0", "igtl:[::1]:18944").
  std::string ToString() const;
};

struct TrackerDeviceOptions
{
  std::vector<int> stations{ 1, 2 };
  FastrakFormat format = FastrakFormat::Binary;
  std::string recordPath; ///< non-empty: record the received bytes (kinds that recordBytes)
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

/// One row of the tracker-device table: how a kind of device is written, what it is, how it
/// behaves in a stream, and how it is made. The CLI's `tracker --device` help, the parse
/// errors, the Trackers panel's device list and TrackerStream all read the table, so a new
/// device is one row (RegisterTrackerDeviceKind) plus its TrackerDevice; its statistics beyond
/// TrackerStatistics come through the TrackerDevice interface (SummaryLines, CountersText).
struct TrackerDeviceKind
{
  enum class Argument
  {
    None,     ///< `sim`
    Optional, ///< `usb` or `usb:N`
    Required  ///< `replay:FILE`
  };
  std::string name;                 ///< the word before ':' ("usb")
  std::vector<std::string> aliases; ///< other words for it ("simulator")
  Argument argument = Argument::None;
  /// How it is written, alternatives separated by '|': "usb|usb:N".
  std::string syntax;
  /// What it is, for the CLI's help: one paragraph, no line breaks.
  std::string help;
  /// Waits on hardware or a network host: opened off the GUI thread, keeps only the newest
  /// poses when the reader falls behind. Otherwise (a recording, the simulator) no pose is lost.
  bool live = false;
  /// `recordPath` records the raw bytes it receives (a Fastrak); otherwise TrackerStream records
  /// the binary records a Fastrak would have sent for the hands.
  bool recordsBytes = false;
  /// What a user is asked to check when no pose comes within the stream's timeout; empty: the
  /// kind is never silent (the simulator) and has no timeout.
  std::string silentHint;
  /// Fills `spec` from the argument (the text after "name:", empty for none). Returns what is
  /// wrong with it (Parse adds the spec and every kind's forms), empty when it is fine; or
  /// throws TrackingConfigurationError with a message of its own.
  std::function<std::string(const std::string& argument, TrackerDeviceSpec& spec)> parse;
  /// Writes the spec back; empty: "name" or "name:argument".
  std::function<std::string(const TrackerDeviceSpec& spec)> format;
  /// Makes the device (not opened yet); throws TrackingError for options it refuses.
  std::function<std::unique_ptr<TrackerDevice>(const TrackerDeviceSpec& spec,
    const TrackerDeviceOptions& options)>
    create;
  /// A finite source that ended without one pose: one line saying what it may be instead;
  /// empty (or no function): nothing wrong.
  std::function<std::string(const TrackerDeviceSpec& spec, const TrackerDeviceOptions& options)>
    noPoses;
};

/// The table, in the order users see it: usb, serial, replay, igtl, sim, then registered kinds.
const std::vector<TrackerDeviceKind>& TrackerDeviceKinds();
/// Adds a kind at the end of the table, or replaces the kind of the same name. Register at
/// start-up, before devices are parsed on other threads. Throws TrackingConfigurationError for
/// a kind without a name, syntax, parse or create function.
void RegisterTrackerDeviceKind(TrackerDeviceKind kind);
/// The row named `name` (or one of its aliases); throws TrackingConfigurationError.
const TrackerDeviceKind& FindTrackerDeviceKind(const std::string& name);
/// Every kind's forms for a message: "usb, usb:N, serial:PATH[@BAUD[,8N1]], replay:FILE,
/// igtl:HOST:PORT or sim".
std::string TrackerDeviceForms();

/// The table for a help text: "SYNTAX: help" per kind (alternatives joined by " or "), each
/// wrapped at `width` columns, continuation lines indented by two spaces.
std::vector<std::string> TrackerDeviceHelpLines(std::size_t width);

/// Builds the device for `spec` through its kind's create (not opened yet).
std::unique_ptr<TrackerDevice> CreateTrackerDevice(const TrackerDeviceSpec& spec,
  const TrackerDeviceOptions& options);

} // namespace bender

#endif
