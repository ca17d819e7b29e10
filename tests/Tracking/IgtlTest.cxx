// OpenIGTLink: the stream decoder on byte buffers, IgtlDevice against a small loopback server
// (messages packed by the OpenIGTLink library itself and version-2 messages with metadata),
// `bender-cli tracker --device igtl:...` and `bender-cli igtl-send` received by a test peer
// that unpacks the POLYDATA with the library. Loopback 127.0.0.1 on ephemeral ports only.

#include "CliCommands.h"
#include "IgtlDevice.h"
#include "IgtlLoopback.h"
#include "IgtlProtocol.h"
#include "IgtlSender.h"
#include "TrackerCommand.h"
#include "TrackerDeviceRegistry.h"
#include "TrackingErrors.h"
#include "TwoHandRibbonInput.h"

#include <igtlMessageHeader.h>
#include <igtlPolyDataMessage.h>
#include <igtlPositionMessage.h>
#include <igtlStatusMessage.h>
#include <igtlStringMessage.h>
#include <igtlTransformMessage.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <arpa/inet.h>
#include <csignal>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

namespace
{
using bender::IgtlMessage;
using bender::IgtlStreamDecoder;
using bender::Quaternion;
using bender::Vec3;
using Bytes = std::vector<std::uint8_t>;

Bytes Packed(igtl::MessageBase* message)
{
  message->Pack();
  const auto* p = static_cast<const std::uint8_t*>(message->GetPackPointer());
  return Bytes(p, p + message->GetPackSize());
}

// A TRANSFORM packed by the library: rotation about z by `angle`, translation t (RAS).
Bytes LibraryTransform(const std::string& name, const Vec3& t, double angle)
{
  igtl::Matrix4x4 m;
  igtl::IdentityMatrix(m);
  m[0][0] = float(std::cos(angle));
  m[0][1] = float(-std::sin(angle));
  m[1][0] = float(std::sin(angle));
  m[1][1] = float(std::cos(angle));
  m[0][3] = float(t.x);
  m[1][3] = float(t.y);
  m[2][3] = float(t.z);
  igtl::TransformMessage::Pointer message = igtl::TransformMessage::New();
  message->SetDeviceName(name.c_str());
  message->SetMatrix(m);
  return Packed(message);
}

Bytes LibraryString(const std::string& name, const std::string& text)
{
  igtl::StringMessage::Pointer message = igtl::StringMessage::New();
  message->SetDeviceName(name.c_str());
  message->SetString(text.c_str());
  return Packed(message);
}

void Append(Bytes& out, const Bytes& more)
{
  out.insert(out.end(), more.begin(), more.end());
}

std::vector<IgtlMessage> DecodeAll(IgtlStreamDecoder& decoder,
  const Bytes& bytes,
  std::size_t piece)
{
  std::vector<IgtlMessage> out;
  for (std::size_t i = 0; i < bytes.size(); i += piece)
  {
    decoder.Feed(bytes.data() + i, std::min(piece, bytes.size() - i));
    while (auto m = decoder.Next())
    {
      out.push_back(*m);
    }
  }
  return out;
}

using bender::test::Collect;
using bender::test::Collected;
using bender::test::DeviceOptions;
using bender::test::HasEvent;
using bender::test::LoopbackServer;
using bender::test::ReadUntilClosed;
using bender::test::SendBytes;
using bender::test::WaitForPeerClose;

} // namespace

// ---------------------------------------------------------------------------------------
TEST(IgtlProtocol, DecodesALibraryTransformAndConvertsRasToLps)
{
  const double angle = 0.5;
  const Bytes bytes = LibraryTransform("StylusToTracker", { 10, 20, 30 }, angle);
  IgtlStreamDecoder decoder;
  const auto messages = DecodeAll(decoder, bytes, bytes.size());
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].type, "TRANSFORM");
  EXPECT_EQ(messages[0].deviceName, "StylusToTracker");
  EXPECT_EQ(messages[0].headerVersion, 1);
  std::vector<bender::IgtlToolPose> poses;
  std::string problem;
  ASSERT_TRUE(bender::DecodeIgtlPoses(messages[0], poses, problem)) << problem;
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR(poses[0].position.x, 10, 1e-5);
  // The tool's x axis in RAS is (cos a, sin a, 0); in LPS it is (-cos a, -sin a, 0).
  const Vec3 lps = bender::RasToLps(poses[0].position);
  EXPECT_NEAR(lps.x, -10, 1e-5);
  EXPECT_NEAR(lps.y, -20, 1e-5);
  EXPECT_NEAR(lps.z, 30, 1e-5);
  const Vec3 axis = bender::RotateByQuaternion(bender::RasToLps(poses[0].orientation), { 1, 0, 0 });
  EXPECT_NEAR(axis.x, -std::cos(angle), 1e-6);
  EXPECT_NEAR(axis.y, -std::sin(angle), 1e-6);
  EXPECT_NEAR(axis.z, 0.0, 1e-6);
}

