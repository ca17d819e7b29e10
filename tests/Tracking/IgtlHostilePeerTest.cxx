// Hostile and silent OpenIGTLink peers on real loopback sockets (issue 25): a server that
// announces a 2^60-byte body, one that trickles a byte at a time, one that floods garbage as
// fast as it can. IgtlDevice keeps its decoder within IgtlStreamDecoder::BufferCap, drops the
// connection with one line saying why, and connects again to a good server afterwards. And
// "never hang": connect, read and write return within their timeouts against a peer that does
// not answer, and Stop() returns within the read timeout while such a peer is connected.
// Every loop here is bounded by a count or by a deadline of a few seconds.

#include "IgtlDevice.h"
#include "IgtlLoopback.h"
#include "IgtlProtocol.h"
#include "IgtlSocket.h"
#include "TrackingErrors.h"

#include <gtest/gtest.h>

#include <netdb.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>

namespace
{
using bender::test::Bytes;
using bender::test::Collect;
using bender::test::Collected;
using bender::test::DeviceOptions;
using bender::test::HasEvent;
using bender::test::LoopbackServer;
using bender::test::SendBytes;
using Clock = std::chrono::steady_clock;

// A TRANSFORM for the first hand at x (RAS), encoded by Bender.
Bytes HandTransform(double x)
{
  return bender::EncodeIgtlMessage(
    "TRANSFORM", "StylusToTracker", bender::EncodeIgtlTransform({ x, 0, 0 }, { 1, 0, 0, 0 }));
}

// A peer that accepts, reads nothing and sends nothing until `done` (at most 10 s).
LoopbackServer::Script Silent(const std::atomic<bool>& done)
{
  return [&done](int)
  {
    for (int i = 0; i < 1000 && !done; ++i)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  };
}

// The one event that ended the stream, checked to be a drop named in one line.
bender::TrackerEvent DropEvent(const Collected& c)
{
  EXPECT_EQ(c.events.size(), 1u);
  if (c.events.empty())
  {
    return {};
  }
  const bender::TrackerEvent& e = c.events.back();
  EXPECT_EQ(e.type, bender::TrackerEventType::ReadError);
  EXPECT_EQ(e.message.rfind("dropped the connection: ", 0), 0u) << e.message;
  EXPECT_EQ(e.message.find('\n'), std::string::npos) << e.message;
  EXPECT_LT(e.message.size(), 300u) << e.message;
  return e;
}

bool Ended(const Collected& c)
{
  return HasEvent(c, bender::TrackerEventType::ReadError) ||
    HasEvent(c, bender::TrackerEventType::Disconnected);
}

// Connects and takes what the device publishes until the stream ends.
Collected StreamUntilEnded(bender::IgtlDevice& device)
{
  device.EnablePoseQueue(100, false);
  device.Open();
  device.Start();
  return Collect(device, Ended);
}

// The second connection of every hostile test: a good server whose pose must come through
// the same device object after Close() and Open().
void ExpectReconnectWorks(bender::IgtlDevice& device)
{
  device.Close();
  device.Open();
  device.Start();
  const Collected good = Collect(device, [](const Collected& c) { return !c.poses.empty(); });
  device.Close();
  ASSERT_EQ(good.poses.size(), 1u);
  EXPECT_NEAR(good.poses[0].position.x, -42.0, 1e-4); // RAS x = 42 is LPS x = -42
  EXPECT_TRUE(good.events.empty());
}

LoopbackServer::Script GoodServer()
{
  return [](int fd)
  {
    SendBytes(fd, HandTransform(42.0));
    bender::test::WaitForPeerClose(fd);
  };
}

// The decoder's memory never went above its documented cap.
void ExpectBounded(const bender::IgtlDevice& device)
{
  const bender::IgtlStatistics s = device.IgtlStats();
  const bender::IgtlStreamDecoder reference(device.GetOptions().maxBodyBytes);
  EXPECT_LE(s.decoder.peakBuffered, reference.BufferCap());
}

} // namespace

