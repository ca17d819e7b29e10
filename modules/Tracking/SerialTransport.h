#ifndef bender_SerialTransport_h
#define bender_SerialTransport_h

#include "Transport.h"

#include <string>

namespace bender
{

/// Line settings of a serial Fastrak; the unit's default is 115200 8N1 (set by its DIP
/// switches). No flow control, raw mode (no echo, no line editing, no CR/LF translation).
struct SerialSettings
{
  unsigned baud = 115200; ///< 9600, 19200, 38400, 57600, 115200, 230400
  int dataBits = 8;       ///< 7 or 8
  char parity = 'N';      ///< 'N', 'E' or 'O'
  int stopBits = 1;       ///< 1 or 2

  /// "115200", "115200,8N1", "9600,7E1"; throws TrackingConfigurationError.
  static SerialSettings Parse(const std::string& text);
  std::string ToString() const; ///< "115200 8N1"
};

/// A serial line (RS-232, or a USB-serial adapter's /dev/ttyUSBn) through termios.
/// Reads wait with poll(); a hang-up or EIO raises DeviceDisconnectedError.
class SerialTransport : public Transport
{
public:
  /// Opens and configures the port. Throws DeviceNotFoundError (no such port),
  /// DeviceAccessError (permission: join the dialout group), TransportError (not a tty, bad
  /// settings).
  SerialTransport(const std::string& path, const SerialSettings& settings = {});
  ~SerialTransport() override;

  std::string Name() const override { return "serial " + this->Path; }
  std::size_t Read(std::uint8_t* buffer, std::size_t capacity, Timeout timeout) override;
  void Write(const std::uint8_t* data, std::size_t size, Timeout timeout) override;
  void Flush() override;
  void Close() override;

private:
  std::string Path;
  int Fd = -1;
};

} // namespace bender

#endif