TEST(IgtlProtocol, VersionTwoHeaderWithMetadataGivesContentAndMetadata)
{
  const Bytes v1 = LibraryTransform("StylusToTracker", { 1, 2, 3 }, 0.0);
  const Bytes content(v1.begin() + 58, v1.end());
  const Bytes v2 = bender::EncodeIgtlMessage("TRANSFORM",
    "StylusToTracker",
    content,
    2,
    { { "TransformStatus", "OK" }, { "Units", "mm" } },
    0,
    42);
  EXPECT_EQ(v2[1], 2); // header version 2
  IgtlStreamDecoder decoder;
  const auto messages = DecodeAll(decoder, v2, 7);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].headerVersion, 2);
  EXPECT_EQ(messages[0].messageId, 42u);
  EXPECT_EQ(messages[0].content, content);
  ASSERT_EQ(messages[0].metadata.size(), 2u);
  EXPECT_EQ(messages[0].metadata[0].first, "TransformStatus");
  EXPECT_EQ(messages[0].metadata[0].second, "OK");
  EXPECT_EQ(messages[0].metadata[1].second, "mm");
  // The same message without metadata, version 1 and with the library's time stamp, is
  // byte-identical to the library's (header layout and CRC agree).
  IgtlStreamDecoder libraryDecoder;
  const auto library = DecodeAll(libraryDecoder, v1, v1.size());
  ASSERT_EQ(library.size(), 1u);
  EXPECT_EQ(
    bender::EncodeIgtlMessage("TRANSFORM", "StylusToTracker", content, 1, {}, library[0].timestamp),
    v1);
}

TEST(IgtlProtocol, CrcErrorsAndGarbageAreSkippedAndCounted)
{
  Bytes stream = { 0xde, 0xad, 0xbe, 0xef, 0x00, 0x01, 'x' };
  Bytes corrupt = LibraryTransform("StylusToTracker", { 1, 1, 1 }, 0.1);
  corrupt[70] ^= 0x40; // a body byte: the CRC no longer matches
  Append(stream, corrupt);
  Append(stream, LibraryTransform("StylusToTracker", { 2, 2, 2 }, 0.1));
  Append(stream, Bytes(100, 0xff));
  Append(stream, LibraryTransform("Stylus2ToTracker", { 3, 3, 3 }, 0.1));
  for (std::size_t piece : { std::size_t(1), std::size_t(13), stream.size() })
  {
    IgtlStreamDecoder decoder;
    const auto messages = DecodeAll(decoder, stream, piece);
    ASSERT_EQ(messages.size(), 2u) << "piece " << piece;
    EXPECT_EQ(messages[0].deviceName, "StylusToTracker");
    EXPECT_EQ(messages[1].deviceName, "Stylus2ToTracker");
    EXPECT_EQ(decoder.Statistics().crcErrors, 1u);
    // 7 + 100 bytes of garbage and the 106 bytes of the damaged message.
    EXPECT_EQ(decoder.Statistics().garbageBytes, 213u);
    EXPECT_EQ(decoder.Pending(), 0u);
  }
}

TEST(IgtlProtocol, AFalseHeaderInGarbageDoesNotSwallowTheNextMessage)
{
  // Garbage that happens to look like a header announcing 100 body bytes, then a real
  // message: the CRC of the false one fails and the real one is still decoded.
  Bytes stream = bender::EncodeIgtlMessage("BLOB", "x", Bytes(100, 0));
  stream.resize(58); // keep only the header (its CRC is that of 100 zeros)
  stream[57] ^= 0xff;
  Append(stream, LibraryTransform("StylusToTracker", { 1, 2, 3 }, 0.0));
  Append(stream, Bytes(60, 0)); // enough for the false body to be complete
  IgtlStreamDecoder decoder;
  const auto messages = DecodeAll(decoder, stream, 5);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].deviceName, "StylusToTracker");
  EXPECT_EQ(decoder.Statistics().crcErrors, 1u);
  // A version-1 TRANSFORM header with a body size other than 48 is not a header at all.
  Bytes wrong = LibraryTransform("StylusToTracker", { 1, 2, 3 }, 0.0);
  wrong[49] = 47;
  IgtlStreamDecoder strict;
  EXPECT_TRUE(DecodeAll(strict, wrong, wrong.size()).empty());
  EXPECT_EQ(strict.Statistics().crcErrors, 0u);
}

