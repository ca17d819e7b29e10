#include "TrackerCommand.h"

#include "CliCommand.h"
#include "CliParsing.h"
#include "RibbonEndMapping.h"
#include "SignalGuard.h"
#include "TrackerDeviceRegistry.h"
#include "TrackerStream.h"
#include "TrackingErrors.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>

namespace bender
{

namespace
{
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

const char* const Details =
  "Streams poses from a Polhemus Fastrak (USB or serial), a recording, the simulator or an "
  "OpenIGTLink server and prints one JSON line per pose on stdout:\n"
  "  {\"t\": s, \"station\": n, \"position\": [x, y, z] (mm), \"quaternion\": [w, x, y, z], "
  "\"button\": 0|1}\n"
  "(OpenIGTLink: with the pose's \"device\" name.) Grab/release events and a summary (rates, "
  "dropped and malformed records) go to stderr. It stops at --count poses, the end of a "
  "replay, --duration, or Ctrl-C.\n"
  "\n"
  "example: bender-cli tracker --device replay:session.fastrak --realtime\n"
  "\n"
  "exit status: 0 streamed, 1 the device failed (not found, no reply, unplugged, bad "
  "recording), 2 usage error\n"
  "See docs/tracking.md for connecting a Fastrak, udev rules and the recording format.";

struct TrackerArguments
{
  std::string device;
  TrackerDeviceOptions options;
  double count = 0.0;
  double duration = 0.0;
  double timeout = 5.0;
  std::string stations;
  std::string tools;
  std::string format = "binary";
};

// A CLI11 check by one of the Tracking parsers, whose TrackingError is the message.
CLI::Validator ParsedBy(const std::function<void(const std::string&)>& parse)
{
  return CLI::Validator(
    [parse](std::string& text) -> std::string
    {
      try
      {
        parse(text);
      }
      catch (const TrackingError& e)
      {
        return e.what();
      }
      return {};
    },
    "");
}

void AddTrackerOptions(CLI::App& tracker, TrackerArguments& a)
{
  std::string devices = "the device: " + TrackerDeviceForms();
  for (const std::string& line : TrackerDeviceHelpLines(64))
  {
    devices += "\n" + line;
  }
  tracker.add_option("--device", a.device, devices)
    ->required()
    ->type_name("SPEC")
    ->check(ParsedBy([](const std::string& text) { TrackerDeviceSpec::Parse(text); }));
  tracker
    .add_option("--tools",
      a.tools,
      "OpenIGTLink device names of hand 1 and hand 2 (default StylusToTracker,Stylus2ToTracker)")
    ->type_name("A,B")
    ->check(CLI::Validator(
      [](std::string& text) -> std::string
      {
        const std::size_t comma = text.find(',');
        return comma == std::string::npos || text.find(',', comma + 1) != std::string::npos
          ? "'" + text + "': expected two names separated by a comma"
          : std::string();
      },
      ""));
  tracker
    .add_option(
      "--record", a.options.recordPath, "write what the device sends to FILE (+ FILE.timestamps)")
    ->type_name("FILE");
  tracker.add_option("--count", a.count, "stop after N poses")
    ->type_name("N")
    ->check(IntegerIn(1, 1e12));
  tracker.add_option("--stations", a.stations, "stations to activate and print (default 1,2)")
    ->type_name("LIST")
    ->check(ParsedBy([](const std::string& text) { ParseStationList(text); }));
  OneOf(
    tracker.add_option("--format", a.format, "Fastrak records (for replay: how FILE was recorded)"),
    { "binary", "ascii" })
    ->capture_default_str();
  tracker.add_flag(
    "--realtime", a.options.realtime, "replay at the recorded pace instead of as fast as possible");
  tracker.add_option("--duration", a.duration, "stop after S seconds of pose time")
    ->type_name("S")
    ->check(NumberIn(0.001, 1e7));
  tracker.add_option("--timeout", a.timeout, "fail when a live device sends no pose within S s")
    ->type_name("S")
    ->check(NumberIn(0.1, 3600))
    ->capture_default_str();
  tracker.add_flag("--reset", a.options.reset, "reset the unit (^Y) first; takes about 10 s");
}

int RunTracker(TrackerArguments a, std::ostream& out, std::ostream& err)
{
  const std::string& deviceText = a.device;
  TrackerDeviceOptions& options = a.options;
  if (!a.tools.empty())
  {
    const std::size_t comma = a.tools.find(',');
    options.igtlToolNames = { a.tools.substr(0, comma), a.tools.substr(comma + 1) };
  }
  if (!a.stations.empty())
  {
    options.stations = ParseStationList(a.stations);
  }
  options.format = a.format == "ascii" ? FastrakFormat::Ascii : FastrakFormat::Binary;
  const std::uint64_t count = std::uint64_t(a.count);
  const double duration = a.duration;
  const double timeout = a.timeout;

  std::unique_ptr<TrackerStream> stream;
  try
  {
    stream = std::make_unique<TrackerStream>(deviceText, options);
  }
  catch (const TrackingError& e)
  {
    err << "bender-cli tracker: " << ErrorLine(e.what()) << "\n";
    return 2;
  }

  bender::SignalGuard signals;
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
      stream->Run(limits, sink, [&signals]() { return signals.Interrupted(); });
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
    err << "bender-cli tracker: " << ErrorLine(e.what()) << "\n";
    return 1;
  }
  return status;
}
} // namespace

void AddTrackerCommand(CLI::App& cli,
  std::ostream& out,
  std::ostream& err,
  std::shared_ptr<UsbBackend> usbBackend)
{
  auto a = std::make_shared<TrackerArguments>();
  a->options.usbBackend = std::move(usbBackend);
  CLI::App* tracker = AddCommand(cli,
    "tracker",
    "stream poses from a Polhemus Fastrak, OpenIGTLink, a recording or the simulator",
    Details,
    [a, &out, &err] { return RunTracker(*a, out, err); });
  AddTrackerOptions(*tracker, *a);
}

int RunTrackerCli(const std::vector<std::string>& args,
  std::ostream& out,
  std::ostream& err,
  std::shared_ptr<UsbBackend> usbBackend)
{
  return RunAlone("tracker",
    args,
    out,
    err,
    [&](CLI::App& cli) { AddTrackerCommand(cli, out, err, usbBackend); });
}

} // namespace bender
