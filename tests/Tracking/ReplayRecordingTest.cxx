// Recording and replay: the committed fixture, record -> replay round trips, the sidecar.
#include "FastrakDevice.h"
#include "FastrakParser.h"
#include "RecordingTransport.h"
#include "ReplayTransport.h"
#include "SimulationScript.h"
#include "StreamRecorder.h"
#include "TrackerDeviceRegistry.h"
#include "TrackingTestUtilities.h"

#include <fstream>
#include <iterator>
#include <sstream>

namespace bender::test
{
namespace
{

const std::string FixturePath = std::string(BENDER_TEST_DATA_DIR) + "/tracking/two-hands.fastrak";
constexpr double FixtureRate = 10.0;     // samples per second per station
constexpr int FixtureSamples = 61;       // 0..6 s
constexpr std::size_t FixtureChunk = 64; // bytes per USB-like packet

std::string ReadText(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
}

/// The fixture: the simulator's two hands at 10 Hz for 6 s, as binary records, received in
/// 64-byte packets stamped with the sample time of their last byte.
void GenerateFixture(const std::string& path)
{
  const SimulationScript script = SimulationScript::TwoHandBend();
  Bytes stream;
  std::vector<double> recordTime;
  for (int k = 0; k < FixtureSamples; ++k)
  {
    for (int station : { 1, 2 })
    {
      const Bytes r =
        EncodeFastrakRecord(script.PoseAt(station, k / FixtureRate), FastrakFormat::Binary);
      stream.insert(stream.end(), r.begin(), r.end());
      recordTime.push_back(k / FixtureRate);
    }
  }
  StreamRecorder recorder(path);
  for (std::size_t offset = 0; offset < stream.size(); offset += FixtureChunk)
  {
    const std::size_t n = std::min(FixtureChunk, stream.size() - offset);
    recorder.Append(stream.data() + offset, n, recordTime[(offset + n - 1) / 34]);
  }
}

std::vector<TrackerPose> DrainUntilEnd(TrackerDevice& device,
  std::vector<TrackerEvent>* eventsOut = nullptr)
{
  std::vector<TrackerPose> poses;
  std::vector<TrackerEvent> events;
  for (int i = 0; i < 1000; ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(20));
    const std::vector<TrackerEvent> e = device.TakeEvents();
    const std::vector<TrackerPose> p = device.TakePoses();
    poses.insert(poses.end(), p.begin(), p.end());
    events.insert(events.end(), e.begin(), e.end());
    if (!events.empty() && events.back().type == TrackerEventType::EndOfStream)
    {
      break;
    }
  }
  if (eventsOut)
  {
    *eventsOut = events;
  }
  return poses;
}

TEST(Replay, CommittedFixtureMatchesItsGenerator)
{
  ScratchDir dir;
  const std::string fresh = dir.File("two-hands.fastrak");
  GenerateFixture(fresh);
  if (std::getenv("BENDER_REGENERATE_TRACKING_FIXTURES"))
  {
    GenerateFixture(FixturePath);
  }
  // EXPECT_TRUE, not EXPECT_EQ: a failure must not print kilobytes of binary.
  EXPECT_TRUE(ReadText(fresh) == ReadText(FixturePath))
    << FixturePath << " is stale: regenerate with BENDER_REGENERATE_TRACKING_FIXTURES=1";
  EXPECT_TRUE(ReadText(fresh + ".timestamps") == ReadText(FixturePath + ".timestamps"));
}

TEST(Replay, FixtureReproducesTheSimulatedPosesAndButtons)
{
  TrackerDeviceOptions options;
  std::unique_ptr<TrackerDevice> device =
    CreateTrackerDevice(TrackerDeviceSpec::Parse("replay:" + FixturePath), options);
  device->EnablePoseQueue(64, true); // smaller than the recording: the reader must wait
  device->Open();
  device->Start();
  std::vector<TrackerEvent> events;
  const std::vector<TrackerPose> poses = DrainUntilEnd(*device, &events);
  ASSERT_EQ(poses.size(), std::size_t(2 * FixtureSamples));
  const SimulationScript script = SimulationScript::TwoHandBend();
  double previous = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const double sampleTime = double(i / 2) / FixtureRate;
    ExpectPoseEq(ExpectedBinary(script.PoseAt(int(i % 2) + 1, sampleTime)), poses[i]);
    EXPECT_GE(poses[i].time, sampleTime - 1e-9);
    EXPECT_LE(poses[i].time, sampleTime + 0.1 + 1e-9);
    EXPECT_GE(poses[i].time, previous);
    previous = poses[i].time;
  }
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].type, TrackerEventType::Grab);
  EXPECT_EQ(events[0].station, 1);
  EXPECT_NEAR(events[0].time, 1.0, 0.1 + 1e-9);
  EXPECT_EQ(events[1].type, TrackerEventType::Release);
  EXPECT_NEAR(events[1].time, 5.0, 0.1 + 1e-9);
  EXPECT_EQ(events[2].type, TrackerEventType::EndOfStream);
  const TrackerStatistics stats = device->Statistics();
  EXPECT_EQ(stats.parser.records, poses.size());
  EXPECT_EQ(stats.parser.dropped + stats.parser.malformed + stats.parser.garbageBytes, 0u);
  ASSERT_EQ(stats.stations.size(), 2u);
  EXPECT_NEAR(stats.stations[0].RateHz(), FixtureRate, 0.5);
  device->Close();
}

