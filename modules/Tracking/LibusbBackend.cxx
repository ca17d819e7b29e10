#include "LibusbBackend.h"

#include "TrackingErrors.h"

#include <cstdio>
#include <libusb.h>

namespace bender
{

namespace
{
std::string Where(const UsbDeviceInfo& d)
{
  char text[64];
  std::snprintf(text,
    sizeof text,
    "USB %04x:%04x (bus %d, address %d)",
    d.vendorId,
    d.productId,
    d.bus,
    d.address);
  return text;
}

UsbStatus StatusOf(int code)
{
  switch (code)
  {
    case LIBUSB_SUCCESS:
      return UsbStatus::Ok;
    case LIBUSB_ERROR_TIMEOUT:
      return UsbStatus::Timeout;
    case LIBUSB_ERROR_NO_DEVICE:
      return UsbStatus::NoDevice;
    case LIBUSB_ERROR_PIPE:
      return UsbStatus::Pipe;
    case LIBUSB_ERROR_OVERFLOW:
      return UsbStatus::Overflow;
    default:
      return UsbStatus::Error;
  }
}

// The handle keeps the interfaces it claimed so that closing releases them.
class LibusbDeviceHandle : public UsbDeviceHandle
{
public:
  LibusbDeviceHandle(libusb_device_handle* handle, std::string where)
    : Handle(handle)
    , Where(std::move(where))
  {
  }
  ~LibusbDeviceHandle() override
  {
    for (int number : this->Claimed)
    {
      libusb_release_interface(this->Handle, number);
    }
    libusb_close(this->Handle);
  }
  void ClaimInterface(int number) override
  {
    libusb_set_auto_detach_kernel_driver(this->Handle, 1);
    const int rc = libusb_claim_interface(this->Handle, number);
    if (rc == LIBUSB_ERROR_BUSY)
    {
      throw TransportError(this->Where + ": interface " + std::to_string(number) +
        " is in use by another program (close other tracker software)");
    }
    if (rc != LIBUSB_SUCCESS)
    {
      throw TransportError(this->Where + ": cannot claim interface " + std::to_string(number) +
        " (" + libusb_strerror(libusb_error(rc)) + ")");
    }
    this->Claimed.push_back(number);
  }
  void ReleaseInterface(int number) override
  {
    for (auto it = this->Claimed.begin(); it != this->Claimed.end(); ++it)
    {
      if (*it == number)
      {
        libusb_release_interface(this->Handle, number);
        this->Claimed.erase(it);
        return;
      }
    }
  }
  UsbTransferResult BulkTransfer(std::uint8_t endpoint,
    std::uint8_t* data,
    int length,
    unsigned timeoutMs) override
  {
    UsbTransferResult result;
    const int rc =
      libusb_bulk_transfer(this->Handle, endpoint, data, length, &result.transferred, timeoutMs);
    result.status = StatusOf(rc);
    if (result.status == UsbStatus::Error)
    {
      result.message = libusb_strerror(libusb_error(rc));
    }
    return result;
  }
  void ClearHalt(std::uint8_t endpoint) override { libusb_clear_halt(this->Handle, endpoint); }

private:
  libusb_device_handle* Handle;
  std::string Where;
  std::vector<int> Claimed;
};
} // namespace

LibusbBackend::LibusbBackend()
{
  const int rc = libusb_init(&this->Context);
  if (rc != LIBUSB_SUCCESS)
  {
    this->Context = nullptr;
    throw TransportError(
      std::string("USB: cannot initialise libusb (") + libusb_strerror(libusb_error(rc)) + ")");
  }
}

LibusbBackend::~LibusbBackend()
{
  if (this->Context)
  {
    libusb_exit(this->Context);
  }
}

std::vector<UsbDeviceInfo> LibusbBackend::ListDevices(std::uint16_t vendorId)
{
  std::vector<UsbDeviceInfo> found;
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(this->Context, &list);
  if (count < 0)
  {
    throw TransportError(
      std::string("USB: cannot list devices (") + libusb_strerror(libusb_error(int(count))) + ")");
  }
  for (ssize_t i = 0; i < count; ++i)
  {
    libusb_device_descriptor descriptor{};
    if (libusb_get_device_descriptor(list[i], &descriptor) != LIBUSB_SUCCESS ||
      descriptor.idVendor != vendorId)
    {
      continue;
    }
    UsbDeviceInfo info;
    info.vendorId = descriptor.idVendor;
    info.productId = descriptor.idProduct;
    info.bus = libusb_get_bus_number(list[i]);
    info.address = libusb_get_device_address(list[i]);
    libusb_config_descriptor* config = nullptr;
    if (libusb_get_active_config_descriptor(list[i], &config) == LIBUSB_SUCCESS)
    {
      for (int k = 0; k < config->bNumInterfaces; ++k)
      {
        const libusb_interface& itf = config->interface[k];
        if (itf.num_altsetting < 1)
        {
          continue;
        }
        const libusb_interface_descriptor& alt = itf.altsetting[0];
        UsbInterfaceInfo interfaceInfo;
        interfaceInfo.number = alt.bInterfaceNumber;
        for (int e = 0; e < alt.bNumEndpoints; ++e)
        {
          interfaceInfo.endpoints.push_back({ alt.endpoint[e].bEndpointAddress,
            alt.endpoint[e].bmAttributes,
            alt.endpoint[e].wMaxPacketSize });
        }
        info.interfaces.push_back(interfaceInfo);
      }
      libusb_free_config_descriptor(config);
    }
    found.push_back(info);
  }
  libusb_free_device_list(list, 1);
  return found;
}

std::unique_ptr<UsbDeviceHandle> LibusbBackend::Open(const UsbDeviceInfo& device)
{
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(this->Context, &list);
  if (count < 0)
  {
    throw TransportError(
      std::string("USB: cannot list devices (") + libusb_strerror(libusb_error(int(count))) + ")");
  }
  libusb_device_handle* handle = nullptr;
  int rc = LIBUSB_ERROR_NO_DEVICE;
  for (ssize_t i = 0; i < count; ++i)
  {
    if (libusb_get_bus_number(list[i]) == device.bus &&
      libusb_get_device_address(list[i]) == device.address)
    {
      rc = libusb_open(list[i], &handle);
      break;
    }
  }
  libusb_free_device_list(list, 1);
  if (rc == LIBUSB_ERROR_ACCESS)
  {
    throw DeviceAccessError(Where(device) + ": permission denied; install " +
      "resources/udev/99-polhemus-fastrak.rules (see docs/tracking.md) and replug the unit");
  }
  if (rc == LIBUSB_ERROR_NO_DEVICE)
  {
    throw DeviceNotFoundError(Where(device) + ": the device went away while opening it");
  }
  if (rc != LIBUSB_SUCCESS)
  {
    throw TransportError(
      Where(device) + ": cannot open (" + libusb_strerror(libusb_error(rc)) + ")");
  }
  return std::make_unique<LibusbDeviceHandle>(handle, Where(device));
}

} // namespace bender
