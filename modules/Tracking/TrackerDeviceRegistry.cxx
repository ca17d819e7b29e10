#include "TrackerDeviceRegistry.h"

#include "FastrakDevice.h"
#include "FileIdentity.h"
#include "IgtlDevice.h"
#include "IgtlSocket.h"
#include "LibusbBackend.h"
#include "LibusbTransport.h"
#include "RecordingTransport.h"
#include "ReplayTransport.h"
#include "SimulatedDevice.h"
#include "TrackingErrors.h"

#include <algorithm>

namespace bender
{

namespace
{
using TransportOpener = std::function<std::unique_ptr<Transport>()>;

// A kind whose devices are a Fastrak over the transport `transport` opens: its bytes are
// recorded as received, and a silent unit is asked about.
TrackerDeviceKind FastrakKind(std::string name,
  TrackerDeviceKind::Argument argument,
  std::string syntax,
  std::string help,
  bool live,
  FastrakOptions fastrak,
  std::function<TransportOpener(const TrackerDeviceSpec&, const TrackerDeviceOptions&)> transport)
{
  TrackerDeviceKind kind;
  kind.name = std::move(name);
  kind.argument = argument;
  kind.syntax = std::move(syntax);
  kind.help = std::move(help);
  kind.live = live;
  kind.recordsBytes = true;
  kind.silentHint = "is the Fastrak switched on, its receivers plugged in and streaming?";
  kind.create = [fastrak, transport](const TrackerDeviceSpec& spec,
                  const TrackerDeviceOptions& options) -> std::unique_ptr<TrackerDevice>
  {
    TransportOpener open = transport(spec, options);
    if (!options.recordPath.empty())
    {
      const std::string record = options.recordPath;
      open = [open, record]() -> std::unique_ptr<Transport>
      { return std::make_unique<RecordingTransport>(open(), record); };
    }
    FastrakOptions settings = fastrak;
    settings.stations = options.stations;
    settings.format = options.format;
    settings.reset = options.reset;
    return std::make_unique<FastrakDevice>(spec.ToString(), open, settings);
  };
  return kind;
}

TrackerDeviceKind UsbKind()
{
  TrackerDeviceKind kind = FastrakKind("usb",
    TrackerDeviceKind::Argument::Optional,
    "usb|usb:N",
    "usb: the first Fastrak on USB (vendor 0x0f44), usb:N the N-th (from 0)",
    true,
    {},
    [](const TrackerDeviceSpec& spec, const TrackerDeviceOptions& options) -> TransportOpener
    {
      auto backend = std::make_shared<std::shared_ptr<UsbBackend>>(options.usbBackend);
      const int index = spec.usbIndex;
      return [backend, index]() -> std::unique_ptr<Transport>
      {
        if (!*backend)
        {
          *backend = std::make_shared<LibusbBackend>();
        }
        LibusbTransport::Options usb;
        usb.deviceIndex = index;
        return std::make_unique<LibusbTransport>(*backend, usb);
      };
    });
  kind.parse = [](const std::string& index, TrackerDeviceSpec& spec) -> std::string
  {
    if (index.empty())
    {
      return {}; // "usb" or "usb:": the first unit
    }
    if (index.size() > 2 || index.find_first_not_of("0123456789") != std::string::npos)
    {
      return "'" + index + "' is not a device number";
    }
    spec.usbIndex = std::stoi(index);
    return {};
  };
  kind.format = [](const TrackerDeviceSpec& spec)
  { return spec.usbIndex == 0 ? std::string("usb") : "usb:" + std::to_string(spec.usbIndex); };
  return kind;
}

TrackerDeviceKind SerialKind()
{
  TrackerDeviceKind kind = FastrakKind("serial",
    TrackerDeviceKind::Argument::Required,
    "serial:PATH[@BAUD[,8N1]]",
    "a Fastrak on a serial port, e.g. serial:/dev/ttyUSB0, at 115200 8N1 unless @BAUD[,8N1] "
    "says otherwise",
    true,
    {},
    [](const TrackerDeviceSpec& spec, const TrackerDeviceOptions&) -> TransportOpener
    {
      return [path = spec.path, serial = spec.serial]() -> std::unique_ptr<Transport>
      { return std::make_unique<SerialTransport>(path, serial); };
    });
  kind.parse = [](const std::string& argument, TrackerDeviceSpec& spec) -> std::string
  {
    const std::size_t at = argument.rfind('@');
    if (at != std::string::npos)
    {
      spec.serial = SerialSettings::Parse(argument.substr(at + 1));
    }
    spec.path = argument.substr(0, at);
    return spec.path.empty() ? "no serial port path" : std::string();
  };
  kind.format = [](const TrackerDeviceSpec& spec) { return "serial:" + spec.path; };
  return kind;
}

TrackerDeviceKind ReplayKind()
{
  // A replay sends no commands: it runs exactly the decoding and threading of a live unit.
  FastrakOptions replayed;
  replayed.configure = false;
  replayed.measureLatency = false;
  TrackerDeviceKind kind = FastrakKind("replay",
    TrackerDeviceKind::Argument::Required,
    "replay:FILE",
    "plays the raw bytes of a Fastrak recording (FILE.timestamps used when present)",
    false,
    replayed,
    [](const TrackerDeviceSpec& spec, const TrackerDeviceOptions& options) -> TransportOpener
    {
      // Recording over the file being replayed would truncate it before it is read.
      if (!options.recordPath.empty() && SameFile(spec.path, options.recordPath))
      {
        throw RecordingError(
          options.recordPath + ": refusing to record over the recording being replayed");
      }
      ReplayTransport::Options replay;
      replay.realtime = options.realtime;
      return [path = spec.path, replay]() -> std::unique_ptr<Transport>
      { return std::make_unique<ReplayTransport>(path, replay); };
    });
  kind.parse = [](const std::string& argument, TrackerDeviceSpec& spec) -> std::string
  {
    spec.path = argument;
    return argument.empty() ? "no recording file" : std::string();
  };
  kind.format = [](const TrackerDeviceSpec& spec) { return "replay:" + spec.path; };
  kind.noPoses = [](const TrackerDeviceSpec& spec, const TrackerDeviceOptions& options)
  {
    return spec.path + ": no pose decoded (not a Fastrak " +
      (options.format == FastrakFormat::Binary ? "binary" : "ASCII") +
      " recording with the output list 2,11,16,0?)";
  };
  return kind;
}

TrackerDeviceKind IgtlKind()
{
  TrackerDeviceKind kind;
  kind.name = "igtl";
  kind.argument = TrackerDeviceKind::Argument::Required;
  kind.syntax = "igtl:HOST:PORT";
  kind.help = "an OpenIGTLink server (PLUS, 3D Slicer): every TRANSFORM, POSITION, QTDATA or "
              "TDATA pose, with its device name (station 1 and 2 for the two tools' names, 0 "
              "for others), converted RAS -> LPS";
  kind.live = true;
  kind.silentHint = "does the server stream TRANSFORM, POSITION, QTDATA or TDATA messages?";
  kind.parse = [](const std::string& argument, TrackerDeviceSpec& spec) -> std::string
  {
    ParseHostPort(argument, "device", spec.host, spec.port);
    return {};
  };
  kind.format = [](const TrackerDeviceSpec& spec)
  {
    return "igtl:" +
      (spec.host.find(':') != std::string::npos ? "[" + spec.host + "]" : spec.host) + ":" +
      std::to_string(spec.port);
  };
  kind.create = [](const TrackerDeviceSpec& spec,
                  const TrackerDeviceOptions& options) -> std::unique_ptr<TrackerDevice>
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
  };
  return kind;
}

TrackerDeviceKind SimulatorKind()
{
  TrackerDeviceKind kind;
  kind.name = "sim";
  kind.aliases = { "simulator" };
  kind.syntax = "sim";
  kind.help = "two scripted hands bending a ribbon";
  kind.parse = [](const std::string&, TrackerDeviceSpec&) { return std::string(); };
  kind.create = [](const TrackerDeviceSpec&,
                  const TrackerDeviceOptions& options) -> std::unique_ptr<TrackerDevice>
  {
    SimulatedDevice::Options sim;
    sim.stations = options.stations;
    sim.rateHz = options.simulatorRate;
    sim.duration = options.simulatorDuration;
    sim.realtime = options.simulatorRealtime;
    return std::make_unique<SimulatedDevice>(sim);
  };
  return kind;
}

std::vector<TrackerDeviceKind>& Table()
{
  static std::vector<TrackerDeviceKind> table{
    UsbKind(), SerialKind(), ReplayKind(), IgtlKind(), SimulatorKind()
  };
  return table;
}

// "usb|usb:N" -> {"usb", "usb:N"}.
std::vector<std::string> Forms(const TrackerDeviceKind& kind)
{
  std::vector<std::string> forms;
  std::size_t begin = 0;
  for (;;)
  {
    const std::size_t bar = kind.syntax.find('|', begin);
    forms.push_back(kind.syntax.substr(begin, bar - begin));
    if (bar == std::string::npos)
    {
      return forms;
    }
    begin = bar + 1;
  }
}

// "a, b or c" (with `separator` ", ").
std::string JoinForms(const std::vector<std::string>& forms, const std::string& separator)
{
  std::string text;
  for (std::size_t i = 0; i < forms.size(); ++i)
  {
    text += (i == 0 ? "" : i + 1 == forms.size() ? " or " : separator) + forms[i];
  }
  return text;
}

const TrackerDeviceKind* Find(const std::string& word)
{
  for (const TrackerDeviceKind& kind : Table())
  {
    if (kind.name == word ||
      std::find(kind.aliases.begin(), kind.aliases.end(), word) != kind.aliases.end())
    {
      return &kind;
    }
  }
  return nullptr;
}
} // namespace