TEST(IgtlProtocol, RefusesScaledMatricesAndWrongSizes)
{
  igtl::Matrix4x4 m;
  igtl::IdentityMatrix(m);
  m[0][0] = 2.0f;
  igtl::TransformMessage::Pointer message = igtl::TransformMessage::New();
  message->SetDeviceName("StylusToTracker");
  message->SetMatrix(m);
  IgtlStreamDecoder decoder;
  const auto messages = DecodeAll(decoder, Packed(message), 1000);
  ASSERT_EQ(messages.size(), 1u);
  std::vector<bender::IgtlToolPose> poses;
  std::string problem;
  EXPECT_FALSE(bender::DecodeIgtlPoses(messages[0], poses, problem));
  EXPECT_NE(problem.find("not a rotation"), std::string::npos) << problem;
  IgtlMessage shortOne = messages[0];
  shortOne.content.resize(20);
  EXPECT_FALSE(bender::DecodeIgtlPoses(shortOne, poses, problem));
  EXPECT_NE(problem.find("20 content bytes"), std::string::npos) << problem;
  EXPECT_TRUE(poses.empty());
}

TEST(IgtlProtocol, DecodesLibraryPositionMessages)
{
  igtl::PositionMessage::Pointer message = igtl::PositionMessage::New();
  message->SetDeviceName("Stylus2ToTracker");
  message->SetPackType(igtl::PositionMessage::ALL);
  message->SetPosition(4.0f, 5.0f, 6.0f);
  const float s = float(std::sin(0.25)), c = float(std::cos(0.25));
  message->SetQuaternion(0.0f, 0.0f, s, c); // 0.5 rad about z
  IgtlStreamDecoder decoder;
  const auto messages = DecodeAll(decoder, Packed(message), 1000);
  ASSERT_EQ(messages.size(), 1u);
  std::vector<bender::IgtlToolPose> poses;
  std::string problem;
  ASSERT_TRUE(bender::DecodeIgtlPoses(messages[0], poses, problem)) << problem;
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR(poses[0].position.z, 6.0, 1e-6);
  EXPECT_NEAR(poses[0].orientation.w, c, 1e-6);
  EXPECT_NEAR(poses[0].orientation.z, s, 1e-6);
}

TEST(IgtlProtocol, DeviceSpecParsesHostAndPort)
{
  const auto spec = bender::TrackerDeviceSpec::Parse("igtl:127.0.0.1:18944");
  EXPECT_EQ(spec.kind, "igtl");
  EXPECT_EQ(spec.host, "127.0.0.1");
  EXPECT_EQ(spec.port, 18944);
  EXPECT_EQ(spec.ToString(), "igtl:127.0.0.1:18944");
  EXPECT_THROW(
    bender::TrackerDeviceSpec::Parse("igtl:localhost"), bender::TrackingConfigurationError);
  EXPECT_THROW(
    bender::TrackerDeviceSpec::Parse("igtl:localhost:0"), bender::TrackingConfigurationError);
  EXPECT_THROW(bender::TrackerDeviceSpec::Parse("igtl::99"), bender::TrackingConfigurationError);
  EXPECT_THROW(bender::TrackerDeviceSpec::Parse("igtl:h:7x"), bender::TrackingConfigurationError);
}

