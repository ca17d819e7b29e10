#include "LibusbTransport.h"

#include "TrackingErrors.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace bender
{

namespace
{
std::string Hex4(unsigned value)
{
  char text[8];
  std::snprintf(text, sizeof text, "%04x", value & 0xFFFFu);
  return text;
}
} // namespace

LibusbTransport::LibusbTransport(std::shared_ptr<UsbBackend> backend)
  : LibusbTransport(std::move(backend), Options{})
{
}

LibusbTransport::LibusbTransport(std::shared_ptr<UsbBackend> backend, const Options& options)
  : Backend(std::move(backend))
  , Opts(options)
{
  const std::string vendor = "0x" + Hex4(this->Opts.vendorId);
  const std::vector<UsbDeviceInfo> all = this->Backend->ListDevices(this->Opts.vendorId);
  std::vector<UsbDeviceInfo> ready;
  const UsbDeviceInfo* noFirmware = nullptr;
  for (const UsbDeviceInfo& d : all)
  {
    if (std::find(this->Opts.productIds.begin(), this->Opts.productIds.end(), d.productId) !=
      this->Opts.productIds.end())
    {
      ready.push_back(d);
    }
    else if (d.productId == this->Opts.noFirmwareProductId && !noFirmware)
    {
      noFirmware = &d;
    }
  }
  if (ready.empty() && noFirmware)
  {
    throw FirmwareMissingError("USB " + Hex4(noFirmware->vendorId) + ":" +
      Hex4(noFirmware->productId) + " (bus " + std::to_string(noFirmware->bus) + ", address " +
      std::to_string(noFirmware->address) + "): a Polhemus Fastrak without its firmware; " +
      "load it with fxload as in resources/fastrak/README.md (the udev rules in " +
      "resources/udev/ do it at plug-in), then replug");
  }
  if (ready.empty())
  {
    throw DeviceNotFoundError("no Polhemus Fastrak found on USB (vendor " + vendor +
      "): check power and cable, or use --device serial:/dev/ttyS0 for an RS-232 unit" +
      (all.empty() ? std::string()
                   : " (" + std::to_string(all.size()) + " other Polhemus device(s) present)"));
  }
  if (this->Opts.deviceIndex < 0 || std::size_t(this->Opts.deviceIndex) >= ready.size())
  {
    throw DeviceNotFoundError("USB: asked for Fastrak number " +
      std::to_string(this->Opts.deviceIndex) + " but " + std::to_string(ready.size()) + " found");
  }
  const UsbDeviceInfo device = ready[std::size_t(this->Opts.deviceIndex)];
  this->DeviceName = "USB " + Hex4(device.vendorId) + ":" + Hex4(device.productId) + " (bus " +
    std::to_string(device.bus) + ", address " + std::to_string(device.address) + ")";
  for (const UsbInterfaceInfo& itf : device.interfaces)
  {
    const UsbEndpointInfo* in = nullptr;
    const UsbEndpointInfo* out = nullptr;
    for (const UsbEndpointInfo& e : itf.endpoints)
    {
      if (e.IsBulk() && e.IsIn() && !in)
      {
        in = &e;
      }
      else if (e.IsBulk() && !e.IsIn() && !out)
      {
        out = &e;
      }
    }
    if (in && out && in->maxPacketSize > 0 && out->maxPacketSize > 0)
    {
      this->In = *in;
      this->Out = *out;
      this->InterfaceNumber = itf.number;
      break;
    }
  }
  if (this->InterfaceNumber < 0)
  {
    throw TransportError(this->DeviceName + ": no interface with a bulk IN and a bulk OUT " +
      "endpoint in its descriptors (not a Fastrak, or firmware not loaded properly)");
  }
  this->Handle = this->Backend->Open(device);
  this->Handle->ClaimInterface(this->InterfaceNumber);
  // Whole packets only: a read shorter than wMaxPacketSize could overflow.
  const std::size_t packets = std::max<std::size_t>(1, 4096 / this->In.maxPacketSize);
  this->Packet.resize(packets * this->In.maxPacketSize);
  this->Flush();
}

LibusbTransport::~LibusbTransport()
{
  this->Close();
}

bool LibusbTransport::Fill(std::chrono::milliseconds timeout)
{
  const unsigned ms = unsigned(std::max<long long>(1, timeout.count()));
  UsbTransferResult r =
    this->Handle->BulkTransfer(this->In.address, this->Packet.data(), int(this->Packet.size()), ms);
  if (r.status == UsbStatus::Pipe)
  {
    // A stalled endpoint: clear it once and try again before giving up.
    this->Handle->ClearHalt(this->In.address);
    r = this->Handle->BulkTransfer(
      this->In.address, this->Packet.data(), int(this->Packet.size()), ms);
  }
  switch (r.status)
  {
    case UsbStatus::Ok:
    case UsbStatus::Timeout:
      break;
    case UsbStatus::NoDevice:
      throw DeviceDisconnectedError(this->DeviceName + ": unplugged or switched off");
    case UsbStatus::Pipe:
      throw TransportError(this->DeviceName + ": IN endpoint stalled and does not recover");
    case UsbStatus::Overflow:
      throw TransportError(this->DeviceName + ": IN transfer overflowed");
    case UsbStatus::Error:
      throw TransportError(this->DeviceName + ": read failed (" + r.message + ")");
  }
  const std::size_t got =
    std::min<std::size_t>(std::size_t(std::max(0, r.transferred)), this->Packet.size());
  if (got == 0)
  {
    return false;
  }
  if (this->PendingBegin == this->Pending.size())
  {
    this->Pending.clear();
    this->PendingBegin = 0;
  }
  this->Pending.insert(
    this->Pending.end(), this->Packet.begin(), this->Packet.begin() + std::ptrdiff_t(got));
  return true;
}

std::size_t LibusbTransport::Read(std::uint8_t* buffer,
  std::size_t capacity,
  std::chrono::milliseconds timeout)
{
  this->CheckOpen(this->Handle != nullptr);
  if (this->PendingBegin == this->Pending.size() && !this->Fill(timeout))
  {
    return 0;
  }
  const std::size_t n = std::min(capacity, this->Pending.size() - this->PendingBegin);
  std::memcpy(buffer, this->Pending.data() + this->PendingBegin, n);
  this->PendingBegin += n;
  return n;
}

void LibusbTransport::Write(const std::uint8_t* data,
  std::size_t size,
  std::chrono::milliseconds timeout)
{
  this->CheckOpen(this->Handle != nullptr);
  const unsigned ms = unsigned(std::max<long long>(1, timeout.count()));
  std::vector<std::uint8_t> copy(data, data + size);
  std::size_t done = 0;
  const auto transfer = [&](std::uint8_t* bytes, int length)
  {
    const UsbTransferResult r = this->Handle->BulkTransfer(this->Out.address, bytes, length, ms);
    switch (r.status)
    {
      case UsbStatus::Ok:
        return r.transferred;
      case UsbStatus::Timeout:
        throw TransportError(
          this->DeviceName + ": write timed out after " + std::to_string(timeout.count()) + " ms");
      case UsbStatus::NoDevice:
        throw DeviceDisconnectedError(this->DeviceName + ": unplugged or switched off");
      case UsbStatus::Pipe:
        this->Handle->ClearHalt(this->Out.address);
        throw TransportError(this->DeviceName + ": OUT endpoint stalled");
      default:
        throw TransportError(this->DeviceName + ": write failed (" + r.message + ")");
    }
  };
  while (done < size)
  {
    const int n = transfer(copy.data() + done, int(size - done));
    if (n <= 0)
    {
      throw TransportError(this->DeviceName + ": write accepted no bytes");
    }
    done += std::size_t(n);
  }
  // The transfer ended on a packet boundary: a zero-length packet tells the device it is done.
  if (size > 0 && size % this->Out.maxPacketSize == 0)
  {
    std::uint8_t none = 0;
    transfer(&none, 0);
  }
}

void LibusbTransport::Flush()
{
  this->CheckOpen(this->Handle != nullptr);
  this->Pending.clear();
  this->PendingBegin = 0;
  for (int i = 0; i < this->Opts.maxFlushTransfers; ++i)
  {
    if (!this->Fill(this->Opts.flushTimeout))
    {
      break;
    }
    this->Pending.clear();
    this->PendingBegin = 0;
  }
  this->Pending.clear();
  this->PendingBegin = 0;
}

void LibusbTransport::Close()
{
  if (this->Handle)
  {
    this->Handle->ReleaseInterface(this->InterfaceNumber);
    this->Handle.reset();
  }
}

} // namespace bender
