#ifndef SlicerSendBox_h
#define SlicerSendBox_h

#include <QGroupBox>

#include <memory>
#include <vector>

namespace bender
{
class BenderSession;
class SlicerLink;
}
class BenderView;
class QCheckBox;
class QLabel;
class QLineEdit;
class QSpinBox;
class QTimer;
class vtkObjectBase;

/// The Trackers panel's "3D Slicer (OpenIGTLink)" box: "Send to Slicer" sends the surface shown
/// (POLYDATA "BenderVessel") and the ribbon's end frames (TRANSFORMs "BenderRibbonStart" /
/// "BenderRibbonEnd") to an OpenIGTLink server (3D Slicer's OpenIGTLinkIF connector, default
/// port 18944) through a bender::SlicerLink: at once when switched on, after each change of
/// the committed surface, and during a bend at most 10 times a second (the newest shape when
/// the rate timer fires). An error shows one line in the session's messages and switches the
/// toggle off; the counters show what was sent.
class SlicerSendBox : public QGroupBox
{
  Q_OBJECT
public:
  explicit SlicerSendBox(QWidget* parent = nullptr);
  ~SlicerSendBox() override;

  /// The session whose surface is sent, and the view whose ribbon widget shows the ribbon.
  void attach(bender::BenderSession* session, BenderView* view);
  /// The session's surface, state or history changed: sends when that is on and due.
  void sessionChanged();
  bool isSending() const;
  unsigned long long messagesSent() const;

private:
  void setSending(bool on);
  void sendSnapshot(bool final);
  void showCounters();
  void pruneRetired();

  QCheckBox* SendToSlicer;
  QLineEdit* SlicerHost;
  QSpinBox* SlicerPort;
  QLabel* SlicerCounters;
  QTimer* SnapshotTimer = nullptr;
  std::unique_ptr<bender::SlicerLink> Link;
  std::vector<std::unique_ptr<bender::SlicerLink>> Retired; ///< switched off, thread ending
  unsigned LinkGeneration = 0; ///< which sender an error report belongs to
  bool SentWhileGrabbed = false;
  vtkObjectBase* SentSurface = nullptr; ///< the committed surface last sent (identity only)
  unsigned long SentSurfaceTime = 0;
  std::size_t SentHistoryPosition = 0;
  bender::BenderSession* Session = nullptr;
  BenderView* View = nullptr;
};

#endif