// ---------------------------------------------------------------------------------------
TEST(IgtlDevice, StreamsHandsInLpsAndButtonsFromStrings)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      Bytes stream;
      for (int k = 0; k < 5; ++k)
      {
        Append(stream, LibraryTransform("StylusToTracker", { 10.0 + k, 20, 30 }, 0.2));
        Append(stream, LibraryTransform("Stylus2ToTracker", { -5, 7, 1.0 * k }, -0.3));
        Append(stream, LibraryTransform("ReferenceToTracker", { 0, 0, 0 }, 0.0));
        if (k == 1)
        {
          Append(stream, LibraryString("StylusToTracker", " Down\n"));
        }
        if (k == 3)
        {
          Append(stream, LibraryString("StylusToTracker", "up"));
        }
      }
      SendBytes(fd, stream); // then close: the device reads everything before the end
    } });
  bender::IgtlDevice device(DeviceOptions(server.Port()));
  device.EnablePoseQueue(1000, false);
  device.EnableNamedQueue(1000);
  device.Open();
  device.Start();
  const Collected c = Collect(
    device, [](const Collected& c) { return HasEvent(c, bender::TrackerEventType::Disconnected); });
  const auto named = device.TakeNamedPoses();
  device.Close();
  server.Join();

  // 10 hand poses + 2 republished on the button changes.
  ASSERT_EQ(c.poses.size(), 12u);
  int hand1 = 0;
  for (const auto& p : c.poses)
  {
    ASSERT_TRUE(p.station == 1 || p.station == 2);
    if (p.station == 1)
    {
      // The pose is republished when the button changes (after k = 1 and k = 3).
      const double expected[7] = { 10, 11, 11, 12, 13, 13, 14 };
      ASSERT_LT(hand1, 7);
      EXPECT_NEAR(p.position.x, -expected[hand1], 1e-4);
      EXPECT_EQ(p.button, hand1 >= 2 && hand1 <= 4) << hand1;
      EXPECT_NEAR(p.position.y, -20, 1e-4);
      EXPECT_NEAR(p.position.z, 30, 1e-4);
      ++hand1;
    }
    else
    {
      EXPECT_NEAR(p.position.x, 5, 1e-4);
      EXPECT_NEAR(p.position.y, -7, 1e-4);
    }
  }
  EXPECT_EQ(hand1, 7);
  ASSERT_EQ(c.events.size(), 3u);
  EXPECT_EQ(c.events[0].type, bender::TrackerEventType::Grab);
  EXPECT_EQ(c.events[0].station, 1);
  EXPECT_EQ(c.events[1].type, bender::TrackerEventType::Release);
  EXPECT_EQ(c.events[2].type, bender::TrackerEventType::Disconnected);
  EXPECT_EQ(c.events[2].message, "the server closed the connection");
  // The named queue has every pose, the reference too (station 0).
  ASSERT_EQ(named.size(), 15u);
  EXPECT_EQ(named[2].name, "ReferenceToTracker");
  EXPECT_EQ(named[2].pose.station, 0);
  const bender::IgtlStatistics s = device.IgtlStats();
  EXPECT_EQ(s.poses, 15u);
  EXPECT_EQ(s.buttonMessages, 2u);
  EXPECT_EQ(s.names.at("ReferenceToTracker"), 5u);
  EXPECT_EQ(device.Statistics().filtered, 5u);
}

TEST(IgtlDevice, VersionTwoMetadataUnknownTypesCrcErrorsAndGarbage)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      const Bytes v1 = LibraryTransform("StylusToTracker", { 1, 2, 3 }, 0.0);
      const Bytes content(v1.begin() + 58, v1.end());
      Bytes stream = bender::EncodeIgtlMessage(
        "TRANSFORM", "StylusToTracker", content, 2, { { "TransformStatus", "OK" } });
      Append(
        stream, bender::EncodeIgtlMessage("IMAGE", "Image", Bytes(500, 7), 2, { { "a", "b" } }));
      Append(stream, Bytes{ 1, 2, 3, 4, 5, 6, 7, 8, 9 });
      Bytes corrupt = v1;
      corrupt[60] ^= 1;
      Append(stream, corrupt);
      igtl::StatusMessage::Pointer status = igtl::StatusMessage::New();
      status->SetDeviceName("Tracker");
      status->SetCode(igtl::StatusMessage::STATUS_NOT_READY);
      status->SetStatusString("tool out of view");
      Append(stream, Packed(status));
      Append(stream, bender::EncodeIgtlMessage("TRANSFORM", "Stylus2ToTracker", content, 2));
      SendBytes(fd, stream);
      WaitForPeerClose(fd);
    } });
  bender::IgtlDevice device(DeviceOptions(server.Port()));
  device.EnablePoseQueue(100, false);
  device.Open();
  device.Start();
  const Collected c = Collect(device, [](const Collected& c) { return c.poses.size() >= 2; });
  // Let the reader drain the bytes it has (the statistics are read after Stop).
  device.Stop();
  const bender::IgtlStatistics s = device.IgtlStats();
  device.Close();
  server.Join();
  ASSERT_EQ(c.poses.size(), 2u);
  EXPECT_NEAR(c.poses[0].position.x, -1, 1e-5);
  EXPECT_EQ(c.poses[1].station, 2);
  EXPECT_EQ(s.decoder.crcErrors, 1u);
  EXPECT_EQ(s.decoder.garbageBytes, 9u + 106u); // garbage + the damaged TRANSFORM
  EXPECT_EQ(s.unknownTypes, 1u);
  EXPECT_EQ(s.skippedTypes.at("IMAGE"), 1u);
  EXPECT_EQ(s.statusMessages, 1u);
  EXPECT_NE(s.lastStatus.find("tool out of view"), std::string::npos) << s.lastStatus;
  EXPECT_TRUE(c.events.empty());
}

