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
class vtkBenderRibbonWidget;

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
/// the hands, the widget shows their ribbon), disconnect, align.
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

  /// What the panel drives. `render` draws a frame; `quietly` runs a call during which the
  /// session's changes do not render (one frame per poll).
  void attach(bender::TrackerSession* trackers,
    bender::BenderSession* session,
    vtkBenderRibbonWidget* widget,
    std::function<void()> render,
    std::function<void(const std::function<void()>&)> quietly);
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
  vtkBenderRibbonWidget* Widget = nullptr;
  std::function<void()> Render;
  std::function<void(const std::function<void()>&)> Quietly;
};

#endif