const std::vector<TrackerDeviceKind>& TrackerDeviceKinds()
{
  return Table();
}

void RegisterTrackerDeviceKind(TrackerDeviceKind kind)
{
  if (kind.name.empty() || kind.name.find(':') != std::string::npos || kind.syntax.empty() ||
    !kind.parse || !kind.create)
  {
    throw TrackingConfigurationError("tracker device kind '" + kind.name +
      "': a kind needs a name without ':', a syntax, a parse and a create function");
  }
  std::vector<TrackerDeviceKind>& table = Table();
  for (TrackerDeviceKind& row : table)
  {
    if (row.name == kind.name)
    {
      row = std::move(kind);
      return;
    }
  }
  table.push_back(std::move(kind));
}

const TrackerDeviceKind& FindTrackerDeviceKind(const std::string& name)
{
  if (const TrackerDeviceKind* kind = Find(name))
  {
    return *kind;
  }
  throw TrackingConfigurationError(
    "no tracker device kind '" + name + "' (expected " + TrackerDeviceForms() + ")");
}

std::string TrackerDeviceForms()
{
  std::vector<std::string> forms;
  for (const TrackerDeviceKind& kind : Table())
  {
    const std::vector<std::string> own = Forms(kind);
    forms.insert(forms.end(), own.begin(), own.end());
  }
  return JoinForms(forms, ", ");
}

