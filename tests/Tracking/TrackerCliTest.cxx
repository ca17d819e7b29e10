// bender-cli tracker, in-process (TrackerCommand) and, once the whole tree is built, as
// the real executable.
#include "FastrakParser.h"
#include "SimulatedDevice.h"
#include "SimulationScript.h"
#include "TrackerCommand.h"
#include "TrackerDeviceRegistry.h"
#include "TrackingErrors.h"
#include "TrackingTestUtilities.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>

namespace bender::test
{
namespace
{

const std::string Fixture = std::string(BENDER_TEST_DATA_DIR) + "/tracking/two-hands.fastrak";

struct CliResult
{
  int status;
  std::vector<std::string> lines;
  std::string err;
};

CliResult RunCli(const std::vector<std::string>& args)
{
  std::ostringstream out, err;
  CliResult r;
  r.status = RunTrackerCli(args, out, err);
  std::istringstream lines(out.str());
  for (std::string line; std::getline(lines, line);)
  {
    r.lines.push_back(line);
  }
  r.err = err.str();
  return r;
}

// Reads the numbers of one output line back ({"t": ..., "station": ..., ...}).
TrackerPose ParseLine(const std::string& line)
{
  TrackerPose p;
  try
  {
    const nlohmann::json j = nlohmann::json::parse(line);
    EXPECT_EQ(j.size(), 5u) << line;
    p.time = j.at("t").get<double>();
    p.station = j.at("station").get<int>();
    const auto& x = j.at("position");
    p.position = { x.at(0).get<double>(), x.at(1).get<double>(), x.at(2).get<double>() };
    const auto& q = j.at("quaternion");
    p.orientation.w = q.at(0).get<double>();
    p.orientation.x = q.at(1).get<double>();
    p.orientation.y = q.at(2).get<double>();
    p.orientation.z = q.at(3).get<double>();
    const int button = j.at("button").get<int>();
    EXPECT_TRUE(button == 0 || button == 1) << line;
    p.button = button == 1;
  }
  catch (const nlohmann::json::exception& e)
  {
    ADD_FAILURE() << "not a pose JSON line: " << line << " (" << e.what() << ")";
  }
  return p;
}

TEST(TrackerCli, HelpAndUsageErrors)
{
  const CliResult help = RunCli({ "--help" });
  EXPECT_EQ(help.status, 0);
  ASSERT_FALSE(help.lines.empty());
  EXPECT_NE(help.lines[0].find("usage: bender-cli tracker --device"), std::string::npos);
  EXPECT_EQ(RunCli({}).status, 2);
  EXPECT_EQ(RunCli({ "--device" }).status, 2);
  EXPECT_EQ(RunCli({ "--device", "floppy" }).status, 2);
  EXPECT_EQ(RunCli({ "--device", "sim", "--count", "zero" }).status, 2);
  EXPECT_EQ(RunCli({ "--device", "sim", "--stations", "1,7" }).status, 2);
  EXPECT_EQ(RunCli({ "--device", "serial:/dev/ttyS0@1234" }).status, 2);
  const CliResult unknown = RunCli({ "--device", "sim", "--frobnicate" });
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("--frobnicate"), std::string::npos);
}

TEST(TrackerCli, ReplayPrintsOneJsonLinePerPoseAndASummary)
{
  const CliResult r = RunCli({ "--device", "replay:" + Fixture });
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.lines.size(), 122u);
  const SimulationScript script = SimulationScript::TwoHandBend();
  for (std::size_t i = 0; i < r.lines.size(); ++i)
  {
    const TrackerPose got = ParseLine(r.lines[i]);
    const TrackerPose expected =
      ExpectedBinary(script.PoseAt(int(i % 2) + 1, double(i / 2) / 10.0));
    EXPECT_EQ(got.station, expected.station);
    EXPECT_EQ(got.button, expected.button);
    ExpectPoseEq(expected, got, 1e-4);
  }
  EXPECT_NE(r.err.find("tracker summary: replay:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("station 1: 61 samples"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("dropped 0, malformed 0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("grab station 1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("release station 1"), std::string::npos) << r.err;
}

TEST(TrackerCli, CountStationsAndDuration)
{
  const CliResult counted = RunCli({ "--device", "replay:" + Fixture, "--count", "5" });
  EXPECT_EQ(counted.status, 0);
  EXPECT_EQ(counted.lines.size(), 5u);
  const CliResult right = RunCli({ "--device", "replay:" + Fixture, "--stations", "2" });
  EXPECT_EQ(right.lines.size(), 61u);
  for (const std::string& line : right.lines)
  {
    EXPECT_EQ(ParseLine(line).station, 2);
  }
  const CliResult early = RunCli({ "--device", "replay:" + Fixture, "--duration", "1.0" });
  EXPECT_EQ(early.status, 0);
  for (const std::string& line : early.lines)
  {
    EXPECT_LE(ParseLine(line).time, 1.0);
  }
  EXPECT_LT(early.lines.size(), 40u);
}

TEST(TrackerCli, BadRecordingsFailWithAMessage)
{
  ScratchDir dir;
  const CliResult missing = RunCli({ "--device", "replay:" + dir.File("nope.fastrak") });
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("nope.fastrak"), std::string::npos) << missing.err;
  const std::string garbage = dir.File("garbage.bin");
  std::ofstream(garbage) << std::string(500, 'z');
  const CliResult noise = RunCli({ "--device", "replay:" + garbage });
  EXPECT_EQ(noise.status, 1);
  EXPECT_TRUE(noise.lines.empty());
  EXPECT_NE(noise.err.find("no pose decoded"), std::string::npos) << noise.err;
  EXPECT_NE(noise.err.find("garbage bytes 500"), std::string::npos) << noise.err;
  const CliResult serial = RunCli({ "--device", "serial:" + dir.File("ttyNothing") });
  EXPECT_EQ(serial.status, 1);
  EXPECT_NE(serial.err.find("no such port"), std::string::npos) << serial.err;
  // Recording over the recording being replayed would truncate it: refused, file untouched.
  const std::string copy = dir.File("copy.fastrak");
  std::ofstream(copy, std::ios::binary) << std::string(1000, '0');
  const CliResult same = RunCli({ "--device", "replay:" + copy, "--record", copy });
  EXPECT_EQ(same.status, 1);
  EXPECT_NE(same.err.find("refusing to record over"), std::string::npos) << same.err;
  std::ifstream back(copy, std::ios::binary | std::ios::ate);
  EXPECT_EQ(static_cast<long>(back.tellg()), 1000L);
}

TEST(TrackerCli, AsciiReplay)
{
  ScratchDir dir;
  const std::string file = dir.File("ascii.fastrak");
  const Bytes stream = Encode(SamplePoses(), FastrakFormat::Ascii);
  std::ofstream(file, std::ios::binary) << std::string(stream.begin(), stream.end());
  const CliResult r = RunCli({ "--device", "replay:" + file, "--format", "ascii" });
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.lines.size(), 4u);
  EXPECT_NEAR(ParseLine(r.lines[0]).position.y, -1507.0, 1e-3);
}

TEST(TrackerCli, SimulatorRecordingReplaysToTheSamePoses)
{
  ScratchDir dir;
  const std::string file = dir.File("sim.fastrak");
  const CliResult sim = RunCli({ "--device", "sim", "--count", "6", "--record", file });
  ASSERT_EQ(sim.status, 0) << sim.err;
  ASSERT_EQ(sim.lines.size(), 6u);
  struct stat info
  {
  };
  ASSERT_EQ(::stat((file + ".timestamps").c_str(), &info), 0);
  const CliResult replay = RunCli({ "--device", "replay:" + file });
  ASSERT_EQ(replay.status, 0) << replay.err;
  ASSERT_EQ(replay.lines.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i)
  {
    ExpectPoseEq(ParseLine(sim.lines[i]), ParseLine(replay.lines[i]), 1e-4);
  }
}

// A device kind registered by a test: the simulator's hands at 20 Hz for `dummy:SECONDS`,
// with a summary line of its own.
class DummyDevice : public SimulatedDevice
{
public:
  using SimulatedDevice::SimulatedDevice;
  std::vector<std::string> SummaryLines() const override { return { "dummy: all quiet" }; }
};

TrackerDeviceKind DummyKind()
{
  TrackerDeviceKind kind;
  kind.name = "dummy";
  kind.argument = TrackerDeviceKind::Argument::Required;
  kind.syntax = "dummy:SECONDS";
  kind.help = "a test's device: scripted hands for SECONDS";
  kind.parse = [](const std::string& seconds, TrackerDeviceSpec& spec) -> std::string
  {
    spec.path = seconds;
    return seconds.find_first_not_of("0123456789") == std::string::npos && !seconds.empty()
      ? std::string()
      : "'" + seconds + "' is not a number of seconds";
  };
  kind.create = [](const TrackerDeviceSpec& spec, const TrackerDeviceOptions& options)
  {
    SimulatedDevice::Options sim;
    sim.stations = options.stations;
    sim.rateHz = 20.0;
    sim.duration = std::stod(spec.path);
    sim.realtime = false;
    return std::make_unique<DummyDevice>(sim);
  };
  return kind;
}

TEST(TrackerCli, ARegisteredDeviceKindIsListedParsedAndStreamed)
{
  RegisterTrackerDeviceKind(DummyKind());
  // Listed where users look: the --device help and the parse errors' list of forms.
  const CliResult help = RunCli({ "--help" });
  std::string helpText;
  for (const std::string& line : help.lines)
  {
    helpText += line + "\n";
  }
  EXPECT_NE(helpText.find("dummy:SECONDS"), std::string::npos) << helpText;
  EXPECT_NE(helpText.find("a test's device"), std::string::npos) << helpText;
  const CliResult unknown = RunCli({ "--device", "floppy" });
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("dummy:SECONDS"), std::string::npos) << unknown.err;
  EXPECT_EQ(RunCli({ "--device", "dummy" }).status, 2);
  const CliResult bad = RunCli({ "--device", "dummy:soon" });
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("'soon' is not a number of seconds"), std::string::npos) << bad.err;
  EXPECT_EQ(TrackerDeviceSpec::Parse("dummy:2").ToString(), "dummy:2");
  EXPECT_THROW(RegisterTrackerDeviceKind(TrackerDeviceKind{}), TrackingConfigurationError);

  // Streamed like any device: 2 s at 20 Hz on two stations, then its own summary line.
  const CliResult r = RunCli({ "--device", "dummy:2" });
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.lines.size(), 2u * 41u);
  const SimulationScript script = SimulationScript::TwoHandBend();
  for (const std::string& line : r.lines)
  {
    const TrackerPose got = ParseLine(line);
    ExpectPoseEq(script.PoseAt(got.station, got.time), got, 1e-4);
  }
  EXPECT_NE(r.err.find("tracker summary: dummy:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("  dummy: all quiet\n"), std::string::npos) << r.err;
}

// The real executable, once the whole tree builds (label: pipeline).
TEST(TrackerCliPipeline, ExecutableReplaysTheFixture)
{
  struct stat info
  {
  };
  if (::stat(BENDER_CLI_PATH, &info) != 0)
  {
    GTEST_FAIL() << BENDER_CLI_PATH << " is not built";
  }
  const std::string command =
    std::string(BENDER_CLI_PATH) + " tracker --device replay:" + Fixture + " --count 3 2>/dev/null";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::vector<std::string> lines;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe))
  {
    lines.emplace_back(buffer);
  }
  const int status = ::pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(ParseLine(lines[0]).station, 1);

  const std::string usb = std::string(BENDER_CLI_PATH) + " tracker --device usb --count 1 2>&1";
  pipe = ::popen(usb.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  while (std::fgets(buffer, sizeof buffer, pipe))
  {
    text += buffer;
  }
  EXPECT_NE(WEXITSTATUS(::pclose(pipe)), 0);
  EXPECT_NE(text.find("USB"), std::string::npos) << text;
}

} // namespace
} // namespace bender::test