TEST(IgtlHostilePeer, DecoderMemoryIsReleasedAndCappedOnceItWaits)
{
  // A 1 MiB message fed in 64 KiB pieces, then small ones: the room of the large one is
  // given back, and the decoder never holds more than the message it waits for.
  const std::uint64_t cap = 2u << 20;
  bender::IgtlStreamDecoder decoder(cap);
  Bytes stream = bender::EncodeIgtlMessage("IMAGE", "Image", Bytes(1u << 20, 9));
  for (int k = 0; k < 10; ++k)
  {
    const Bytes m = HandTransform(k);
    stream.insert(stream.end(), m.begin(), m.end());
  }
  int messages = 0;
  for (std::size_t at = 0; at < stream.size(); at += 65536)
  {
    decoder.Feed(stream.data() + at, std::min<std::size_t>(65536, stream.size() - at));
    while (decoder.Next())
    {
      ++messages;
    }
    EXPECT_EQ(decoder.Buffered(), decoder.Pending());
    EXPECT_LT(decoder.Buffered(), decoder.BufferCap());
  }
  EXPECT_EQ(messages, 11);
  EXPECT_EQ(decoder.Pending(), 0u);
  EXPECT_GE(decoder.Statistics().peakBuffered, 1u << 20);
  EXPECT_LT(decoder.Statistics().peakBuffered, decoder.BufferCap());
  EXPECT_EQ(decoder.BufferCap(), 58 + cap);
}

TEST(IgtlHostilePeer, AnInStepHeaderAboveTheLimitIsARefusalGarbageIsNot)
{
  Bytes huge = bender::EncodeIgtlMessage("IMAGE", "Image", {});
  huge[42] = 0x10; // body size 2^60, big-endian at bytes 42..49
  // In step: after a message.
  Bytes stream = HandTransform(1.0);
  stream.insert(stream.end(), huge.begin(), huge.end());
  bender::IgtlStreamDecoder decoder;
  decoder.Feed(stream.data(), stream.size());
  EXPECT_TRUE(decoder.Next());
  EXPECT_FALSE(decoder.Next());
  EXPECT_EQ(decoder.Refusal(),
    "IMAGE message 'Image' announces 1152921504606846976 body bytes, more than the 67108864 "
    "accepted");
  // The same header found while hunting through garbage is garbage like any other.
  Bytes garbage = { 0xde, 0xad };
  garbage.insert(garbage.end(), huge.begin(), huge.end());
  bender::IgtlStreamDecoder hunting;
  hunting.Feed(garbage.data(), garbage.size());
  EXPECT_FALSE(hunting.Next());
  EXPECT_TRUE(hunting.Refusal().empty());
  EXPECT_EQ(hunting.Statistics().oversized, 1u);
  hunting.Reset();
  EXPECT_EQ(hunting.Statistics().garbageBytes, 0u);
}

TEST(IgtlHostilePeer, TextsFromThePeerAreMadeFitToShow)
{
  // Found by fuzz_igtl: a STATUS text and a QTDATA element name are shown (status line, names
  // seen, the terminal); control bytes and escape sequences from the peer must not get there.
  Bytes status = { 0, 4, 0, 0, 0, 0, 0, 0, 0, 0 };
  const std::string name = "Not\x1b[31mReady";
  status.insert(status.end(), name.begin(), name.end());
  status.resize(30, 0);
  const std::string text = "tool\x07 out of view\xf7";
  status.insert(status.end(), text.begin(), text.end());
  status.push_back(0);
  bender::IgtlMessage message;
  message.type = "STATUS";
  message.deviceName = "Tracker";
  message.content = status;
  const std::optional<bender::IgtlStatus> decoded = bender::DecodeIgtlStatus(message);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->code, 4);
  EXPECT_EQ(decoded->errorName, "Not?[31mReady");
  EXPECT_EQ(decoded->text, "tool? out of view?");

  Bytes element(50, 0);
  const std::string elementName = "Stylus\x1b]0;x";
  std::copy(elementName.begin(), elementName.end(), element.begin());
  message.type = "QTDATA";
  message.content = element;
  std::vector<bender::IgtlToolPose> poses;
  std::string problem;
  EXPECT_FALSE(bender::DecodeIgtlPoses(message, poses, problem));
  EXPECT_EQ(problem, "QTDATA 'Tracker': element 1: name is not printable ASCII");
  EXPECT_TRUE(poses.empty());
}