TEST(IgtlDevice, ClosedMidMessageIsADisconnectAndReconnectWorks)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      Bytes stream = LibraryTransform("StylusToTracker", { 1, 1, 1 }, 0.0);
      const Bytes next = LibraryTransform("StylusToTracker", { 2, 2, 2 }, 0.0);
      stream.insert(stream.end(), next.begin(), next.begin() + 80); // cut in the body
      SendBytes(fd, stream);
    },
    [](int fd)
    {
      SendBytes(fd, LibraryTransform("StylusToTracker", { 5, 5, 5 }, 0.0));
      WaitForPeerClose(fd);
    } });
  bender::IgtlDevice device(DeviceOptions(server.Port()));
  device.EnablePoseQueue(100, false);
  device.Open();
  device.Start();
  const Collected first = Collect(
    device, [](const Collected& c) { return HasEvent(c, bender::TrackerEventType::Disconnected); });
  ASSERT_EQ(first.poses.size(), 1u);
  ASSERT_EQ(first.events.size(), 1u);
  EXPECT_EQ(first.events[0].type, bender::TrackerEventType::Disconnected);
  EXPECT_NE(first.events[0].message.find("in the middle of a message (TRANSFORM message "
                                         "'StylusToTracker' with 22 of 48 body bytes)"),
    std::string::npos)
    << first.events[0].message;
  EXPECT_FALSE(device.IsStreaming());
  EXPECT_EQ(device.Statistics().parser.truncated, 1u);
  // Reconnect when asked.
  device.Close();
  device.Open();
  device.Start();
  const Collected second = Collect(device, [](const Collected& c) { return !c.poses.empty(); });
  device.Close();
  server.Join();
  ASSERT_EQ(second.poses.size(), 1u);
  EXPECT_NEAR(second.poses[0].position.x, -5, 1e-5);
}

TEST(IgtlDevice, SlowPeerLosesNothing)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      Bytes stream;
      for (int k = 0; k < 3; ++k)
      {
        Append(stream, LibraryTransform("StylusToTracker", { double(k), 0, 0 }, 0.0));
      }
      // One byte at a time with a pause every 16 bytes: messages arrive in many reads.
      for (std::size_t i = 0; i < stream.size(); ++i)
      {
        SendBytes(fd, Bytes{ stream[i] });
        if (i % 16 == 0)
        {
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
      }
      WaitForPeerClose(fd);
    } });
  bender::IgtlDevice device(DeviceOptions(server.Port()));
  device.EnablePoseQueue(100, false);
  device.Open();
  device.Start();
  const Collected c = Collect(device, [](const Collected& c) { return c.poses.size() >= 3; });
  device.Close();
  server.Join();
  ASSERT_EQ(c.poses.size(), 3u);
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(c.poses[std::size_t(k)].position.x, -k, 1e-6);
  }
  EXPECT_EQ(device.IgtlStats().decoder.garbageBytes, 0u);
}

TEST(IgtlDevice, RefusedConnectionIsAClearError)
{
  int port = 0;
  {
    LoopbackServer closed; // bound and listening, then closed: nobody listens on the port
    port = closed.Port();
  }
  bender::IgtlDevice device(DeviceOptions(port));
  try
  {
    device.Open();
    FAIL() << "connected to a closed port";
  }
  catch (const bender::DeviceNotFoundError& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("igtl 127.0.0.1:" + std::to_string(port)), std::string::npos)
      << e.what();
  }
  EXPECT_THROW(
    (bender::IgtlDevice({ "127.0.0.1", 1, { "A", "A" } })), bender::TrackingConfigurationError);
}

TEST(IgtlCli, TrackerPrintsEveryPoseWithItsDeviceName)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      Bytes stream;
      for (int k = 0; k < 2; ++k)
      {
        Append(stream, LibraryTransform("NeedleToTracker", { 1, 2, 3 }, 0.0));
        Append(stream, LibraryTransform("Tip", { 4, 5, 6 }, 0.0));
      }
      SendBytes(fd, stream);
      WaitForPeerClose(fd);
    } });
  std::ostringstream out, err;
  const int status = bender::RunTrackerCli({ "--device",
                                             "igtl:127.0.0.1:" + std::to_string(server.Port()),
                                             "--count",
                                             "4",
                                             "--tools",
                                             "Tip,Other" },
    out,
    err);
  server.Join();
  ASSERT_EQ(status, 0) << err.str();
  std::istringstream lines(out.str());
  std::string line;
  std::vector<nlohmann::json> poses;
  while (std::getline(lines, line))
  {
    poses.push_back(nlohmann::json::parse(line));
  }
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_EQ(poses[0]["device"], "NeedleToTracker");
  EXPECT_EQ(poses[0]["station"], 0);
  EXPECT_EQ(poses[0]["position"][0], -1.0);
  EXPECT_EQ(poses[0]["position"][1], -2.0);
  EXPECT_EQ(poses[0]["position"][2], 3.0);
  EXPECT_EQ(poses[1]["device"], "Tip");
  EXPECT_EQ(poses[1]["station"], 1);
  EXPECT_NE(err.str().find("device 'NeedleToTracker': 2 poses (not a hand"), std::string::npos)
    << err.str();
}

