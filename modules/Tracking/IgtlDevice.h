#ifndef bender_IgtlDevice_h
#define bender_IgtlDevice_h

#include "IgtlProtocol.h"
#include "IgtlSocket.h"
#include "TrackerDevice.h"

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace bender
{

/// What an OpenIGTLink device counted since Open().
struct IgtlStatistics
{
  IgtlDecoderStatistics decoder;
  std::uint64_t poses = 0;          ///< tool poses decoded (any device name)
  std::uint64_t invalidPoses = 0;   ///< tracking messages refused (size, NaN, not a rotation)
  std::uint64_t unknownTypes = 0;   ///< messages of other types (IMAGE, POLYDATA, ...) skipped
  std::uint64_t buttonMessages = 0; ///< STRING messages understood as a button state
  std::uint64_t statusMessages = 0;
  std::uint64_t truncated = 0;                ///< 1 when the peer closed the connection mid-message
  std::map<std::string, std::uint64_t> names; ///< poses per device name
  std::map<std::string, std::uint64_t> skippedTypes; ///< unknown messages per type
  std::string lastStatus; ///< the last STATUS that was not OK, "" when none
};

/// A tracker reached over OpenIGTLink: a TCP client of a PLUS server, 3D Slicer or any peer
/// that sends tracking messages (`--device igtl:HOST:PORT`).
///
/// - Poses: TRANSFORM, POSITION, QTDATA and TDATA messages; the device name (or the element
///   name of QTDATA/TDATA) `toolNames[0]` is station 1 (first hand), `toolNames[1]` station 2.
///   Other names are counted (Statistics().filtered, IgtlStats().names) and, with
///   EnableNamedQueue(), handed out by TakeNamedPoses() so that a user sees what a server
///   sends.
/// - Frame: OpenIGTLink is RAS millimetres; poses are converted to LPS (x and y negated, the
///   rotation pre-multiplied by diag(-1,-1,1)). TrackerPose::time is seconds since Start()
///   (receive time, steady clock).
/// - Button: a STRING message whose device name is a hand's name and whose text is "down",
///   "pressed", "1" or "up", "released", "0" (any case, surrounding blanks ignored) sets that
///   hand's button; the new state is published at once with the hand's last pose and then
///   carried by every following pose, so grab/release events come from the PoseStore as for
///   the Fastrak. Without such messages the application uses a key instead.
/// - Robustness: header version 1 and 2 (extended header + metadata) are read; CRC errors,
///   garbage and unknown types are skipped and counted; a connection closed by the peer (also
///   in the middle of a message, which the event message says) is a Disconnected event;
///   Close() and Open() reconnect.
/// - Hostile or broken peers: the connection is dropped, with a ReadError event whose one line
///   says why ("dropped the connection: ..."), when an in-step header announces a body above
///   `maxBodyBytes` (see IgtlStreamDecoder::Refusal), when more than `maxGarbageBytes` arrive
///   without a valid message, or when bytes stay pending without completing a message for
///   `stallTimeout` (a peer trickling bytes). Between reads the decoder holds fewer than
///   58 + maxBodyBytes bytes (IgtlStreamDecoder::BufferCap; IgtlStats().decoder.peakBuffered),
///   and while decoding a read at most 64 KiB more.
///   A server that accepts and sends nothing is not dropped: it is idle, and Stop() still
///   returns within `readTimeout`.
class IgtlDevice : public TrackerDevice
{
public:
  struct Options
  {
    std::string host = "127.0.0.1";
    int port = 18944; ///< the OpenIGTLink default (PLUS and Slicer)
    std::array<std::string, 2> toolNames{ "StylusToTracker", "Stylus2ToTracker" };
    std::chrono::milliseconds connectTimeout{ 3000 };
    std::chrono::milliseconds readTimeout{ 50 };     ///< reader poll; bounds Stop()
    std::uint64_t maxBodyBytes = 64ull << 20;        ///< largest message body held (64 MiB)
    std::uint64_t maxGarbageBytes = 1ull << 20;      ///< bytes without a valid message (1 MiB)
    std::chrono::milliseconds stallTimeout{ 10000 }; ///< pending bytes with no message
  };

  /// Throws TrackingConfigurationError for an empty or over-long (> 20 characters) tool name,
  /// two equal names, or a port outside 1..65535.
  explicit IgtlDevice(Options options);
  ~IgtlDevice() override;
  IgtlDevice(const IgtlDevice&) = delete;
  IgtlDevice& operator=(const IgtlDevice&) = delete;

  std::string Name() const override
  {
    return "igtl:" + this->Opts.host + ":" + std::to_string(this->Opts.port);
  }
  /// Connects (DeviceNotFoundError when refused or unanswered within connectTimeout).
  void Open() override;
  void Start() override;
  void Stop() override;
  void Close() override;
  bool IsOpen() const override { return this->Link.IsOpen(); }
  TrackerStatistics Statistics() const override;

  IgtlStatistics IgtlStats() const;
  /// Keeps every received pose, whatever its name (LPS millimetres; station 1/2 for the two
  /// hands' names, 0 for any other name); true.
  bool EnableNamedQueue(std::size_t capacity) override;
  std::vector<NamedTrackerPose> TakeNamedPoses() override;
  /// "igtl: N messages, ...", the poses per device name (which hand, or "not a hand"), the
  /// skipped message types and the last problem.
  std::vector<std::string> SummaryLines() const override;
  /// "OpenIGTLink: names seen: ...", CRC errors, garbage bytes, skipped messages, invalid
  /// poses and the last STATUS.
  std::string CountersText() const override;

  const Options& GetOptions() const { return this->Opts; }

private:
  void ReaderLoop();
  void Handle(const IgtlMessage& message);
  /// Why the peer must be dropped now ("" when it need not); `sinceMessage`: garbage bytes
  /// since the last message, `stalled`: how long bytes have been pending without a message.
  std::string DropReason(std::uint64_t sinceMessage, std::chrono::milliseconds stalled) const;

  Options Opts;
  IgtlConnection Link;
  IgtlStreamDecoder Decoder;
  std::array<bool, 2> Buttons{};
  std::array<std::optional<TrackerPose>, 2> LastPoses;
  mutable std::mutex StatsMutex;
  IgtlStatistics Stats;
  std::uint64_t Filtered = 0;
  std::deque<NamedTrackerPose> Named;
  std::size_t NamedCapacity = 0;
};

} // namespace bender

#endif
