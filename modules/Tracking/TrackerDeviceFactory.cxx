#include "TrackerDeviceFactory.h"

#include "FastrakDevice.h"
#include "IgtlDevice.h"
#include "IgtlSocket.h"
#include "LibusbBackend.h"
#include "LibusbTransport.h"
#include "RecordingTransport.h"
#include "ReplayTransport.h"
#include "SimulatedDevice.h"
#include "TrackingErrors.h"

namespace bender
{

TrackerDeviceSpec TrackerDeviceSpec::Parse(const std::string& text)
{
  TrackerDeviceSpec spec;
  const auto bad = [&](const std::string& why)
  {
    return TrackingConfigurationError("device '" + text + "': " + why +
      " (expected usb, usb:N, serial:PATH[@BAUD[,8N1]], replay:FILE, igtl:HOST:PORT or sim)");
  };
  if (text == "sim" || text == "simulator")
  {
    spec.kind = Kind::Simulator;
  }
  else if (text == "usb" || text.rfind("usb:", 0) == 0)
  {
    spec.kind = Kind::Usb;
    if (text.size() > 4)
    {
      const std::string index = text.substr(4);
      if (index.empty() || index.size() > 2 ||
        index.find_first_not_of("0123456789") != std::string::npos)
      {
        throw bad("'" + index + "' is not a device number");
      }
      spec.usbIndex = std::stoi(index);
    }
  }
  else if (text.rfind("serial:", 0) == 0)
  {
    spec.kind = Kind::Serial;
    std::string rest = text.substr(7);
    const std::size_t at = rest.rfind('@');
    if (at != std::string::npos)
    {
      spec.serial = SerialSettings::Parse(rest.substr(at + 1));
      rest = rest.substr(0, at);
    }
    if (rest.empty())
    {
      throw bad("no serial port path");
    }
    spec.path = rest;
  }
  else if (text.rfind("replay:", 0) == 0)
  {
    spec.kind = Kind::Replay;
    spec.path = text.substr(7);
    if (spec.path.empty())
    {
      throw bad("no recording file");
    }
  }
  else if (text.rfind("igtl:", 0) == 0)
  {
    spec.kind = Kind::Igtl;
    ParseHostPort(text.substr(5), "device", spec.host, spec.port);
  }
  else
  {
    throw bad("unknown device");
  }
  return spec;
}

std::string TrackerDeviceSpec::ToString() const
{
  switch (this->kind)
  {
    case Kind::Usb:
      return this->usbIndex == 0 ? "usb" : "usb:" + std::to_string(this->usbIndex);
    case Kind::Serial:
      return "serial:" + this->path;
    case Kind::Replay:
      return "replay:" + this->path;
    case Kind::Simulator:
      return "sim";
    case Kind::Igtl:
      return "igtl:" +
        (this->host.find(':') != std::string::npos ? "[" + this->host + "]" : this->host) + ":" +
        std::to_string(this->port);
  }
  return "?";
}

std::unique_ptr<TrackerDevice> CreateTrackerDevice(const TrackerDeviceSpec& spec,
  const TrackerDeviceOptions& options)
{
  if (spec.kind == TrackerDeviceSpec::Kind::Simulator)
  {
    SimulatedDevice::Options sim;
    sim.stations = options.stations;
    sim.rateHz = options.simulatorRate;
    sim.duration = options.simulatorDuration;
    sim.realtime = options.simulatorRealtime;
    return std::make_unique<SimulatedDevice>(sim);
  }
  if (spec.kind == TrackerDeviceSpec::Kind::Igtl)
  {
    if (!options.recordPath.empty())
    {
      throw TrackingConfigurationError(
        spec.ToString() + ": recording the raw stream is only for Fastrak devices");
    }
    IgtlDevice::Options igtl;
    igtl.host = spec.host;
    igtl.port = spec.port;
    igtl.toolNames = options.igtlToolNames;
    return std::make_unique<IgtlDevice>(igtl);
  }
  FastrakOptions fastrak;
  fastrak.stations = options.stations;
  fastrak.format = options.format;
  fastrak.reset = options.reset;
  std::function<std::unique_ptr<Transport>()> open;
  switch (spec.kind)
  {
    case TrackerDeviceSpec::Kind::Usb:
    {
      auto backend = std::make_shared<std::shared_ptr<UsbBackend>>(options.usbBackend);
      const int index = spec.usbIndex;
      open = [backend, index]() -> std::unique_ptr<Transport>
      {
        if (!*backend)
        {
          *backend = std::make_shared<LibusbBackend>();
        }
        LibusbTransport::Options usb;
        usb.deviceIndex = index;
        return std::make_unique<LibusbTransport>(*backend, usb);
      };
      break;
    }
    case TrackerDeviceSpec::Kind::Serial:
    {
      const std::string path = spec.path;
      const SerialSettings serial = spec.serial;
      open = [path, serial]() -> std::unique_ptr<Transport>
      { return std::make_unique<SerialTransport>(path, serial); };
      break;
    }
    case TrackerDeviceSpec::Kind::Replay:
    {
      fastrak.configure = false;
      fastrak.measureLatency = false;
      ReplayTransport::Options replay;
      replay.realtime = options.realtime;
      const std::string path = spec.path;
      open = [path, replay]() -> std::unique_ptr<Transport>
      { return std::make_unique<ReplayTransport>(path, replay); };
      break;
    }
    case TrackerDeviceSpec::Kind::Simulator:
    case TrackerDeviceSpec::Kind::Igtl:
      break;
  }
  if (!options.recordPath.empty())
  {
    const std::string record = options.recordPath;
    open = [open, record]() -> std::unique_ptr<Transport>
    { return std::make_unique<RecordingTransport>(open(), record); };
  }
  return std::make_unique<FastrakDevice>(spec.ToString(), open, fastrak);
}

} // namespace bender