TEST(IgtlCli, IgtlSendDeliversThePolyDataInRas)
{
  // A unit cube from (1, 2, 3) to (2, 3, 4) in LPS, six quads.
  const auto dir =
    std::filesystem::temp_directory_path() / ("bender-igtl-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "cube.off").string();
  {
    std::ofstream off(path);
    off << "OFF\n8 6 0\n";
    for (int i = 0; i < 8; ++i)
    {
      off << 1 + (i & 1) << ' ' << 2 + ((i >> 1) & 1) << ' ' << 3 + ((i >> 2) & 1) << '\n';
    }
    off << "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
  }
  LoopbackServer server;
  Bytes received;
  server.Serve({ [&received](int fd) { received = ReadUntilClosed(fd); } });
  const int status = bender::RunBenderCli({ "igtl-send",
    path,
    "--to",
    "127.0.0.1:" + std::to_string(server.Port()),
    "--name",
    "Vessel" });
  server.Join();
  std::filesystem::remove_all(dir);
  ASSERT_EQ(status, 0);
  ASSERT_GT(received.size(), 58u);

  // Unpack with the library, CRC checked.
  igtl::MessageHeader::Pointer header = igtl::MessageHeader::New();
  header->InitPack();
  std::memcpy(header->GetPackPointer(), received.data(), std::size_t(header->GetPackSize()));
  header->Unpack();
  EXPECT_STREQ(header->GetDeviceType(), "POLYDATA");
  EXPECT_STREQ(header->GetDeviceName(), "Vessel");
  ASSERT_EQ(std::size_t(header->GetBodySizeToRead()) + 58, received.size());
  igtl::PolyDataMessage::Pointer poly = igtl::PolyDataMessage::New();
  poly->SetMessageHeader(header);
  poly->AllocatePack();
  std::memcpy(
    poly->GetPackBodyPointer(), received.data() + 58, std::size_t(poly->GetPackBodySize()));
  ASSERT_TRUE(poly->Unpack(1) & igtl::MessageHeader::UNPACK_BODY);
  ASSERT_EQ(poly->GetPoints()->GetNumberOfPoints(), 8);
  ASSERT_EQ(int(poly->GetPolygons()->GetNumberOfCells()), 6);
  std::array<double, 6> bounds{ 1e9, -1e9, 1e9, -1e9, 1e9, -1e9 };
  for (int i = 0; i < 8; ++i)
  {
    float p[3];
    poly->GetPoints()->GetPoint(unsigned(i), p);
    for (int k = 0; k < 3; ++k)
    {
      bounds[std::size_t(2 * k)] = std::min(bounds[std::size_t(2 * k)], double(p[k]));
      bounds[std::size_t(2 * k + 1)] = std::max(bounds[std::size_t(2 * k + 1)], double(p[k]));
    }
  }
  // RAS: x and y negated.
  EXPECT_EQ(bounds, (std::array<double, 6>{ -2, -1, -3, -2, 3, 4 }));
  EXPECT_EQ(poly->GetPolygons()->GetCellSize(0), 4u);
}

TEST(IgtlCli, IgtlSendReportsAnUnreachableServerAndBadArguments)
{
  int port = 0;
  {
    LoopbackServer closed;
    port = closed.Port();
  }
  EXPECT_EQ(bender::RunBenderCli({ "igtl-send", "/nonexistent/x.stl", "--to", "127.0.0.1:1" }), 1);
  EXPECT_EQ(bender::RunBenderCli({ "igtl-send", "x.stl" }), 2);
  EXPECT_EQ(bender::RunBenderCli({ "igtl-send", "x.stl", "--to", "nohost" }), 2);
  EXPECT_EQ(bender::RunBenderCli({ "igtl-send", "x.stl", "--to", "h:1", "--name", "" }), 2);
  bender::IgtlSender::Options o;
  o.port = port;
  bender::IgtlSender sender(o);
  EXPECT_THROW(sender.Connect(), bender::DeviceNotFoundError);
  EXPECT_THROW(bender::EncodeIgtlPolyData({ { { 0, 0, 0 } }, { { 0, 1, 2 } } }, "Bad"),
    bender::TrackingConfigurationError);
}

TEST(IgtlSender, SendSurfaceIfDueKeepsTheRateBounded)
{
  LoopbackServer server;
  Bytes received;
  server.Serve({ [&received](int fd) { received = ReadUntilClosed(fd); } });
  bender::IgtlSender::Options o;
  o.port = server.Port();
  o.maxSurfaceRateHz = 0.001; // one surface per 1000 s: the second call must be skipped
  bender::IgtlSender sender(o);
  const bender::IgtlSurface triangle{ { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 } } };
  EXPECT_TRUE(sender.SendSurfaceIfDue(triangle, "S"));
  EXPECT_FALSE(sender.SendSurfaceIfDue(triangle, "S"));
  sender.SendTransform("RibbonEnd1", { 1, 2, 3 }, Quaternion{});
  EXPECT_EQ(sender.MessagesSent(), 2u);
  sender.Close();
  server.Join();
  IgtlStreamDecoder decoder;
  const auto messages = DecodeAll(decoder, received, received.size());
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0].type, "POLYDATA");
  EXPECT_EQ(messages[1].type, "TRANSFORM");
  std::vector<bender::IgtlToolPose> poses;
  std::string problem;
  ASSERT_TRUE(bender::DecodeIgtlPoses(messages[1], poses, problem)) << problem;
  EXPECT_NEAR(poses[0].position.x, -1, 1e-6); // sent in RAS
  EXPECT_NEAR(poses[0].position.y, -2, 1e-6);
  EXPECT_NEAR(poses[0].position.z, 3, 1e-6);
}

