#ifndef bender_IgtlSocket_h
#define bender_IgtlSocket_h

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

struct addrinfo;

namespace bender
{

/// "HOST:PORT" (HOST a name, an IPv4 address or [IPv6]); throws TrackingConfigurationError
/// naming `what` and the text when it does not parse or the port is outside 1..65535.
void ParseHostPort(const std::string& text, const std::string& what, std::string& host, int& port);

/// A host name lookup with getaddrinfo's arguments and result (the default is getaddrinfo
/// itself; tests give one that never answers). Its results are freed with freeaddrinfo.
using HostLookup = std::function<int(const char*, const char*, const addrinfo*, addrinfo**)>;
struct FreeAddresses
{
  void operator()(addrinfo* addresses) const;
};
using AddressList = std::unique_ptr<addrinfo, FreeAddresses>;

/// The TCP addresses of HOST:PORT, never waiting longer than `timeout`: a numeric address
/// (IPv4, IPv6) is read at once; a name is looked up on a thread of its own, given up at the
/// timeout (the lookup finishes, unwaited for, on its thread; at most a few are left so).
/// Throws DeviceNotFoundError when no answer came in time, TrackingConfigurationError when
/// the name does not resolve.
AddressList ResolveHost(const std::string& host,
  int port,
  std::chrono::milliseconds timeout,
  const HostLookup& lookup = {});

/// A TCP client connection for OpenIGTLink (POSIX sockets, every wait bounded by a poll
/// timeout so that a reader thread can be stopped). Not copyable; closes on destruction.
class IgtlConnection
{
public:
  IgtlConnection() = default;
  ~IgtlConnection();
  IgtlConnection(const IgtlConnection&) = delete;
  IgtlConnection& operator=(const IgtlConnection&) = delete;

  /// Resolves the host (ResolveHost) and connects, each within `timeout`. Throws
  /// DeviceNotFoundError when the peer refuses or does not answer ("igtl HOST:PORT:
  /// connection refused (is the server running?)") or the name server does not answer, and
  /// TrackingConfigurationError when the host name does not resolve.
  void Connect(const std::string& host, int port, std::chrono::milliseconds timeout);
  bool IsOpen() const { return this->Fd >= 0; }
  void Close();
  /// Ends the connection both ways (the peer sees it closed) but keeps the socket until
  /// Close(), so that a reader thread may call it while other threads ask IsOpen().
  void Shutdown();

  enum class ReadResult
  {
    Data,    ///< `received` bytes were read
    Timeout, ///< nothing within the timeout
    Closed   ///< the peer closed the connection (or reset it)
  };
  /// Reads what is available, waiting at most `timeout`. Throws TransportError on other
  /// socket errors.
  ReadResult Read(std::uint8_t* buffer,
    std::size_t capacity,
    std::size_t& received,
    std::chrono::milliseconds timeout);
  /// Writes everything within `timeout`; throws DeviceDisconnectedError when the peer went
  /// away and TransportError when it does not take the bytes in time.
  void WriteAll(const std::uint8_t* data, std::size_t size, std::chrono::milliseconds timeout);

  /// "HOST:PORT", for messages.
  const std::string& Peer() const { return this->PeerName; }

private:
  int Fd = -1;
  std::string PeerName;
};

} // namespace bender

#endif