TEST(IgtlHostilePeer, AServerAnnouncingA2To60ByteBodyIsDroppedAndReconnectWorks)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      Bytes header = bender::EncodeIgtlMessage("IMAGE", "Image", {});
      header[42] = 0x10;
      Bytes stream = HandTransform(1.0);
      stream.insert(stream.end(), header.begin(), header.end());
      SendBytes(fd, stream);
      // Then the "body", until the device hangs up (at most about 2 GB or 5 s).
      const Bytes zeros(1 << 16, 0);
      const auto deadline = Clock::now() + std::chrono::seconds(5);
      for (int i = 0; i < 32768 && Clock::now() < deadline && SendBytes(fd, zeros); ++i)
      {
      }
    },
    GoodServer() });
  bender::IgtlDevice device(DeviceOptions(server.Port()));
  const Collected c = StreamUntilEnded(device);
  ASSERT_EQ(c.poses.size(), 1u);
  const bender::TrackerEvent drop = DropEvent(c);
  EXPECT_NE(drop.message.find("announces 1152921504606846976 body bytes"), std::string::npos)
    << drop.message;
  EXPECT_FALSE(device.IsStreaming());
  ExpectBounded(device);
  ExpectReconnectWorks(device);
  server.Join();
}

TEST(IgtlHostilePeer, AServerTricklingOneByteASecondIsDroppedAndReconnectWorks)
{
  LoopbackServer server;
  server.Serve({ [](int fd)
    {
      // A valid message, one byte a second, until the device hangs up (at most 6 s).
      const Bytes message = HandTransform(1.0);
      for (std::size_t i = 0; i < 6 && SendBytes(fd, Bytes{ message[i] }); ++i)
      {
        std::this_thread::sleep_for(std::chrono::seconds(1));
      }
    },
    GoodServer() });
  bender::IgtlDevice::Options options = DeviceOptions(server.Port());
  options.stallTimeout = std::chrono::milliseconds(1500);
  bender::IgtlDevice device(options);
  const Collected c = StreamUntilEnded(device);
  EXPECT_TRUE(c.poses.empty());
  const bender::TrackerEvent drop = DropEvent(c);
  EXPECT_NE(drop.message.find("no complete message for "), std::string::npos) << drop.message;
  EXPECT_NE(drop.message.find("bytes of a message header"), std::string::npos) << drop.message;
  ExpectBounded(device);
  ExpectReconnectWorks(device);
  server.Join();
}

TEST(IgtlHostilePeer, AServerFloodingGarbageIsDroppedWithMemoryBoundedAndReconnectWorks)
{
  std::uint64_t offered = 0;
  LoopbackServer server;
  server.Serve({ [&offered](int fd)
    {
      // Random bytes as fast as the socket takes them, until the device hangs up (at most 4 s).
      std::mt19937 random(25);
      Bytes garbage(1 << 20);
      for (std::uint8_t& b : garbage)
      {
        b = std::uint8_t(random());
      }
      const auto deadline = Clock::now() + std::chrono::seconds(4);
      while (Clock::now() < deadline && SendBytes(fd, garbage))
      {
        offered += garbage.size();
      }
    },
    GoodServer() });
  bender::IgtlDevice device(DeviceOptions(server.Port()));
  const Collected c = StreamUntilEnded(device);
  EXPECT_TRUE(c.poses.empty());
  const bender::TrackerEvent drop = DropEvent(c);
  EXPECT_NE(drop.message.find("without a valid OpenIGTLink message"), std::string::npos)
    << drop.message;
  const bender::IgtlStatistics s = device.IgtlStats();
  EXPECT_GT(s.decoder.garbageBytes, device.GetOptions().maxGarbageBytes);
  ExpectBounded(device);
  ExpectReconnectWorks(device);
  server.Join();
  EXPECT_GT(offered, device.GetOptions().maxGarbageBytes);
}

// ---------------------------------------------------------------------------------------
// Never hang: every call that waits on the peer returns within its timeout.

