#include "TrackerCommand.h"

#include "RibbonEndMapping.h"
#include "TrackerStream.h"
#include "TrackingErrors.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <ostream>

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
  std::string devices;
  for (const TrackerDeviceKind& kind : TrackerDeviceKinds())
  {
    devices += (devices.empty() ? "" : "|") + kind.syntax;
  }
  std::string deviceHelp;
  for (const std::string& line : TrackerDeviceHelpLines(71))
  {
    deviceHelp += "                   " + line + "\n";
  }
  return "usage: bender-cli tracker --device SPEC\n"
         "                          [--record FILE] [--count N] [--stations 1,2]\n"
         "                          [--tools NAME1,NAME2]\n"
         "                          [--format binary|ascii] [--realtime] [--duration S]\n"
         "                          [--timeout S] [--reset]\n\n"
         "Streams poses from a Polhemus Fastrak (USB or serial), a recording, the simulator or\n"
         "an OpenIGTLink server and prints one JSON line per pose on stdout:\n"
         "  {\"t\": s, \"station\": n, \"position\": [x, y, z] (mm), \"quaternion\": [w, x, y, z],"
         " \"button\": 0|1}\n"
         "(OpenIGTLink: with the pose's \"device\" name.) Grab/release events and a summary\n"
         "(rates, dropped and malformed records) go to stderr.\n\n"
         "  --device SPEC    " +
    devices + "\n" + deviceHelp +
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

  std::unique_ptr<TrackerStream> stream;
  try
  {
    stream = std::make_unique<TrackerStream>(deviceText, options);
  }
  catch (const TrackingError& e)
  {
    err << "bender-cli tracker: " << e.what() << "\n";
    return 2;
  }

  SignalGuard signals;
  int status = 0;
  try
  {
    TrackerStream::Limits limits;
    limits.count = count;
    limits.duration = duration;
    limits.timeout = timeout;
    TrackerStream::Sink sink;
    sink.pose = [&out](const TrackerPose& pose, const std::string* name)
    { out << PoseJson(pose, name) << '\n'; };
    sink.batchDone = [&out]() { out.flush(); };
    sink.event = [&err](const TrackerEvent& event)
    {
      char line[96];
      std::snprintf(line,
        sizeof line,
        "%s station %d at t=%.3f s\n",
        ToString(event.type),
        event.station,
        event.time);
      err << line;
    };
    const TrackerStream::Result result =
      stream->Run(limits, sink, []() { return Interrupted != 0; });
    if (result.interrupted)
    {
      err << "bender-cli tracker: interrupted\n";
    }
    if (!result.failure.empty())
    {
      err << "bender-cli tracker: " << result.failure << "\n";
      status = 1;
    }
    PrintSummary(err, stream->Name(), stream->Statistics(), result.poses);
    for (const std::string& line : stream->SummaryLines())
    {
      err << "  " << line << "\n";
    }
    stream->Close();
    if (!result.noPoses.empty())
    {
      err << "bender-cli tracker: " << result.noPoses << "\n";
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
