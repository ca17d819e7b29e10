#ifndef bender_UsbBackend_h
#define bender_UsbBackend_h

#include "UsbDeviceHandle.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace bender
{

/// The descriptors LibusbTransport needs, copied out of libusb.
struct UsbEndpointInfo
{
  std::uint8_t address = 0;    ///< bit 7 set: IN
  std::uint8_t attributes = 0; ///< bits 0-1: 0 control, 1 isochronous, 2 bulk, 3 interrupt
  std::uint16_t maxPacketSize = 0;

  bool IsIn() const { return (this->address & 0x80u) != 0; }
  bool IsBulk() const { return (this->attributes & 0x03u) == 2; }
};

struct UsbInterfaceInfo
{
  int number = 0; ///< bInterfaceNumber (alternate setting 0)
  std::vector<UsbEndpointInfo> endpoints;
};

struct UsbDeviceInfo
{
  std::uint16_t vendorId = 0;
  std::uint16_t productId = 0;
  int bus = 0;
  int address = 0;
  /// Interfaces of the active configuration; empty when it cannot be read.
  std::vector<UsbInterfaceInfo> interfaces;
};

/// Enumerates and opens USB devices: libusb-1.0 in production (LibusbBackend), a fake in the
/// tests, so that LibusbTransport is the same code in both.
class UsbBackend
{
public:
  virtual ~UsbBackend() = default;
  /// Devices whose vendor id is `vendorId`.
  virtual std::vector<UsbDeviceInfo> ListDevices(std::uint16_t vendorId) = 0;
  /// Opens the device at (bus, address). Throws DeviceAccessError when permissions forbid it,
  /// DeviceNotFoundError when it is gone, TransportError otherwise.
  virtual std::unique_ptr<UsbDeviceHandle> Open(const UsbDeviceInfo& device) = 0;
};

} // namespace bender

#endif
