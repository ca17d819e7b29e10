#ifndef bender_TrackerSession_h
#define bender_TrackerSession_h

#include "RibbonEndMapping.h"
#include "TrackerCalibration.h"
#include "TrackerDeviceRegistry.h"
#include "TrackerStatistics.h"
#include "TwoHandRibbonInput.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace bender
{

class BenderSession;

/// Bending with trackers: a tracker device (Fastrak over USB or serial, a replayed recording,
/// the simulator) and the two-hand mapping drive a BenderSession. The stylus button grabs and
/// releases (or, for devices without buttons, PressHands/ReleaseHands: a key or a foot pedal);
/// while grabbed the final ribbon follows the hands. When the device fails mid-warp
/// (disconnected, read error, end of a replay) the live warp is cancelled, the last committed
/// shape stays and the session gets a warning message.
///
/// The mapping is relative as soon as the session has a ribbon (BenderSession::GetRibbon, the
/// one on screen): on connect, and whenever the session's ribbon changes between grabs (placed,
/// released, cancelled, undone), the hands are anchored to it (TwoHandRibbonInput::AnchorTo),
/// so connecting moves nothing; the ribbon stays between grabs, and while the stylus is held it
/// moves by the hands' displacements (with the motion scale, automatic by default) in the
/// ribbon's own frame. Without a ribbon the hands map absolutely through the calibration.
///
/// Not thread-safe: Poll() is called from the thread that owns the session (a GUI timer at the
/// display rate); the device's own reader thread only fills its pose store.
class TrackerSession
{
public:
  explicit TrackerSession(BenderSession& session);
  ~TrackerSession();
  TrackerSession(const TrackerSession&) = delete;
  TrackerSession& operator=(const TrackerSession&) = delete;

  /// Opens and starts the device named by `deviceSpec` (usb, usb:N, serial:PATH[@BAUD],
  /// replay:FILE, sim). False with a message naming the device on failure.
  bool Connect(const std::string& deviceSpec,
    const TrackerDeviceOptions& options = {},
    const HandMapping& hands = {},
    const TrackerCalibration& calibration = {});
  /// Same with a device made by the caller (tests, custom devices, TrackerStream::TakeDevice);
  /// takes ownership. A device that is already open (TrackerStream::Open) is only started.
  bool Connect(std::unique_ptr<TrackerDevice> device,
    const HandMapping& hands = {},
    const TrackerCalibration& calibration = {});
  /// The connected device (its own counters: TrackerDevice::CountersText); null when not
  /// connected.
  const TrackerDevice* GetDevice() const { return this->Device.get(); }
  /// Stops and closes; a live warp is cancelled.
  void Disconnect();
  bool IsConnected() const { return this->Device != nullptr; }

  /// What one Poll did.
  struct PollResult
  {
    bool moved = false;    ///< the final ribbon was moved (while grabbed)
    bool grabbed = false;  ///< a grab started
    bool released = false; ///< a warp was committed
    bool cancelled = false;
    bool ended = false; ///< the device stopped (failure or end of a replay); disconnected
  };
  /// Takes the device's latest poses and events and drives the session.
  PollResult Poll();

  /// The hands' button pressed from the keyboard or a foot pedal, for devices that send no
  /// button (an OpenIGTLink server without STRING messages, PLUS's default): grabs with the
  /// hands as a press of the left hand's stylus does (the hands are anchored to the ribbon as
  /// it is, then move it). False, with a message, when not connected, before both hands are
  /// seen, or while a grab is under way.
  bool PressHands();
  /// Lets go of the button PressHands pressed: commits as a stylus release does (through the
  /// release handler). False when PressHands holds nothing.
  bool ReleaseHands();
  /// Whether PressHands holds the hands now (until ReleaseHands, a cancel or a disconnect).
  bool HandsPressed() const;

  /// How a stylus release commits: by default BenderSession::Release() at once; a window sets a
  /// handler that starts the release job on its worker (as its G key does) and returns whether
  /// it started (PollResult::released then means "the commit started").
  void SetReleaseHandler(std::function<bool()> handler)
  {
    this->ReleaseHandler = std::move(handler);
  }

  /// The ribbon the hands hold now (model space), if both hands have been seen.
  std::optional<RibbonSpec> CurrentRibbon() const;
  /// Where the hands map now (model space), whether or not the stylus is held: the left hand's
  /// end as `start`, the right hand's as `end`, from the device's newest poses. Anchored
  /// (relative mapping): the anchored ribbon end moved and turned by the hand's motion since
  /// the anchor (RelativeRibbonEnd), so between grabs it drifts away from the ribbon as the
  /// hands move while the ribbon stays; right after an anchoring (connect, a stylus press,
  /// AlignTo) it is the ribbon's ends. Absolute: through the calibration (RibbonEndFromPose).
  /// While grabbing it is the ribbon being bent. Empty when not connected, before both hands
  /// are seen, or anchored to a ribbon the hands have not been seen holding yet.
  std::optional<RibbonSpec> MappedHands() const;
  /// Motion scale of the relative mapping: > 0 model mm per hand mm, 0 automatic (the hands'
  /// span is the ribbon's length). False, with a message, outside [0, 1000].
  bool SetRelativeScale(double scale);
  double GetRelativeScale() const { return this->RelativeScale; }
  /// Whether the hands are anchored to a ribbon (relative mapping).
  bool IsRelative() const { return this->Input && this->Input->IsRelative(); }
  /// The clutch: the ribbon stays while the hands move freely (re-anchors on release).
  void SetClutch(bool engaged);
  bool ClutchEngaged() const { return this->Input && this->Input->ClutchEngaged(); }
  /// The calibration in use (identity when not connected).
  TrackerCalibration GetCalibration() const;
  /// Replaces the calibration (alignment and motion scale); refused while grabbing.
  bool SetCalibration(const TrackerCalibration& calibration);
  /// Anchors the hands to a ribbon in model space (e.g. the one on screen) as they are now
  /// (the device's newest poses): the ribbon shown becomes `target`, the left hand holds its
  /// start and the right hand its end, the direction between the hands is the ribbon's
  /// direction and the left hand's normal its start normal (the relative mapping; see
  /// RibbonAnchor). Afterwards MappedHands() is `target`'s ends; the message says how far each
  /// hand's mapped point moved onto its end. Nothing is warped. False (with a message) when
  /// not connected, the hands are not both seen or a grab is under way.
  bool AlignTo(const RibbonSpec& target);

  /// Device name and per-station rates for the Trackers panel.
  std::string StatusText() const;
  TrackerStatistics Statistics() const;

private:
  void Fail(const std::string& reason);
  void SyncRibbon();
  /// The device's newest poses of both hands into the input.
  void RefreshHands();
  /// What a gesture of the input does to the session.
  void Apply(const TwoHandRibbonInput::Gesture& gesture, PollResult& result);

  BenderSession& Session;
  std::unique_ptr<TrackerDevice> Device;
  std::unique_ptr<TwoHandRibbonInput> Input;
  std::string DeviceName;
  std::function<bool()> ReleaseHandler;
  std::optional<RibbonSpec> Synced; // the session's ribbon the hands were last anchored to
  double RelativeScale = 0.0;
  bool KeyPressed = false; // PressHands holds the hands
};

} // namespace bender

#endif