std::vector<std::string> TrackerDeviceHelpLines(std::size_t width)
{
  std::vector<std::string> lines;
  for (const TrackerDeviceKind& kind : Table())
  {
    std::string line = JoinForms(Forms(kind), ", ") + ":";
    std::size_t begin = 0;
    while (begin < kind.help.size())
    {
      std::size_t end = kind.help.find(' ', begin);
      end = end == std::string::npos ? kind.help.size() : end;
      const std::string word = kind.help.substr(begin, end - begin);
      if (line.size() + 1 + word.size() > width && line.size() > 2)
      {
        lines.push_back(line);
        line = "  " + word;
      }
      else
      {
        line += " " + word;
      }
      begin = end + 1;
    }
    lines.push_back(line);
  }
  return lines;
}

TrackerDeviceSpec TrackerDeviceSpec::Parse(const std::string& text)
{
  const auto bad = [&](const std::string& why)
  {
    return TrackingConfigurationError(
      "device '" + text + "': " + why + " (expected " + TrackerDeviceForms() + ")");
  };
  const std::size_t colon = text.find(':');
  const bool hasArgument = colon != std::string::npos;
  const TrackerDeviceKind* kind = Find(text.substr(0, colon));
  if (!kind || (hasArgument && kind->argument == TrackerDeviceKind::Argument::None) ||
    (!hasArgument && kind->argument == TrackerDeviceKind::Argument::Required))
  {
    throw bad("unknown device");
  }
  TrackerDeviceSpec spec;
  spec.kind = kind->name;
  spec.argument = hasArgument ? text.substr(colon + 1) : std::string();
  if (const std::string why = kind->parse(spec.argument, spec); !why.empty())
  {
    throw bad(why);
  }
  return spec;
}

std::string TrackerDeviceSpec::ToString() const
{
  const TrackerDeviceKind* kind = Find(this->kind);
  if (kind && kind->format)
  {
    return kind->format(*this);
  }
  return this->argument.empty() ? this->kind : this->kind + ":" + this->argument;
}

std::unique_ptr<TrackerDevice> CreateTrackerDevice(const TrackerDeviceSpec& spec,
  const TrackerDeviceOptions& options)
{
  return FindTrackerDeviceKind(spec.kind).create(spec, options);
}

} // namespace bender
