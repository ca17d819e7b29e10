#ifndef bender_LibusbBackend_h
#define bender_LibusbBackend_h

#include "UsbBackend.h"

struct libusb_context;

namespace bender
{

/// UsbBackend over libusb-1.0, with its own libusb context. Handles it opens must not
/// outlive it (LibusbTransport keeps a shared_ptr to its backend).
class LibusbBackend : public UsbBackend
{
public:
  /// Throws TransportError when libusb cannot be initialised.
  LibusbBackend();
  ~LibusbBackend() override;
  LibusbBackend(const LibusbBackend&) = delete;
  LibusbBackend& operator=(const LibusbBackend&) = delete;

  std::vector<UsbDeviceInfo> ListDevices(std::uint16_t vendorId) override;
  std::unique_ptr<UsbDeviceHandle> Open(const UsbDeviceInfo& device) override;

private:
  libusb_context* Context = nullptr;
};

} // namespace bender

#endif
