#ifndef bender_TrackingErrors_h
#define bender_TrackingErrors_h

#include "BenderErrors.h"

namespace bender
{

/// Base of every error thrown by modules/Tracking, a bender::Error. Messages are one line and
/// name the device or file and the problem, e.g. "serial /dev/ttyUSB0: permission denied
/// (...)".
class TrackingError : public Error
{
public:
  using Error::Error;
};

/// No device of the requested kind is present (nothing on USB, no such serial port).
class DeviceNotFoundError : public TrackingError
{
public:
  using TrackingError::TrackingError;
};

/// A Fastrak is on USB but still enumerates as 0f44:0001: its firmware is not loaded yet.
class FirmwareMissingError : public TrackingError
{
public:
  using TrackingError::TrackingError;
};

/// The device is there but this user may not open it (udev rules, dialout group).
class DeviceAccessError : public TrackingError
{
public:
  using TrackingError::TrackingError;
};

/// An I/O error on an open transport (write timeout, USB pipe error, termios failure, ...).
class TransportError : public TrackingError
{
public:
  using TrackingError::TrackingError;
};

/// The device went away while open (unplugged, powered off, serial hang-up).
class DeviceDisconnectedError : public TransportError
{
public:
  using TransportError::TransportError;
};

/// The device answered nothing, or nothing that decodes, within the allowed time.
class DeviceNotRespondingError : public TrackingError
{
public:
  using TrackingError::TrackingError;
};

/// A recording (raw byte file or its .timestamps sidecar) cannot be read or written.
class RecordingError : public TrackingError
{
public:
  using TrackingError::TrackingError;
};

/// Invalid configuration: a bad device spec, station list, baud rate or calibration.
class TrackingConfigurationError : public TrackingError
{
public:
  using TrackingError::TrackingError;
};

} // namespace bender

#endif