TEST(IgtlNeverHang, ConnectToAPeerThatNeverCompletesTheHandshakeTimesOut)
{
  // A listening socket whose accept queue is full: the kernel drops further handshakes, so a
  // connect neither succeeds nor fails until its timeout.
  const int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(listener, 0), 0);
  socklen_t len = sizeof a;
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&a), &len);
  const int port = ntohs(a.sin_port);
  std::vector<std::unique_ptr<bender::IgtlConnection>> fillers;
  const std::chrono::milliseconds timeout(300);
  bool timedOut = false;
  for (int i = 0; i < 16 && !timedOut; ++i)
  {
    auto connection = std::make_unique<bender::IgtlConnection>();
    const auto start = Clock::now();
    try
    {
      connection->Connect("127.0.0.1", port, timeout);
      fillers.push_back(std::move(connection));
    }
    catch (const bender::DeviceNotFoundError& e)
    {
      const auto took = Clock::now() - start;
      timedOut = true;
      EXPECT_NE(std::string(e.what()).find("no answer within 300 ms"), std::string::npos)
        << e.what();
      // It waited (poll counts whole milliseconds, so allow one less), and not much longer.
      EXPECT_GE(took, timeout - std::chrono::milliseconds(2));
      EXPECT_LT(took, timeout + std::chrono::seconds(2));
    }
  }
  EXPECT_TRUE(timedOut) << "the kernel completed " << fillers.size() << " handshakes";
  ::close(listener);
}

// A name server that does not answer: each lookup blocks until released (or 10 s, so that
// not even a resolver that waits for it can hang the test), counting its calls.
struct SilentNameServer
{
  struct State
  {
    std::mutex mutex;
    std::condition_variable released;
    bool open = false;
    int calls = 0;
    int returned = 0;
  };
  std::shared_ptr<State> S = std::make_shared<State>();

  bender::HostLookup Lookup() const
  {
    return [s = this->S](const char*, const char*, const addrinfo*, addrinfo**)
    {
      std::unique_lock<std::mutex> lock(s->mutex);
      ++s->calls;
      s->released.wait_for(lock, std::chrono::seconds(10), [&s] { return s->open; });
      ++s->returned;
      s->released.notify_all();
      return EAI_AGAIN;
    };
  }
  int Calls() const
  {
    std::lock_guard<std::mutex> lock(this->S->mutex);
    return this->S->calls;
  }
  // Lets every lookup return and waits (bounded) until the `calls` made have.
  bool ReleaseAndJoin(int calls) const
  {
    std::unique_lock<std::mutex> lock(this->S->mutex);
    this->S->open = true;
    this->S->released.notify_all();
    return this->S->released.wait_for(
      lock, std::chrono::seconds(10), [this, calls] { return this->S->returned >= calls; });
  }
};

TEST(IgtlNeverHang, AHostNameTheNameServerNeverAnswersIsGivenUpAtTheTimeout)
{
  const SilentNameServer dns;
  const std::chrono::milliseconds timeout(200);
  const auto start = Clock::now();
  try
  {
    bender::ResolveHost("tracker.hangs.example", 18944, timeout, dns.Lookup());
    ADD_FAILURE() << "resolved a name that the name server never answered";
  }
  catch (const bender::DeviceNotFoundError& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find("tracker.hangs.example:18944"), std::string::npos) << message;
    EXPECT_NE(message.find("not resolved within 200 ms"), std::string::npos) << message;
  }
  const auto took = Clock::now() - start;
  EXPECT_GE(took, timeout - std::chrono::milliseconds(2));
  EXPECT_LT(took, timeout + std::chrono::seconds(2));
  EXPECT_TRUE(dns.ReleaseAndJoin(1));
  EXPECT_EQ(dns.Calls(), 1);
}

TEST(IgtlNeverHang, ANumericAddressAsksNoNameServerANameTheSystemOne)
{
  const SilentNameServer dns;
  for (const char* host : { "127.0.0.1", "::1" })
  {
    const auto start = Clock::now();
    const bender::AddressList found =
      bender::ResolveHost(host, 18944, std::chrono::milliseconds(5000), dns.Lookup());
    ASSERT_TRUE(found) << host;
    EXPECT_LT(Clock::now() - start, std::chrono::seconds(1)) << host;
  }
  EXPECT_EQ(dns.Calls(), 0);
  EXPECT_TRUE(dns.ReleaseAndJoin(0));
  // A name goes through the system's lookup (getaddrinfo, on its thread).
  EXPECT_TRUE(bender::ResolveHost("localhost", 18944, std::chrono::milliseconds(5000)));
}