// The same gesture path as the Fastrak: two hands streamed over OpenIGTLink (in RAS, as
// PLUS sends them), a STRING button press and release, TwoHandRibbonInput gives one warp
// whose ribbon ends are in LPS and keep their orientation (no flip).
TEST(IgtlDevice, StreamedHandsDriveAGrabBendRelease)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      const Quaternion facing{ 0, 0, 0, 1 }; // right hand: local +x towards the left hand
      Bytes stream;
      for (int k = 0; k <= 12; ++k)
      {
        const double lift = k <= 2 ? 0.0 : 3.0 * (k - 2);
        Append(stream, bender::EncodeIgtlTransformMessage("StylusToTracker", { -100, 0, 0 }, {}));
        Append(
          stream, bender::EncodeIgtlTransformMessage("Stylus2ToTracker", { 100, 0, lift }, facing));
        if (k == 1)
        {
          Append(stream, LibraryString("StylusToTracker", "down"));
        }
      }
      Append(stream, LibraryString("StylusToTracker", "up"));
      SendBytes(fd, stream);
    } });
  bender::IgtlDevice device(DeviceOptions(server.Port()));
  device.EnablePoseQueue(1000, false);
  device.Open();
  device.Start();
  const Collected c = Collect(
    device, [](const Collected& c) { return HasEvent(c, bender::TrackerEventType::Disconnected); });
  device.Close();
  server.Join();

  bender::TwoHandRibbonInput input;
  std::vector<bender::TwoHandRibbonInput::Gesture> gestures;
  bool button = false;
  for (const bender::TrackerPose& pose : c.poses)
  {
    input.UpdatePose(pose);
    if (pose.station == 1 && pose.button != button)
    {
      button = pose.button;
      const auto type = button ? bender::TrackerEventType::Grab : bender::TrackerEventType::Release;
      if (auto g = input.HandleEvent({ type, 1, pose.time, {} }))
      {
        gestures.push_back(*g);
      }
    }
  }
  ASSERT_EQ(gestures.size(), 2u);
  EXPECT_EQ(gestures[0].kind, bender::TwoHandRibbonInput::Gesture::Kind::Grabbed);
  ASSERT_EQ(gestures[1].kind, bender::TwoHandRibbonInput::Gesture::Kind::Released);
  const bender::RibbonSpec& a = gestures[1].initial;
  const bender::RibbonSpec& b = gestures[1].final;
  EXPECT_NEAR(bender::Distance(a.start.position, { -100, 0, 0 }), 0.0, 1e-4);
  EXPECT_NEAR(bender::Distance(a.end.position, { 100, 0, 0 }), 0.0, 1e-4);
  EXPECT_NEAR(bender::Distance(b.end.position, { 100, 0, 30 }), 0.0, 1e-4);
  for (const bender::RibbonEnd* end : { &a.start, &a.end, &b.start, &b.end })
  {
    EXPECT_NEAR(end->tangent.x, 1.0, 1e-6); // along the ribbon at both ends: no flip
    EXPECT_NEAR(end->normal.z, 1.0, 1e-6);  // up stays up
  }
}

