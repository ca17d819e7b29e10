#ifndef bender_LibusbTransport_h
#define bender_LibusbTransport_h

#include "Transport.h"
#include "UsbBackend.h"

#include <memory>
#include <vector>

namespace bender
{

/// A Fastrak on USB through bulk endpoints (libusb-1.0 via a UsbBackend).
///
/// Opening enumerates vendor 0x0F44, takes the `deviceIndex`-th unit whose product id is in
/// `productIds` (0x0002 Fastrak USB with its firmware loaded, 0x0003 Fastrak 3), picks the
/// first interface that has a bulk IN and a bulk OUT endpoint (addresses and packet sizes
/// from the descriptors, never hard-coded), claims it and flushes stale input.
/// A unit that shows up only as 0x0001 has no firmware: FirmwareMissingError points to
/// resources/fastrak/README.md and the udev rules. Reads request whole packets (no overflow)
/// and hand out what they got; a write whose length is a multiple of the OUT packet size is
/// followed by a zero-length packet so the device sees its end.
class LibusbTransport : public Transport
{
public:
  struct Options
  {
    std::uint16_t vendorId = 0x0F44;
    std::vector<std::uint16_t> productIds{ 0x0002, 0x0003 };
    std::uint16_t noFirmwareProductId = 0x0001;
    int deviceIndex = 0;                          ///< which unit when several are present
    std::chrono::milliseconds flushTimeout{ 20 }; ///< per flush read
    int maxFlushTransfers = 64;                   ///< bounds the flush of a chatty unit
  };

  /// Throws DeviceNotFoundError, FirmwareMissingError, DeviceAccessError, TransportError.
  explicit LibusbTransport(std::shared_ptr<UsbBackend> backend);
  LibusbTransport(std::shared_ptr<UsbBackend> backend, const Options& options);
  ~LibusbTransport() override;

  std::string Name() const override { return this->DeviceName; }
  std::size_t Read(std::uint8_t* buffer, std::size_t capacity, Timeout timeout) override;
  void Write(const std::uint8_t* data, std::size_t size, Timeout timeout) override;
  void Flush() override;
  void Close() override;

  std::uint8_t InEndpoint() const { return this->In.address; }
  std::uint8_t OutEndpoint() const { return this->Out.address; }
  int Interface() const { return this->InterfaceNumber; }

private:
  /// One IN transfer into Pending; returns false on timeout with nothing received.
  bool Fill(Timeout timeout);

  std::shared_ptr<UsbBackend> Backend;
  Options Opts;
  std::unique_ptr<UsbDeviceHandle> Handle;
  std::string DeviceName;
  UsbEndpointInfo In;
  UsbEndpointInfo Out;
  int InterfaceNumber = -1;
  std::vector<std::uint8_t> Pending;
  std::size_t PendingBegin = 0;
  std::vector<std::uint8_t> Packet;
};

} // namespace bender

#endif
