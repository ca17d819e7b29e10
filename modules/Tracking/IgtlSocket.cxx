#include "IgtlSocket.h"

#include "TrackingErrors.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <system_error>
#include <thread>
#include <unistd.h>

namespace bender
{

void ParseHostPort(const std::string& text, const std::string& what, std::string& host, int& port)
{
  const auto bad = [&](const std::string& why) {
    return TrackingConfigurationError(what + " '" + text + "': " + why + " (expected HOST:PORT)");
  };
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
  {
    throw bad("no host or no port");
  }
  host = text.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']')
  {
    host = host.substr(1, host.size() - 2);
  }
  const std::string portText = text.substr(colon + 1);
  if (portText.empty() || portText.size() > 5 ||
    portText.find_first_not_of("0123456789") != std::string::npos)
  {
    throw bad("'" + portText + "' is not a port number");
  }
  port = std::stoi(portText);
  if (port < 1 || port > 65535)
  {
    throw bad("port " + portText + " is outside 1..65535");
  }
}

namespace
{
// Name lookups that outlived their wait run on, unwaited for: beyond this many at once, a name
// server that does not answer is said so without starting another.
constexpr int MaxUnansweredLookups = 4;
std::atomic<int> UnansweredLookups{ 0 };

// One lookup, shared by its thread and the caller that waits for it (or gave up on it).
struct PendingLookup
{
  std::mutex mutex;
  std::condition_variable done;
  bool finished = false;
  bool abandoned = false;
  int status = EAI_AGAIN;
  addrinfo* found = nullptr;
};
} // namespace

void FreeAddresses::operator()(addrinfo* addresses) const
{
  ::freeaddrinfo(addresses);
}

AddressList ResolveHost(const std::string& host,
  int port,
  std::chrono::milliseconds timeout,
  const HostLookup& lookup)
{
  const std::string prefix = "igtl " + host + ":" + std::to_string(port) + ": ";
  const std::string service = std::to_string(port);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  // A numeric address asks no name server.
  addrinfo numeric = hints;
  numeric.ai_flags = AI_NUMERICHOST;
  addrinfo* found = nullptr;
  if (::getaddrinfo(host.c_str(), service.c_str(), &numeric, &found) == 0 && found)
  {
    return AddressList(found);
  }
  if (UnansweredLookups.load() >= MaxUnansweredLookups)
  {
    throw DeviceNotFoundError(prefix +
      "cannot resolve host: " + std::to_string(MaxUnansweredLookups) +
      " earlier lookups are still unanswered (is the name server reachable?)");
  }
  auto pending = std::make_shared<PendingLookup>();
  const HostLookup resolve = lookup ? lookup : HostLookup(::getaddrinfo);
  ++UnansweredLookups;
  try
  {
    std::thread(
      [pending, resolve, host, service, hints]()
      {
        addrinfo* result = nullptr;
        int status = EAI_FAIL;
        try
        {
          status = resolve(host.c_str(), service.c_str(), &hints, &result);
        }
        catch (...)
        {
          result = nullptr;
        }
        std::lock_guard<std::mutex> lock(pending->mutex);
        --UnansweredLookups;
        if (pending->abandoned)
        {
          if (result)
          {
            ::freeaddrinfo(result);
          }
          return;
        }
        pending->status = status;
        pending->found = result;
        pending->finished = true;
        pending->done.notify_all();
      })
      .detach();
  }
  catch (const std::system_error& e)
  {
    --UnansweredLookups;
    throw DeviceNotFoundError(prefix + "cannot start the host lookup (" + e.what() + ")");
  }
  std::unique_lock<std::mutex> lock(pending->mutex);
  if (!pending->done.wait_for(lock, timeout, [&pending] { return pending->finished; }))
  {
    pending->abandoned = true;
    throw DeviceNotFoundError(prefix + "the host name was not resolved within " +
      std::to_string(timeout.count()) + " ms (is the name server reachable?)");
  }
  AddressList addresses(pending->found);
  if (pending->status != 0 || !addresses)
  {
    throw TrackingConfigurationError(
      prefix + "cannot resolve host (" + ::gai_strerror(pending->status) + ")");
  }
  return addresses;
}

IgtlConnection::~IgtlConnection()
{
  this->Close();
}

