#ifndef bender_UsbDeviceHandle_h
#define bender_UsbDeviceHandle_h

#include <cstdint>
#include <string>

namespace bender
{

/// Outcome of one USB transfer, as libusb reports it.
enum class UsbStatus
{
  Ok,
  Timeout,  ///< `transferred` may still be > 0 (a partial transfer)
  NoDevice, ///< the device was unplugged
  Pipe,     ///< endpoint halted (stall)
  Overflow, ///< the device sent more than asked for
  Error     ///< anything else; see `message`
};

struct UsbTransferResult
{
  UsbStatus status = UsbStatus::Ok;
  int transferred = 0;
  std::string message; ///< backend's text for Error
};

/// An open USB device, the part of libusb that LibusbTransport uses. Implemented over
/// libusb-1.0 by LibusbBackend and by fakes in the tests.
class UsbDeviceHandle
{
public:
  virtual ~UsbDeviceHandle() = default;
  /// Claims an interface (detaching a kernel driver if one is bound); throws TransportError.
  virtual void ClaimInterface(int number) = 0;
  virtual void ReleaseInterface(int number) = 0;
  /// One bulk transfer; direction from the endpoint address (bit 7 set: IN).
  virtual UsbTransferResult BulkTransfer(std::uint8_t endpoint,
    std::uint8_t* data,
    int length,
    unsigned timeoutMs) = 0;
  virtual void ClearHalt(std::uint8_t endpoint) = 0;
};

} // namespace bender

#endif
