#ifndef bender_IgtlLoopback_h
#define bender_IgtlLoopback_h

// Helpers shared by the OpenIGTLink tests: a loopback server that runs one script per accepted
// client, byte sending and receiving on its sockets, and the collection of what an IgtlDevice
// publishes. Loopback 127.0.0.1 on ephemeral ports only.

#include "IgtlDevice.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

namespace bender::test
{

using Bytes = std::vector<std::uint8_t>;

// A one-connection-at-a-time loopback server: each accepted client gets the next script.
class LoopbackServer
{
public:
  using Script = std::function<void(int fd)>;

  LoopbackServer()
  {
    this->Listen = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    EXPECT_EQ(::bind(this->Listen, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    EXPECT_EQ(::listen(this->Listen, 4), 0);
    socklen_t len = sizeof a;
    ::getsockname(this->Listen, reinterpret_cast<sockaddr*>(&a), &len);
    this->PortNumber = ntohs(a.sin_port);
  }
  ~LoopbackServer()
  {
    if (this->Worker.joinable())
    {
      this->Worker.join();
    }
    ::close(this->Listen);
  }
  int Port() const { return this->PortNumber; }

  /// Accepts `scripts.size()` clients one after the other and runs each script; the
  /// connection is closed when its script returns.
  void Serve(std::vector<Script> scripts)
  {
    this->Worker = std::thread(
      [this, scripts]
      {
        for (const Script& script : scripts)
        {
          const int fd = ::accept(this->Listen, nullptr, nullptr);
          if (fd < 0)
          {
            return;
          }
          script(fd);
          ::close(fd);
        }
      });
  }
  void Join()
  {
    if (this->Worker.joinable())
    {
      this->Worker.join();
    }
  }

private:
  int Listen = -1;
  int PortNumber = 0;
  std::thread Worker;
};

// Sends every byte unless the peer has gone; false once it has (reset or closed).
inline bool SendBytes(int fd, const Bytes& bytes)
{
  std::size_t sent = 0;
  while (sent < bytes.size())
  {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0)
    {
      return false;
    }
    sent += std::size_t(n);
  }
  return true;
}

// Waits (bounded by a count of polls, never by a timed assertion) until the peer closes.
inline void WaitForPeerClose(int fd)
{
  std::uint8_t b[256];
  for (int i = 0; i < 2000 && ::recv(fd, b, sizeof b, 0) > 0; ++i)
  {
  }
}

inline Bytes ReadUntilClosed(int fd)
{
  Bytes out;
  std::uint8_t b[65536];
  ssize_t n = 0;
  while ((n = ::recv(fd, b, sizeof b, 0)) > 0)
  {
    out.insert(out.end(), b, b + n);
  }
  return out;
}

// Takes what the device publishes until `done` says so or the device stops streaming
// (the loop is bounded: at most 400 waits of 50 ms).
struct Collected
{
  std::vector<bender::TrackerPose> poses;
  std::vector<bender::TrackerEvent> events;
};

inline Collected Collect(bender::TrackerDevice& device,
  const std::function<bool(const Collected&)>& done)
{
  Collected c;
  for (int i = 0; i < 400 && !done(c); ++i)
  {
    device.WaitForActivity(std::chrono::milliseconds(50));
    // Events first: the poses the device queued before an event (a disconnection after the
    // last message) are then in the queue when the poses are taken. The other order lost the
    // last poses when the device queued them and the event between the two calls.
    for (const auto& e : device.TakeEvents())
    {
      c.events.push_back(e);
    }
    for (const auto& p : device.TakePoses())
    {
      c.poses.push_back(p);
    }
  }
  return c;
}

inline bool HasEvent(const Collected& c, bender::TrackerEventType type)
{
  for (const auto& e : c.events)
  {
    if (e.type == type)
    {
      return true;
    }
  }
  return false;
}

inline bender::IgtlDevice::Options DeviceOptions(int port)
{
  bender::IgtlDevice::Options o;
  o.host = "127.0.0.1";
  o.port = port;
  o.toolNames = { "StylusToTracker", "Stylus2ToTracker" };
  return o;
}

} // namespace bender::test

#endif
