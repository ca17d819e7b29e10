#ifndef bender_SlicerLink_h
#define bender_SlicerLink_h

#include "IgtlSender.h"
#include "WarpPlan.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

class vtkPolyData;

namespace bender
{

/// Sends surfaces and ribbon end frames to 3D Slicer (an OpenIGTLinkIF connector in server
/// mode, or any OpenIGTLink peer that listens) on a thread of its own: connects, then sends the
/// newest frame handed to it (Submit replaces a frame not yet sent, so nothing queues up). A
/// live frame goes through IgtlSender::SendSurfaceIfDue; when it is not due the thread waits
/// the rest of the interval (or for a newer frame) and tries again, so the last frame of a bend
/// is always sent. A final frame (a committed surface) is sent at once. The surface goes as
/// POLYDATA `surfaceName`, the ribbon's ends as TRANSFORMs `ribbonPrefix` + "Start"/"End".
///
/// Used by the Trackers panel's "Send to Slicer" (live, reporting its counters and errors) and
/// by `bender-cli igtl-send` (one final frame, then Finish).
class SlicerLink
{
public:
  struct Options
  {
    IgtlSender::Options sender;                ///< host, port, timeouts, live surface rate
    std::string surfaceName = "BenderVessel";  ///< POLYDATA device name, 1..20 characters
    std::string ribbonPrefix = "BenderRibbon"; ///< TRANSFORM names' prefix, at most 15
  };
  /// What to send: a surface (LPS mm) and, when there is one, the ribbon whose ends to send.
  struct Frame
  {
    IgtlSurface surface;
    std::optional<RibbonSpec> ribbon;
    bool final = false; ///< sent at once; otherwise at most sender.maxSurfaceRateHz a second
  };
  /// What the link has done so far (read from any thread).
  struct Counters
  {
    bool connected = false;
    std::uint64_t messages = 0;
    std::uint64_t bytes = 0;
    std::uint64_t surfaces = 0; ///< frames sent
  };

  /// A frame of `surface` (LPS mm; InputError naming `name` when it cannot be sent: see
  /// MakeIgtlSurface) and `ribbon`, left out when one of its end frames is degenerate.
  static std::shared_ptr<Frame> MakeFrame(vtkPolyData* surface,
    const std::string& name,
    const std::optional<RibbonSpec>& ribbon,
    bool final);

  /// Starts the thread, which connects. `onError` (may be empty) is called once, on the link's
  /// thread, with one line naming the peer and the problem when connecting or sending fails;
  /// the thread then ends.
  SlicerLink(Options options, std::function<void(std::string)> onError = nullptr);
  /// Asks the thread to stop and joins it (bounded by the connect and write timeouts).
  ~SlicerLink();
  SlicerLink(const SlicerLink&) = delete;
  SlicerLink& operator=(const SlicerLink&) = delete;

  /// Hands the newest frame to the thread; a frame not yet sent is replaced (a newer shape
  /// that replaces a final frame is final too, so it is still sent without waiting).
  void Submit(std::shared_ptr<Frame> frame);
  /// Asks the thread to stop without waiting for it (it ends on its own: see Ended).
  void RequestStop();
  /// Waits until every submitted frame is sent, then stops the thread. Throws bender::Error
  /// with the failure's line when connecting or sending failed.
  void Finish();
  /// The thread has ended (stopped or failed).
  bool Ended() const { return this->Done.load(); }
  Counters GetCounters() const;

private:
  void Loop();

  Options Opts;
  std::function<void(std::string)> OnError;
  mutable std::mutex Mutex;
  std::condition_variable Wake;
  std::shared_ptr<Frame> Pending;
  bool StopRequested = false;
  std::string Failure;
  std::atomic<bool> Connected{ false };
  std::atomic<bool> Done{ false };
  std::atomic<std::uint64_t> Messages{ 0 };
  std::atomic<std::uint64_t> Bytes{ 0 };
  std::atomic<std::uint64_t> Surfaces{ 0 };
  std::thread Thread;
};

} // namespace bender

#endif
