#ifndef bender_TrackerCommand_h
#define bender_TrackerCommand_h

#include "UsbBackend.h"

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace CLI
{
class App;
}

namespace bender
{

/// `bender-cli tracker` on its own (the tests, with their streams and USB back end): args are
/// the words after "tracker". Prints one JSON line per pose
/// on `out` ({"t": s, "station": n, "position": [x, y, z] (mm), "quaternion": [w, x, y, z],
/// "button": 0|1}) and the grab/release events and a summary on `err`. Returns 0 on
/// success, 1 when the device fails (not found, no reply, unplugged, bad recording), 2 on a
/// usage error. Stops at --count poses, the end of a replay, --duration, or SIGINT/SIGTERM.
/// `usbBackend` replaces libusb (tests); empty in production.
int RunTrackerCli(const std::vector<std::string>& args,
  std::ostream& out,
  std::ostream& err,
  std::shared_ptr<UsbBackend> usbBackend = nullptr);

/// Adds `bender-cli tracker` to `cli` (CliCommand.h), printing on `out` and `err`.
void AddTrackerCommand(CLI::App& cli,
  std::ostream& out,
  std::ostream& err,
  std::shared_ptr<UsbBackend> usbBackend = nullptr);

} // namespace bender

#endif