TEST(IgtlCli, IgtlSendWithAPlanSendsTheRibbonEndFramesInRas)
{
  const auto dir =
    std::filesystem::temp_directory_path() / ("bender-igtl-plan-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "triangle.off").string();
  {
    std::ofstream off(path);
    off << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  }
  LoopbackServer server;
  Bytes received;
  server.Serve({ [&received](int fd) { received = ReadUntilClosed(fd); } });
  // The last warp's final ribbon: start (0,0,0) tangent +x, end (30,20,0) tangent +y, normal +z.
  const int status = bender::RunBenderCli({ "igtl-send",
    path,
    "--to",
    "127.0.0.1:" + std::to_string(server.Port()),
    "--name",
    "Vessel",
    "--plan",
    std::string(BENDER_TEST_DATA_DIR) + "/io/example.bender.json" });
  server.Join();
  std::filesystem::remove_all(dir);
  ASSERT_EQ(status, 0);
  IgtlStreamDecoder decoder;
  const auto messages = DecodeAll(decoder, received, received.size());
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[0].type, "POLYDATA");
  EXPECT_EQ(messages[1].deviceName, "VesselRibbonStart");
  EXPECT_EQ(messages[2].deviceName, "VesselRibbonEnd");
  std::vector<bender::IgtlToolPose> poses;
  std::string problem;
  ASSERT_TRUE(bender::DecodeIgtlPoses(messages[2], poses, problem)) << problem;
  ASSERT_EQ(poses.size(), 1u);
  // RAS: (-30, -20, 0); the frame's x axis (the tangent +y in LPS) is -y in RAS.
  EXPECT_NEAR(poses[0].position.x, -30, 1e-5);
  EXPECT_NEAR(poses[0].position.y, -20, 1e-5);
  const Vec3 x = bender::RotateByQuaternion(poses[0].orientation, { 1, 0, 0 });
  const Vec3 z = bender::RotateByQuaternion(poses[0].orientation, { 0, 0, 1 });
  EXPECT_NEAR(x.y, -1.0, 1e-6);
  EXPECT_NEAR(z.z, 1.0, 1e-6);
}

// The TrackerServer example of openigtlink-examples (a real peer, not ours) streams its
// known trajectory: pose i at RAS 50 (cos 0.2i, sin 0.2i, cos 0.2i) mm, device "Tracker".
TEST(IgtlCli, TrackerReadsTheOpenIgtlinkExampleServerInLps)
{
#ifndef BENDER_IGTL_TRACKER_SERVER
  GTEST_SKIP() << "openigtlink-examples is not installed";
#else
  int port = 0;
  {
    LoopbackServer probe; // an ephemeral port that is free once the probe closes
    port = probe.Port();
  }
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0)
  {
    const int devNull = ::open("/dev/null", O_WRONLY); // the example prints every matrix
    ::dup2(devNull, STDOUT_FILENO);
    const std::string portText = std::to_string(port);
    ::execl(BENDER_IGTL_TRACKER_SERVER,
      BENDER_IGTL_TRACKER_SERVER,
      portText.c_str(),
      "200",
      static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::ostringstream out, err;
  int status = 1;
  // The server needs a moment to listen: retry a refused connection (bounded).
  for (int attempt = 0; attempt < 100; ++attempt)
  {
    out.str("");
    err.str("");
    status = bender::RunTrackerCli(
      { "--device", "igtl:127.0.0.1:" + std::to_string(port), "--count", "10" }, out, err);
    if (status == 0 || err.str().find("refused") == std::string::npos)
    {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGTERM);
  int exitStatus = 0;
  ::waitpid(pid, &exitStatus, 0);
  ASSERT_EQ(status, 0) << err.str();
  std::istringstream lines(out.str());
  std::string line;
  int i = 0;
  for (; std::getline(lines, line); ++i)
  {
    const nlohmann::json pose = nlohmann::json::parse(line);
    EXPECT_EQ(pose["device"], "Tracker");
    EXPECT_EQ(pose["station"], 0);
    const double phi = 0.2 * i;
    EXPECT_NEAR(pose["position"][0].get<double>(), -50.0 * std::cos(phi), 1e-3) << i;
    EXPECT_NEAR(pose["position"][1].get<double>(), -50.0 * std::sin(phi), 1e-3) << i;
    EXPECT_NEAR(pose["position"][2].get<double>(), 50.0 * std::cos(phi), 1e-3) << i;
  }
  EXPECT_EQ(i, 10);
#endif
}