TEST(Replay, StationFilterPassesOnlyTheAskedStations)
{
  TrackerDeviceOptions options;
  options.stations = { 2 };
  std::unique_ptr<TrackerDevice> device =
    CreateTrackerDevice(TrackerDeviceSpec::Parse("replay:" + FixturePath), options);
  device->EnablePoseQueue(1024, true);
  device->Open();
  device->Start();
  const std::vector<TrackerPose> poses = DrainUntilEnd(*device);
  ASSERT_EQ(poses.size(), std::size_t(FixtureSamples));
  for (const TrackerPose& p : poses)
  {
    EXPECT_EQ(p.station, 2);
  }
  EXPECT_EQ(device->Statistics().filtered, std::uint64_t(FixtureSamples));
}

TEST(Replay, RecordThenReplayGivesTheSamePosesAndTimes)
{
  ScratchDir dir;
  const std::string file = dir.File("session.fastrak");
  auto shared = std::make_shared<ScriptedTransport::Shared>();
  const std::vector<TrackerPose> poses = SamplePoses();
  const Bytes stream = Encode(poses, FastrakFormat::Binary);
  FastrakOptions live;
  live.configure = false;
  std::vector<TrackerPose> recorded;
  {
    FastrakDevice device(
      "scripted",
      [shared, file] {
        return std::make_unique<RecordingTransport>(
          std::make_unique<ScriptedTransport>(shared), file);
      },
      live);
    device.EnablePoseQueue(64, false);
    device.Open();
    device.Start();
    // Garbage and records split oddly, with pauses between the chunks.
    ScriptedTransport::Push(*shared, { 0x13, '0' });
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
    ScriptedTransport::Push(*shared, Bytes(stream.begin(), stream.begin() + 40));
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
    ScriptedTransport::Push(*shared, Bytes(stream.begin() + 40, stream.end()));
    for (int i = 0; i < 100 && recorded.size() < poses.size(); ++i)
    {
      device.WaitForActivity(std::chrono::milliseconds(10));
      device.TakeEvents(); // button events are not what this test is about
      for (const TrackerPose& p : device.TakePoses())
      {
        recorded.push_back(p);
      }
    }
    device.Close();
  }
  ASSERT_EQ(recorded.size(), poses.size());
  Bytes expectedFile = { 0x13, '0' };
  expectedFile.insert(expectedFile.end(), stream.begin(), stream.end());
  const std::string raw = ReadText(file);
  EXPECT_EQ(Bytes(raw.begin(), raw.end()), expectedFile)
    << "the recording is not the bytes as received";

  FastrakOptions replayOptions;
  replayOptions.configure = false;
  FastrakDevice replay(
    "replay", [file] { return std::make_unique<ReplayTransport>(file); }, replayOptions);
  replay.EnablePoseQueue(64, true);
  replay.Open();
  replay.Start();
  const std::vector<TrackerPose> replayed = DrainUntilEnd(replay);
  ASSERT_EQ(replayed.size(), recorded.size());
  for (std::size_t i = 0; i < replayed.size(); ++i)
  {
    ExpectPoseEq(recorded[i], replayed[i]);
    EXPECT_NEAR(replayed[i].time, recorded[i].time, 0.05);
  }
  EXPECT_GE(replay.Statistics().parser.garbageBytes, 1u);
}

TEST(Replay, WithoutSidecarUsesFixedChunksAndByteRateTime)
{
  ScratchDir dir;
  const std::string file = dir.File("raw.fastrak");
  const Bytes stream = Encode(SamplePoses(), FastrakFormat::Binary);
  WriteText(file, std::string(stream.begin(), stream.end()));
  ReplayTransport::Options options;
  options.chunkSize = 10;
  options.bytesPerSecond = 100.0;
  ReplayTransport replay(file, options);
  EXPECT_FALSE(replay.HasTimestamps());
  std::uint8_t buffer[64];
  std::size_t total = 0;
  while (!replay.AtEnd())
  {
    const std::size_t n = replay.Read(buffer, sizeof buffer, std::chrono::milliseconds(10));
    ASSERT_LE(n, 10u);
    total += n;
    EXPECT_DOUBLE_EQ(*replay.RecordedTime(), double(total) / 100.0);
  }
  EXPECT_EQ(total, stream.size());
  EXPECT_EQ(replay.Read(buffer, sizeof buffer, std::chrono::milliseconds(10)), 0u);
}

