#ifndef TrackersPanel_h
#define TrackersPanel_h

#include <QWidget>

#include <functional>

namespace bender
{
class BenderSession;
class TrackerSession;
}
class QTimer;
class BenderView;

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;

/// The Trackers panel: which device (usb, usb:N, serial:PATH[@BAUD], replay:FILE, sim), which
/// stations the two hands hold, the motion scale, connect/disconnect, the clutch, alignment of
/// the hands onto the current ribbon, and the device's status and rates. Once attached, the panel
/// drives the tracker session itself: connect, poll at the display rate (the live warp follows
/// the hands, the widget shows their ribbon; a stylus release starts the window's release job),
/// disconnect, align.
class TrackersPanel : public QWidget
{
  Q_OBJECT
public:
  explicit TrackersPanel(QWidget* parent = nullptr);

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
  /// Connects the device as the panel says and starts polling.
  bool connectDevice();
  void disconnectDevice();
  /// One poll (the timer's; tests may call it).
  void poll();

private:
  QLineEdit* Device;
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
