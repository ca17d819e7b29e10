#include "TrackerCommand.h"

#include "FastrakEncoding.h"
#include "IgtlDevice.h"
#include "RibbonEndMapping.h"
#include "StreamRecorder.h"
#include "TrackerDeviceFactory.h"
#include "TrackingErrors.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ostream>
#include <sys/stat.h>

namespace bender
{

namespace
{
volatile std::sig_atomic_t Interrupted = 0;

extern "C" void OnSignal(int)
{
  Interrupted = 1;
}

// Installs the handlers for the duration of the command and restores the previous ones.
class SignalGuard
{
public:
  SignalGuard()
  {
    Interrupted = 0;
    this->OldInt = std::signal(SIGINT, OnSignal);
    this->OldTerm = std::signal(SIGTERM, OnSignal);
  }
  ~SignalGuard()
  {
    std::signal(SIGINT, this->OldInt);
    std::signal(SIGTERM, this->OldTerm);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

private:
  void (*OldInt)(int) = SIG_DFL;
  void (*OldTerm)(int) = SIG_DFL;
};

struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

double ParseNumber(const std::string& option, const std::string& value, double min, double max)
{
  std::size_t used = 0;
  double v = 0.0;
  try
  {
    v = std::stod(value, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used != value.size() || !std::isfinite(v) || v < min || v > max)
  {
    throw UsageError(option + " '" + value + "': expected a number in [" + std::to_string(min) +
      ", " + std::to_string(max) + "]");
  }
  return v;
}

// Rounded to the printed precision (4 decimals in mm, 6 for time and quaternions); "+ 0.0"
// turns -0 into 0, so that JSON consumers never see "-0.0".
double Rounded(double value, double scale)
{
  return std::round(value * scale) / scale + 0.0;
}

std::string PoseJson(const TrackerPose& p, const std::string* deviceName = nullptr)
{
  nlohmann::ordered_json line;
  line["t"] = Rounded(p.time, 1e6);
  line["station"] = p.station;
  if (deviceName)
  {
    line["device"] = *deviceName;
  }
  line["position"] = {
    Rounded(p.position.x, 1e4), Rounded(p.position.y, 1e4), Rounded(p.position.z, 1e4)
  };
  line["quaternion"] = { Rounded(p.orientation.w, 1e6),
    Rounded(p.orientation.x, 1e6),
    Rounded(p.orientation.y, 1e6),
    Rounded(p.orientation.z, 1e6) };
  line["button"] = p.button ? 1 : 0;
  return line.dump();
}

void PrintSummary(std::ostream& err,
  const std::string& device,
  const TrackerStatistics& s,
  std::uint64_t printed)
{
  char line[256];
  std::snprintf(line,
    sizeof line,
    "tracker summary: %s, %llu poses printed\n",
    device.c_str(),
    static_cast<unsigned long long>(printed));
  err << line;
  for (const StationStatistics& st : s.stations)
  {
    std::snprintf(line,
      sizeof line,
      "  station %d: %llu samples over %.3f s, %.1f Hz\n",
      st.station,
      static_cast<unsigned long long>(st.samples),
      st.lastTime - st.firstTime,
      st.RateHz());
    err << line;
  }
  std::snprintf(line,
    sizeof line,
    "  records %llu, dropped %llu, malformed %llu, truncated %llu, garbage bytes %llu, "
    "warnings %llu, other stations %llu, queue overflows %llu\n",
    static_cast<unsigned long long>(s.parser.records),
    static_cast<unsigned long long>(s.parser.dropped),
    static_cast<unsigned long long>(s.parser.malformed),
    static_cast<unsigned long long>(s.parser.truncated),
    static_cast<unsigned long long>(s.parser.garbageBytes),
    static_cast<unsigned long long>(s.parser.warnings),
    static_cast<unsigned long long>(s.filtered),
    static_cast<unsigned long long>(s.queueOverflows));
  err << line;
  if (s.latencyMs)
  {
    std::snprintf(
      line, sizeof line, "  latency: %.1f ms (median round trip of 'P')\n", *s.latencyMs);
    err << line;
  }
}
} // namespace

std::string TrackerCliUsage()
{
  return "usage: bender-cli tracker --device usb|usb:N|serial:PATH[@BAUD[,8N1]]|replay:FILE|sim|\n"
         "                                   igtl:HOST:PORT\n"
         "                          [--record FILE] [--count N] [--stations 1,2]\n"
         "                          [--tools NAME1,NAME2]\n"
         "                          [--format binary|ascii] [--realtime] [--duration S]\n"
         "                          [--timeout S] [--reset]\n\n"
         "Streams poses from a Polhemus Fastrak (USB or serial), a recording or the simulator\n"
         "and prints one JSON line per pose on stdout:\n"
         "  {\"t\": s, \"station\": n, \"position\": [x, y, z] (mm), \"quaternion\": [w, x, y, z],"
         " \"button\": 0|1}\n"
         "Grab/release events and a summary (rates, dropped and malformed records) go to "
         "stderr.\n\n"
         "  --device SPEC    usb: first Fastrak on USB (vendor 0x0f44); serial:/dev/ttyUSB0 at\n"
         "                   115200 8N1 unless @BAUD[,8N1] says otherwise; replay:FILE plays raw\n"
         "                   bytes recorded in binary mode (FILE.timestamps used when present);\n"
         "                   sim: two scripted hands bending a ribbon; igtl:HOST:PORT: an\n"
         "                   OpenIGTLink server (PLUS, 3D Slicer): every TRANSFORM, POSITION,\n"
         "                   QTDATA or TDATA pose is printed with its \"device\" name (station 1\n"
         "                   and 2 for the --tools names, 0 for others), converted RAS -> LPS\n"
         "  --tools A,B      OpenIGTLink device names of hand 1 and hand 2\n"
         "                   (default StylusToTracker,Stylus2ToTracker)\n"
         "  --record FILE    write what the device sends to FILE (+ FILE.timestamps)\n"
         "  --count N        stop after N poses\n"
         "  --stations LIST  stations to activate and print (default 1,2)\n"
         "  --format F       binary (default) or ascii records (for replay: how FILE was "
         "recorded)\n"
         "  --realtime       replay at the recorded pace instead of as fast as possible\n"
         "  --duration S     stop after S seconds of pose time\n"
         "  --timeout S      fail when a live device sends no pose within S s (default 5)\n"
         "  --reset          reset the unit (^Y) first; takes about 10 s\n"
         "See docs/tracking.md for connecting a Fastrak, udev rules and the recording format.\n";
}

int RunTrackerCli(const std::vector<std::string>& args,
  std::ostream& out,
  std::ostream& err,
  std::shared_ptr<UsbBackend> usbBackend)
{
  std::string deviceText;
  TrackerDeviceOptions options;
  options.usbBackend = std::move(usbBackend);
  std::uint64_t count = 0;
  double duration = 0.0;
  double timeout = 5.0;
  try
  {
    CLI::App app("", "bender-cli tracker");
    app.set_help_flag();
    bool help = false;
    std::string countText, stationsText, formatText, durationText, timeoutText, toolsText;
    app.add_flag("-h,--help", help);
    app.add_option("--device", deviceText);
    app.add_option("--record", options.recordPath);
    app.add_option("--count", countText);
    app.add_option("--stations", stationsText);
    app.add_option("--tools", toolsText);
    app.add_option("--format", formatText);
    app.add_flag("--realtime", options.realtime);
    app.add_option("--duration", durationText);
    app.add_option("--timeout", timeoutText);
    app.add_flag("--reset", options.reset);
    try
    {
      std::vector<std::string> reversed(args.rbegin(), args.rend());
      app.parse(reversed);
    }
    catch (const CLI::ParseError& e)
    {
      if (!help)
      {
        throw UsageError(e.what());
      }
    }
    if (help)
    {
      out << TrackerCliUsage();
      return 0;
    }
    if (app.count("--count"))
    {
      count = std::uint64_t(ParseNumber("--count", countText, 1, 1e12));
    }
    if (app.count("--stations"))
    {
      options.stations = ParseStationList(stationsText);
    }
    if (app.count("--tools"))
    {
      const std::size_t comma = toolsText.find(',');
      if (comma == std::string::npos || toolsText.find(',', comma + 1) != std::string::npos)
      {
        throw UsageError("--tools '" + toolsText + "': expected two names separated by a comma");
      }
      options.igtlToolNames = { toolsText.substr(0, comma), toolsText.substr(comma + 1) };
    }
    if (app.count("--format"))
    {
      if (formatText != "binary" && formatText != "ascii")
      {
        throw UsageError("--format '" + formatText + "': expected binary or ascii");
      }
      options.format = formatText == "binary" ? FastrakFormat::Binary : FastrakFormat::Ascii;
    }
    if (app.count("--duration"))
    {
      duration = ParseNumber("--duration", durationText, 0.001, 1e7);
    }
    if (app.count("--timeout"))
    {
      timeout = ParseNumber("--timeout", timeoutText, 0.1, 3600);
    }
    if (deviceText.empty())
    {
      throw UsageError("--device is required");
    }
  }
  catch (const std::exception& e)
  {
    err << "bender-cli tracker: " << e.what() << "\n"
        << "run 'bender-cli tracker --help' for usage\n";
    return 2;
  }

  TrackerDeviceSpec spec;
  try
  {
    spec = TrackerDeviceSpec::Parse(deviceText);
  }
  catch (const TrackingError& e)
  {
    err << "bender-cli tracker: " << e.what() << "\n";
    return 2;
  }
  const bool live = spec.kind == TrackerDeviceSpec::Kind::Usb ||
    spec.kind == TrackerDeviceSpec::Kind::Serial || spec.kind == TrackerDeviceSpec::Kind::Igtl;
  const bool simulated = spec.kind == TrackerDeviceSpec::Kind::Simulator;
  const bool igtl = spec.kind == TrackerDeviceSpec::Kind::Igtl;

  // Recording over the file being replayed would truncate it before it is read.
  if (spec.kind == TrackerDeviceSpec::Kind::Replay && !options.recordPath.empty())
  {
    struct stat a
    {
    }, b{};
    if (::stat(spec.path.c_str(), &a) == 0 && ::stat(options.recordPath.c_str(), &b) == 0 &&
      a.st_dev == b.st_dev && a.st_ino == b.st_ino)
    {
      err << "bender-cli tracker: " << options.recordPath
          << ": refusing to record over the recording being replayed\n";
      return 1;
    }
  }

  SignalGuard signals;
  std::unique_ptr<TrackerDevice> device;
  std::unique_ptr<StreamRecorder> simRecorder;
  std::uint64_t printed = 0;
  int status = 0;
  try
  {
    // The simulator and OpenIGTLink send no Fastrak bytes: their recording is the binary
    // records a Fastrak would have sent for the two hands (so replay:FILE plays it back).
    TrackerDeviceOptions deviceOptions = options;
    if ((simulated || igtl) && !options.recordPath.empty())
    {
      simRecorder = std::make_unique<StreamRecorder>(options.recordPath);
      deviceOptions.recordPath.clear();
    }
    device = CreateTrackerDevice(spec, deviceOptions);
    // Replay: lose nothing (the reader waits for us); live: keep the newest.
    device->EnablePoseQueue(4096, !live);
    // OpenIGTLink: print every pose with its device name, hands or not.
    IgtlDevice* igtlDevice = dynamic_cast<IgtlDevice*>(device.get());
    if (igtlDevice)
    {
      igtlDevice->EnableNamedQueue(4096);
    }
    device->Open();
    device->Start();
    const auto started = std::chrono::steady_clock::now();
    bool done = false;
    while (!done)
    {
      if (Interrupted)
      {
        err << "bender-cli tracker: interrupted\n";
        break;
      }
      device->WaitForActivity(std::chrono::milliseconds(100));
      const std::vector<TrackerEvent> events = device->TakeEvents();
      const std::vector<TrackerPose> poses = device->TakePoses();
      std::vector<IgtlNamedPose> named;
      if (igtlDevice)
      {
        named = igtlDevice->TakeNamedPoses();
      }
      else
      {
        for (const TrackerPose& pose : poses)
        {
          named.push_back({ {}, pose });
        }
      }
      for (const IgtlNamedPose& item : named)
      {
        const TrackerPose& pose = item.pose;
        if (duration > 0.0 && pose.time > duration)
        {
          done = true;
          break;
        }
        out << PoseJson(pose, igtlDevice ? &item.name : nullptr) << '\n';
        if (simRecorder && pose.station >= 1)
        {
          const std::vector<std::uint8_t> record = EncodeFastrakRecord(pose, FastrakFormat::Binary);
          simRecorder->Append(record.data(), record.size(), pose.time);
        }
        ++printed;
        if (count > 0 && printed >= count)
        {
          done = true;
          break;
        }
      }
      out.flush();
      for (const TrackerEvent& event : events)
      {
        if (event.type == TrackerEventType::Grab || event.type == TrackerEventType::Release)
        {
          char line[96];
          std::snprintf(line,
            sizeof line,
            "%s station %d at t=%.3f s\n",
            ToString(event.type),
            event.station,
            event.time);
          err << line;
        }
        else if (event.type == TrackerEventType::EndOfStream)
        {
          done = true;
        }
        else if (!done)
        {
          err << "bender-cli tracker: " << device->Name() << ": " << event.message << "\n";
          status = 1;
          done = true;
        }
      }
      if (!done && printed == 0 && !simulated &&
        std::chrono::steady_clock::now() - started > std::chrono::duration<double>(timeout))
      {
        err << "bender-cli tracker: " << device->Name() << ": no pose within " << timeout
            << (igtl ? " s; does the server stream TRANSFORM, POSITION, QTDATA or TDATA messages?\n"
                     : " s; is the Fastrak switched on, its receivers plugged in and streaming?\n");
        status = 1;
        done = true;
      }
    }
    device->Stop();
    PrintSummary(err, spec.ToString(), device->Statistics(), printed);
    if (igtlDevice)
    {
      const IgtlStatistics s = igtlDevice->IgtlStats();
      err << "  igtl: " << s.decoder.messages << " messages, " << s.poses << " poses, "
          << s.invalidPoses << " invalid, " << s.decoder.crcErrors << " CRC errors, "
          << s.decoder.malformed << " malformed, " << s.unknownTypes << " skipped ("
          << s.buttonMessages << " button, " << s.statusMessages << " status messages)\n";
      for (const auto& [name, n] : s.names)
      {
        err << "  device '" << name << "': " << n << " poses"
            << (name == options.igtlToolNames[0]      ? " (hand 1)"
                   : name == options.igtlToolNames[1] ? " (hand 2)"
                                                      : " (not a hand: see --tools)")
            << "\n";
      }
      for (const auto& [type, n] : s.skippedTypes)
      {
        err << "  skipped " << type << ": " << n << "\n";
      }
      if (!s.lastStatus.empty())
      {
        err << "  last problem: " << s.lastStatus << "\n";
      }
    }
    device->Close();
    if (status == 0 && printed == 0 && spec.kind == TrackerDeviceSpec::Kind::Replay)
    {
      err << "bender-cli tracker: " << spec.path << ": no pose decoded (not a Fastrak "
          << (options.format == FastrakFormat::Binary ? "binary" : "ASCII")
          << " recording with the output list 2,11,16,0?)\n";
      status = 1;
    }
  }
  catch (const std::exception& e)
  {
    err << "bender-cli tracker: " << e.what() << "\n";
    return 1;
  }
  return status;
}

} // namespace bender