TEST(Replay, RealtimeFollowsTheRecordedTimes)
{
  ScratchDir dir;
  const std::string file = dir.File("paced.fastrak");
  const Bytes stream = Encode(SamplePoses(), FastrakFormat::Binary);
  {
    StreamRecorder recorder(file);
    for (std::size_t i = 0; i < 4; ++i)
    {
      recorder.Append(stream.data() + 34 * i, 34, 10.0 + 0.05 * double(i));
    }
  }
  ReplayTransport::Options options;
  options.realtime = true;
  ReplayTransport replay(file, options);
  std::uint8_t buffer[64];
  const auto start = std::chrono::steady_clock::now();
  std::size_t total = 0;
  while (!replay.AtEnd())
  {
    total += replay.Read(buffer, sizeof buffer, std::chrono::milliseconds(20));
  }
  const double elapsed =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(total, stream.size());
  EXPECT_GE(elapsed, 0.14);
  EXPECT_LT(elapsed, 2.0);
}

TEST(Replay, BadRecordingsAreReportedWithTheirName)
{
  ScratchDir dir;
  const auto expectError = [](const std::string& file, const std::string& needle)
  {
    try
    {
      ReplayTransport replay(file);
      ADD_FAILURE() << "accepted " << file;
    }
    catch (const RecordingError& e)
    {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expectError(dir.File("missing.fastrak"), "missing.fastrak");
  WriteText(dir.File("empty.fastrak"), "");
  expectError(dir.File("empty.fastrak"), "empty");
  const std::string file = dir.File("data.fastrak");
  WriteText(file, std::string(100, 'x'));
  WriteText(file + ".timestamps", "# header\n0 50 0.1\n60 40 0.2\n");
  expectError(file, "line 3");
  WriteText(file + ".timestamps", "0 50 0.2\n50 50 0.1\n");
  expectError(file, "backwards");
  WriteText(file + ".timestamps", "0 fifty 0.1\n");
  expectError(file, "OFFSET SIZE SECONDS");
  expectError(dir.File(""), "not a regular file");
}

// What a replay of `file` gives: its bytes, and the recorded time of each byte.
struct Replayed
{
  std::string bytes;
  std::vector<double> times;
  std::size_t unlisted = 0;
};

Replayed ReplayWhole(const std::string& file)
{
  ReplayTransport replay(file);
  EXPECT_TRUE(replay.HasTimestamps()) << file;
  Replayed out;
  out.unlisted = replay.UnlistedBytes();
  std::uint8_t buffer[4096];
  while (!replay.AtEnd())
  {
    const std::size_t n = replay.Read(buffer, sizeof buffer, std::chrono::milliseconds(10));
    out.bytes.append(reinterpret_cast<const char*>(buffer), n);
    out.times.insert(out.times.end(), n, *replay.RecordedTime());
  }
  return out;
}

std::size_t DecodedRecords(const std::string& bytes)
{
  FastrakParser parser;
  return parser.Feed(std::vector<std::uint8_t>(bytes.begin(), bytes.end())).size();
}

// Issue 25: StreamRecorder writes a chunk's bytes, then its line: a crash leaves the file cut
// at any byte of the chunk being written, its line unwritten or cut at any byte of its own.
// Every such recording replays: the listed chunks at their times, the rest at the last time.
TEST(Replay, ARecordingCutAtAnyByteOfItsLastChunkReplaysWhatItHolds)
{
  ScratchDir dir;
  const std::string whole = dir.File("whole.fastrak");
  GenerateFixture(whole);
  const std::string data = ReadText(whole);
  std::vector<std::string> lines;
  {
    std::istringstream sidecar(ReadText(whole + ".timestamps"));
    for (std::string line; std::getline(sidecar, line);)
    {
      lines.push_back(line + "\n");
    }
  }
  ASSERT_GE(lines.size(), 3u); // the header and at least two chunks
  const std::string last = lines.back();
  std::size_t lastOffset = 0, lastSize = 0;
  std::istringstream(last) >> lastOffset >> lastSize;
  ASSERT_EQ(lastOffset + lastSize, data.size());
  std::string listedBefore;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i)
  {
    listedBefore += lines[i];
  }
  const Replayed reference = ReplayWhole(whole);
  ASSERT_EQ(reference.bytes, data);
  EXPECT_EQ(reference.unlisted, 0u);
  const double timeBefore = reference.times[lastOffset - 1];

  const std::string cut = dir.File("cut.fastrak");
  const auto expectPrefix = [&](std::size_t size, std::size_t unlisted, const std::string& what)
  {
    const Replayed replayed = ReplayWhole(cut);
    EXPECT_TRUE(replayed.bytes == data.substr(0, size)) << what;
    EXPECT_EQ(replayed.unlisted, unlisted) << what;
    ASSERT_EQ(replayed.times.size(), size) << what;
    for (std::size_t i = 0; i < size; ++i)
    {
      // Listed bytes at their recorded time; unlisted ones at the last listed time.
      const double expected = i < size - unlisted ? reference.times[i] : timeBefore;
      ASSERT_EQ(replayed.times[i], expected) << what << ", byte " << i;
    }
    EXPECT_EQ(DecodedRecords(replayed.bytes), size / FastrakParser::BinaryRecordSize) << what;
  };
  // Killed while the last chunk's bytes were written, or before its line.
  for (std::size_t size = lastOffset; size <= data.size(); ++size)
  {
    WriteText(cut, data.substr(0, size));
    WriteText(cut + ".timestamps", listedBefore);
    expectPrefix(size, size - lastOffset, "file cut at byte " + std::to_string(size));
  }
  // Killed while the last line was written: a line without its newline is not read.
  for (std::size_t length = 0; length < last.size(); ++length)
  {
    WriteText(cut, data);
    WriteText(cut + ".timestamps", listedBefore + last.substr(0, length));
    expectPrefix(data.size(), lastSize, "last line cut at byte " + std::to_string(length));
  }
  WriteText(cut + ".timestamps", listedBefore + last);
  expectPrefix(data.size(), 0, "whole");
  // A line listing bytes the file does not hold is not what the recorder writes: refused.
  WriteText(cut, data.substr(0, data.size() - 1));
  EXPECT_THROW(ReplayTransport{ cut }, RecordingError);
}

// Issue 13: a forged SIZE made offset + size wrap around 64 bits and pass the range check
// (heap over-read, SIGSEGV); 1e300 seconds printed 300 digits; raw bytes were echoed.
TEST(Replay, ForgedSidecarsAreRefusedInOneLine)
{
  ScratchDir dir;
  const auto expectError = [](const std::string& file, const std::string& needle)
  {
    try
    {
      ReplayTransport replay(file);
      ADD_FAILURE() << "accepted " << file;
    }
    catch (const RecordingError& e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find(needle), std::string::npos) << message;
      EXPECT_LT(message.size(), 300u) << message;
      EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
    }
  };
  const std::string file = dir.File("data.fastrak");
  WriteText(file, std::string(100, 'x'));
  WriteText(file + ".timestamps", "0 50 0.1\n50 18446744073709551570 0.2\n");
  expectError(file, "does not follow on");
  WriteText(file + ".timestamps", "0 50 0.1\n50 50 1e300\n");
  expectError(file, "time 1e+300 s is out of range");
  WriteText(file + ".timestamps", "0 50 \x1b[31mred\n");
  expectError(file, "\\x1b[31mred");
  WriteText(file + ".timestamps", "0 100 0.1" + std::string(1000, ' ') + "\n");
  expectError(file, "longer than 256 bytes");
}

// Issue 13: "--record F.timestamps" while replaying F truncated the replay's own sidecar.
TEST(Replay, RecordingRefusesToOverwriteTheReplayedFiles)
{
  ScratchDir dir;
  const std::string file = dir.File("in.fastrak");
  GenerateFixture(file);
  const std::string sidecar = ReadText(file + ".timestamps");
  const std::string data = ReadText(file);
  for (const std::string& target : { file + ".timestamps", file, dir.File("./in.fastrak") })
  {
    EXPECT_THROW(
      RecordingTransport(std::make_unique<ReplayTransport>(file), target), RecordingError)
      << target;
  }
  EXPECT_EQ(ReadText(file + ".timestamps"), sidecar);
  EXPECT_EQ(ReadText(file), data);
  // Another name records as before.
  RecordingTransport ok(std::make_unique<ReplayTransport>(file), dir.File("copy.fastrak"));
  EXPECT_TRUE(std::filesystem::exists(dir.File("copy.fastrak.timestamps")));
}

TEST(Replay, RecorderRefusesAnUnwritablePath)
{
  EXPECT_THROW(StreamRecorder("/nonexistent-dir/x.fastrak"), RecordingError);
}

} // namespace
} // namespace bender::test
