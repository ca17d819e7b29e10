#ifndef bender_Transport_h
#define bender_Transport_h

#include "TrackingErrors.h"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace bender
{

/// A byte pipe to a tracker: USB bulk endpoints, a serial line, or a recorded file.
/// Not thread safe: FastrakDevice uses it from one thread at a time (configuration, then its
/// reader thread). Every call that waits has a timeout.
class Transport
{
public:
  /// How long a call may wait.
  using Timeout = std::chrono::milliseconds;

  Transport() = default;
  virtual ~Transport() = default;
  /// A transport owns its device (a handle, a descriptor, a file): not copyable.
  Transport(const Transport&) = delete;
  Transport& operator=(const Transport&) = delete;

  /// Short name for messages, e.g. "USB 0f44:0002 (bus 1, address 4)", "serial /dev/ttyS0".
  virtual std::string Name() const = 0;

  /// Reads up to `capacity` bytes, waiting at most `timeout` for the first one. Returns the
  /// number read; 0 when nothing came in time, or when AtEnd(). Throws
  /// DeviceDisconnectedError when the device went away, TransportError on other failures.
  virtual std::size_t Read(std::uint8_t* buffer, std::size_t capacity, Timeout timeout) = 0;

  /// Writes all bytes or throws TransportError (including on timeout).
  virtual void Write(const std::uint8_t* data, std::size_t size, Timeout timeout) = 0;

  /// Discards input that arrived but was not read yet.
  virtual void Flush() = 0;

  /// Releases the device; further calls throw TransportError. Never throws.
  virtual void Close() = 0;

  /// True once a finite source (a replay) has delivered its last byte.
  virtual bool AtEnd() const { return false; }

  /// For a replay: the recorded receive time (seconds) of the bytes last returned by Read.
  virtual std::optional<double> RecordedTime() const { return std::nullopt; }

  void WriteText(const std::string& text, Timeout timeout)
  {
    this->Write(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), timeout);
  }

protected:
  /// For Read, Write and Flush: throws TransportError "NAME: used after Close()" unless `open`.
  void CheckOpen(bool open) const
  {
    if (!open)
    {
      throw TransportError(this->Name() + ": used after Close()");
    }
  }
};

} // namespace bender

#endif
