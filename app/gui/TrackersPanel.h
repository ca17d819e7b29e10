#ifndef TrackersPanel_h
#define TrackersPanel_h

#include <QWidget>

#include <functional>
#include <memory>
#include <vector>

namespace bender
{
class BenderSession;
class TrackerDevice;
class TrackerSession;
}
class HandMarkers;
class SlicerSendBox;
class QTimer;
class BenderView;
class QComboBox;

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;

/// The Trackers panel: which device (usb, usb:N, serial:PATH[@BAUD], replay:FILE, sim, or an
/// OpenIGTLink server: host, port and the two tools' device names), which stations the two
/// hands hold, the motion scale, connect/disconnect, the clutch, alignment of the hands onto the
/// current ribbon, and the device's status and rates (for OpenIGTLink also the device names
/// seen, CRC errors, garbage bytes, skipped messages and the last STATUS). Once attached, the
/// panel drives the tracker session itself: connect (opened on a pool thread for OpenIGTLink,
/// USB and serial devices, so the GUI thread never waits for a host), poll at the display rate
/// (the live warp follows the hands, the widget shows their ribbon; a stylus release starts the
/// window's release job), disconnect, align. A line under the clutch says which keys press the
/// hands' button for devices that send none (G, and Space held: a foot pedal), as
/// GestureController routes them while a tracker is connected.
///
/// While connected, the 3D view shows where each hand maps now (TrackerSession::MappedHands):
/// an orange ball labelled "left hand" / "right hand", tied by a line to the ribbon end it
/// holds. Between grabs the ribbon stays while the hands move, so the balls drift away from
/// the ends; a stylus press or "Align hands to the ribbon" anchors the hands again and the
/// balls jump onto the ends (the status bar says how far they moved; nothing is bent). Align
/// is disabled, with a tooltip saying why, until a tracker is connected.
///
/// The device's lifecycle is a bender::TrackerStream (created here, opened on a pool thread
/// when live) handed to the TrackerSession; the markers are HandMarkers; "Send to Slicer" is
/// the SlicerSendBox below the tracker controls.
class TrackersPanel : public QWidget
{
  Q_OBJECT
public:
  explicit TrackersPanel(QWidget* parent = nullptr);
  ~TrackersPanel() override;

  QString deviceSpec() const;
  void setDeviceSpec(const QString& spec);
  int leftStation() const;
  int rightStation() const;
  double motionScale() const;
  void setMotionScale(double scale);
  void setConnected(bool connected);
  void setStatus(const QString& status);

  /// What the panel drives: the tracker session, the session it bends, the view (the widget
  /// shows the hands' ribbon; one frame per poll) and how a stylus release commits (the
  /// window's release job on its worker, as the G key does).
  void attach(bender::TrackerSession* trackers,
    bender::BenderSession* session,
    BenderView* view,
    std::function<bool()> release);
  /// Connects the device as the panel says and starts polling. OpenIGTLink, USB and serial
  /// devices are opened on a pool thread: true means the connection started (connectFinished
  /// tells how it ended); replay and sim connect at once (true: connected).
  bool connectDevice();
  /// Connects a device made by the caller (tests, scripts), as the panel's stations and motion
  /// scale say, and starts polling; false (with a message) when it fails or one is connected.
  bool connectWith(std::unique_ptr<bender::TrackerDevice> device);
  bool isConnecting() const { return this->Connecting; }
  void disconnectDevice();
  /// One poll (the timer's; tests may call it).
  void poll();
  /// The Align button: anchors the hands, as they are now, to the ribbon shown; the hand
  /// markers jump onto its ends. False (with a message) when not connected, without a ribbon,
  /// before both hands are seen or while grabbing.
  bool alignHands();
  QPushButton* alignButton() const { return this->AlignButton; }
  /// Whether the hand markers are drawn, and where (0 left, 1 right; model mm).
  bool handMarkersShown() const;
  bool handMarkerPosition(int hand, double position[3]) const;
  /// The session's surface, state or history changed (the window's refresh): sends to
  /// Slicer when that is on.
  void sessionChanged();
  /// Whether "Send to Slicer" is on, and the messages the sender has sent so far.
  bool isSendingToSlicer() const;
  unsigned long long slicerMessagesSent() const;

signals:
  void connectFinished(bool connected);
  /// A tracker's stylus press started a grab (in this poll), and the ribbon moved while a
  /// tracker holds it: the window's live measurements follow them as they follow the mouse.
  void trackerGrabbed();
  void trackerMoved();

private:
  void updateHandMarkers();
  void finishConnect(bool connected);
  void showCounters();

  QComboBox* Kind;
  QLineEdit* Device;
  QLineEdit* IgtlHost;
  QSpinBox* IgtlPort;
  QLineEdit* IgtlTool1;
  QLineEdit* IgtlTool2;
  QLabel* IgtlCounters;
  SlicerSendBox* Slicer;
  QTimer* CountersTimer = nullptr;
  std::unique_ptr<HandMarkers> Markers;
  bool Connecting = false;
  QSpinBox* Left;
  QSpinBox* Right;
  QDoubleSpinBox* Scale;
  QPushButton* ConnectButton;
  QPushButton* DisconnectButton;
  QPushButton* AlignButton;
  QCheckBox* Clutch;
  QLabel* Status;
  QTimer* Timer = nullptr;
  bender::TrackerSession* Trackers = nullptr;
  bender::BenderSession* Session = nullptr;
  BenderView* View = nullptr;
};

#endif