void IgtlConnection::Close()
{
  if (this->Fd >= 0)
  {
    ::close(this->Fd);
    this->Fd = -1;
  }
}

void IgtlConnection::Shutdown()
{
  if (this->Fd >= 0)
  {
    ::shutdown(this->Fd, SHUT_RDWR);
  }
}

void IgtlConnection::Connect(const std::string& host, int port, std::chrono::milliseconds timeout)
{
  this->Close();
  this->PeerName = host + ":" + std::to_string(port);
  const std::string prefix = "igtl " + this->PeerName + ": ";
  const AddressList found = ResolveHost(host, port, timeout);
  std::string lastProblem = "no address";
  for (addrinfo* a = found.get(); a; a = a->ai_next)
  {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0)
    {
      lastProblem = std::strerror(errno);
      continue;
    }
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    int error = 0;
    if (::connect(fd, a->ai_addr, a->ai_addrlen) != 0)
    {
      error = errno;
      if (error == EINPROGRESS)
      {
        // Waits for the handshake until the deadline, also across signals (a poll cut short
        // by one must not pass for a connected socket).
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        int ready = 0;
        do
        {
          const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
          pollfd p{ fd, POLLOUT, 0 };
          ready = ::poll(&p, 1, int(std::max<std::int64_t>(0, left.count())));
        } while (ready < 0 && errno == EINTR);
        if (ready == 0)
        {
          error = ETIMEDOUT;
        }
        else if (ready < 0)
        {
          error = errno;
        }
        else
        {
          socklen_t len = sizeof error;
          ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &len);
        }
      }
    }
    if (error == 0)
    {
      const int one = 1;
      ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      this->Fd = fd;
      return;
    }
    ::close(fd);
    lastProblem = error == ETIMEDOUT ? "no answer within " + std::to_string(timeout.count()) + " ms"
                                     : std::strerror(error);
  }
  throw DeviceNotFoundError(prefix + lastProblem + " (is the OpenIGTLink server running?)");
}

IgtlConnection::ReadResult IgtlConnection::Read(std::uint8_t* buffer,
  std::size_t capacity,
  std::size_t& received,
  std::chrono::milliseconds timeout)
{
  received = 0;
  if (this->Fd < 0)
  {
    return ReadResult::Closed;
  }
  pollfd p{ this->Fd, POLLIN, 0 };
  const int ready = ::poll(&p, 1, int(timeout.count()));
  if (ready < 0)
  {
    if (errno == EINTR)
    {
      return ReadResult::Timeout;
    }
    throw TransportError("igtl " + this->PeerName + ": poll: " + std::strerror(errno));
  }
  if (ready == 0)
  {
    return ReadResult::Timeout;
  }
  const ssize_t n = ::recv(this->Fd, buffer, capacity, 0);
  if (n > 0)
  {
    received = std::size_t(n);
    return ReadResult::Data;
  }
  if (n == 0 || errno == ECONNRESET)
  {
    return ReadResult::Closed;
  }
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
  {
    return ReadResult::Timeout;
  }
  throw TransportError("igtl " + this->PeerName + ": recv: " + std::strerror(errno));
}

void IgtlConnection::WriteAll(const std::uint8_t* data,
  std::size_t size,
  std::chrono::milliseconds timeout)
{
  const std::string prefix = "igtl " + this->PeerName + ": ";
  if (this->Fd < 0)
  {
    throw DeviceDisconnectedError(prefix + "not connected");
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::size_t sent = 0;
  while (sent < size)
  {
    const ssize_t n = ::send(this->Fd, data + sent, size - sent, MSG_NOSIGNAL);
    if (n > 0)
    {
      sent += std::size_t(n);
      continue;
    }
    if (n < 0 && (errno == EPIPE || errno == ECONNRESET))
    {
      throw DeviceDisconnectedError(prefix + "the peer closed the connection");
    }
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
    {
      throw TransportError(prefix + "send: " + std::strerror(errno));
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
      deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0)
    {
      throw TransportError(prefix + "the peer took only " + std::to_string(sent) + " of " +
        std::to_string(size) + " bytes within " + std::to_string(timeout.count()) + " ms");
    }
    pollfd p{ this->Fd, POLLOUT, 0 };
    ::poll(&p, 1, int(left.count()));
  }
}

} // namespace bender
