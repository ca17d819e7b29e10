#ifndef TrackersPanel_h
#define TrackersPanel_h

#include <QWidget>

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;

/// The Trackers panel: which device (usb, usb:N, serial:PATH[@BAUD], replay:FILE, sim), which
/// stations the two hands hold, the motion scale, connect/disconnect, the clutch, alignment of
/// the hands onto the current ribbon, and the device's status and rates.
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

signals:
  void connectRequested();
  void disconnectRequested();
  void clutchToggled(bool engaged);
  void alignRequested();

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
};

#endif
