#ifndef FileOpener_h
#define FileOpener_h

#include <QObject>
#include <QString>

namespace bender
{
class BenderSession;
class SegmentationSession;
}
class BendPanel;
class BenderView;
class GestureController;
class MainActions;
class SegmentPanel;
class WorkRunner;

/// Brings data into a window: File > Open, Open Recent, Load plan, the demo, a volume's
/// segmentation, files dropped on the window and the recovery offered at start. The kind of a
/// file is bender::ClassifyFile's (Logic); reading, segmenting, replaying and recovering run on
/// the window's worker and their results go into the sessions on the GUI thread.
class FileOpener : public QObject
{
  Q_OBJECT
public:
  FileOpener(bender::BenderSession& session,
    bender::SegmentationSession& segmentation,
    WorkRunner* worker,
    MainActions* actions,
    BenderView* view,
    GestureController* gesture,
    BendPanel* bend,
    SegmentPanel* segment,
    QWidget* window);

  /// Opens a file by its kind (see MainWindow::openFile); false when refused at once.
  bool openFile(const QString& path);
  void startDemo();
  bool segmentVolume();
  /// Asks whether to recover the autosaved session (Bender did not close cleanly).
  void offerRecovery();

signals:
  /// The volume or its mask changed (the slice views follow).
  void volumeChanged();
  /// The panel the user goes on with.
  void panelWanted(QWidget* panel);

protected:
  /// Drag and drop on the window: the first local file dropped is opened.
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  bool openMesh(const QString& path);
  bool openVolume(const QString& path);

  bender::BenderSession& Session;
  bender::SegmentationSession& Segmentation;
  WorkRunner* Worker;
  MainActions* Actions;
  BenderView* View;
  GestureController* Gesture;
  BendPanel* Bend;
  SegmentPanel* Segment;
  QWidget* Window;
};

#endif
