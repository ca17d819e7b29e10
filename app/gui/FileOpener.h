#ifndef FileOpener_h
#define FileOpener_h

#include <QObject>
#include <QString>

#include "SegmentationSession.h"

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <utility>

namespace bender
{
class AutosaveCopies;
class BenderSession;
class SessionJob;
struct SessionSnapshot;
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
///
/// No lost work: Open (a mesh, a volume, a session), Demo and segmenting again ask "Save
/// changes?" (Save plan / Discard / Cancel) while the session has unsaved warps
/// (BenderSession::HasUnsavedChanges); a plan whose warps are already the last ones committed
/// is not replayed again without asking (refused with a message when not interactive). The
/// file dialogs start in the folder used last (QSettings "folders/<kind>"); File > Open takes a
/// DICOM series by any file of its folder, File > Open DICOM folder by the folder (several
/// series: the largest, and the status bar says which).
///
/// Recovery of everything: fillSnapshot adds the volume (its path, series and grid; a volume
/// made here and the segmentation's mask are written beside the autosave, on a thread of their
/// own: bender::AutosaveCopies, the autosave referencing each only once it is complete and
/// autosaving again when it is), the Segment panel's
/// parameters and the placed ribbon to every autosave (BenderSession's autosave
/// decorator); recoverSession reads the volume again (checked against the recorded grid), shows
/// the parameters in the Segment panel, recovers the surface and the warps and puts the ribbon
/// back. A volume that is missing or changed gets one message; the rest is recovered.
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
  /// Waits for the copies beside the autosave that are being written.
  ~FileOpener() override;

  /// Opens a file by its kind (see MainWindow::openFile); false when refused at once.
  bool openFile(const QString& path);
  void startDemo();
  bool segmentVolume();
  /// Asks whether to recover the autosaved session (Bender did not close cleanly): the dialog
  /// ("recoverSession") lists what the autosave holds. No: the autosave is discarded.
  void offerRecovery();
  /// Recovers a session file (an autosave or a saved session) on the worker: the volume, the
  /// segmentation parameters, the surface with its name, the warps and the ribbon. False when
  /// refused at once (busy, an unreadable session file: one message naming it).
  bool recoverSession(const QString& path);
  /// Adds the window's part to an autosave: the loaded volume (a volume without a file, the
  /// demo's, is written once beside the autosave, and so is each new mask: off the GUI thread,
  /// left out of the autosave until complete, then autosaved again), the Segment panel's
  /// parameters and the session's ribbon with the Bend parameters and the handles' size.
  void fillSnapshot(bender::SessionSnapshot& snapshot);
  /// Waits for the copies beside the autosave being written (closing the window, tests); then
  /// the autosave they end with is posted to the GUI thread.
  void waitForAutosaveCopies();
  /// Opens the DICOM series of `folder` (File > Open DICOM folder, after its dialog).
  bool openDicomFolder(const QString& folder);
  /// Removes the autosave and what the window keeps beside it (the work was saved or
  /// discarded).
  void discardAutosave();
  /// Dialogs may be shown (the window's MainWindowOptions::interactive); without, nothing is
  /// asked: unsaved work is replaced as before and a plan applied twice is refused.
  void setInteractive(bool interactive) { this->Interactive = interactive; }
  /// Called on the copies' thread before each copy beside the autosave is written (tests).
  void setAutosaveCopyHook(std::function<void()> hook) { this->CopyHook = std::move(hook); }
  bool isInteractive() const { return this->Interactive; }
  /// Before `what` (Open, Demo, Quit, ...) replaces the work: true to go on. With unsaved
  /// warps and interactive, asks Save plan (then goes on when saved) / Discard (the work counts
  /// as discarded: the autosave may go) / Cancel.
  bool confirmDiscard(const QString& what);
  /// The folder a file dialog of `kind` ("open", "plan", "recording", ...) starts in: the one
  /// used last, else the home folder; rememberFolder stores the folder of `path`.
  static QString lastFolder(const QString& kind);
  static void rememberFolder(const QString& kind, const QString& path);

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
  bool openPlan(const QString& path);
  /// Takes a recovery's results in: the volume (when it is still the session's), the
  /// parameters, the surface and warps, the ribbon; then one message for what was not.
  void finishRecovery(const bender::SessionSnapshot& snapshot,
    const bender::SegmentationSession::ReadJob* read,
    const std::string& volumeProblem,
    bender::SessionJob& recover);

  bender::BenderSession& Session;
  bender::SegmentationSession& Segmentation;
  WorkRunner* Worker;
  MainActions* Actions;
  BenderView* View;
  GestureController* Gesture;
  BendPanel* Bend;
  SegmentPanel* Segment;
  QWidget* Window;
  bool Interactive = false;
  // The volume without a file and the mask, written beside the autosave (once each).
  std::unique_ptr<bender::AutosaveCopies> Copies;
  // Counts discarded autosaves: a copy finished before the last discard autosaves no more.
  std::atomic<int> CopiesGeneration{ 0 };
  std::function<void()> CopyHook;
};

#endif