TEST(IgtlNeverHang, LookupsLeftUnansweredAreBoundedAndNamesResolveAgainAfterwards)
{
  const SilentNameServer dns;
  int given = 0;
  // Each lookup given up on runs on; a few at most, then the next is refused at once.
  for (int i = 0; i < 12; ++i)
  {
    const auto start = Clock::now();
    EXPECT_THROW(bender::ResolveHost(
                   "tracker.hangs.example", 18944, std::chrono::milliseconds(30), dns.Lookup()),
      bender::DeviceNotFoundError);
    EXPECT_LT(Clock::now() - start, std::chrono::seconds(2));
    given = dns.Calls();
  }
  EXPECT_GE(given, 1);
  EXPECT_LT(given, 12);
  ASSERT_TRUE(dns.ReleaseAndJoin(given));
  // Answered lookups again: a name that resolves (the loopback address, as a name server
  // answers) and one that does not.
  const bender::HostLookup loopback =
    [](const char*, const char* service, const addrinfo* hints, addrinfo** found)
  { return ::getaddrinfo("127.0.0.1", service, hints, found); };
  bender::AddressList found;
  for (int tries = 0; tries < 100 && !found; ++tries)
  {
    try
    {
      found =
        bender::ResolveHost("tracker.example", 18944, std::chrono::milliseconds(2000), loopback);
    }
    catch (const bender::DeviceNotFoundError&)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(20)); // the last threads ending
    }
  }
  ASSERT_TRUE(found);
  const bender::HostLookup unknown = [](const char*, const char*, const addrinfo*, addrinfo**)
  { return EAI_NONAME; };
  EXPECT_THROW(
    bender::ResolveHost("no.such.host.example", 18944, std::chrono::milliseconds(2000), unknown),
    bender::TrackingConfigurationError);
}

TEST(IgtlNeverHang, APeerThatAcceptsAndNeverAnswersBlocksNothing)
{
  std::atomic<bool> done{ false };
  LoopbackServer server;
  server.Serve({ Silent(done), Silent(done) });
  // Read: the device streams nothing, is not dropped (idle is not hostile), and Stop()
  // returns within about its read timeout.
  bender::IgtlDevice::Options options = DeviceOptions(server.Port());
  options.stallTimeout = std::chrono::milliseconds(200);
  bender::IgtlDevice device(options);
  device.EnablePoseQueue(100, false);
  const auto openStart = Clock::now();
  device.Open();
  device.Start();
  EXPECT_LT(Clock::now() - openStart, std::chrono::seconds(2));
  for (int i = 0; i < 8; ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(device.IsStreaming());
  EXPECT_TRUE(device.TakeEvents().empty());
  const auto stopStart = Clock::now();
  device.Close();
  EXPECT_LT(Clock::now() - stopStart, options.readTimeout + std::chrono::seconds(2));

  // Write: far more bytes than the loopback socket buffers on both sides hold, to a peer that
  // reads nothing, fail within the write timeout, naming how much the peer took.
  bender::IgtlConnection writer;
  writer.Connect("127.0.0.1", server.Port(), std::chrono::milliseconds(1000));
  const Bytes lots(64u << 20, 0);
  const std::chrono::milliseconds writeTimeout(300);
  const auto writeStart = Clock::now();
  try
  {
    writer.WriteAll(lots.data(), lots.size(), writeTimeout);
    ADD_FAILURE() << "a peer that reads nothing took 64 MiB";
  }
  catch (const bender::TransportError& e)
  {
    EXPECT_NE(std::string(e.what()).find("the peer took only "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("within 300 ms"), std::string::npos) << e.what();
  }
  EXPECT_LT(Clock::now() - writeStart, writeTimeout + std::chrono::seconds(2));
  writer.Close();
  done = true;
  server.Join();
}

TEST(IgtlNeverHang, ReadOnASilentConnectionReturnsAtItsTimeout)
{
  std::atomic<bool> done{ false };
  LoopbackServer server;
  server.Serve({ Silent(done) });
  bender::IgtlConnection connection;
  connection.Connect("127.0.0.1", server.Port(), std::chrono::milliseconds(1000));
  std::uint8_t buffer[64];
  std::size_t received = 0;
  const auto start = Clock::now();
  const auto result =
    connection.Read(buffer, sizeof buffer, received, std::chrono::milliseconds(200));
  const auto took = Clock::now() - start;
  EXPECT_EQ(result, bender::IgtlConnection::ReadResult::Timeout);
  EXPECT_EQ(received, 0u);
  EXPECT_GE(took, std::chrono::milliseconds(190));
  EXPECT_LT(took, std::chrono::milliseconds(200) + std::chrono::seconds(2));
  done = true;
  connection.Close();
  server.Join();
}
