#ifndef AutosaveController_h
#define AutosaveController_h

#include "SegmentationSession.h"
#include "WindowParts.h"

#include <QObject>
#include <QString>

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <utility>

namespace bender
{
class AutosaveCopies;
class SessionJob;
struct SessionSnapshot;
}

/// Recovery of everything a window holds: the session autosaves (BenderSession: the surface's
/// source, its name, the warps, and the ribbon once it rests) with the window's part added by
/// fillSnapshot (BenderSession's autosave decorator): the volume (its path, series and grid;
/// a volume made here and the segmentation's mask are written beside the autosave, on a thread
/// of their own: bender::AutosaveCopies, the autosave referencing each only once it is complete
/// and autosaving again when it is), the Segment panel's parameters and the placed ribbon with
/// the Bend parameters and the handles' size. At start, when an autosave is left from a crash,
/// offerRecovery asks; recoverSession (also for a session file opened) reads the volume again
/// (checked against the recorded grid), shows the parameters in the Segment panel, recovers the
/// surface and the warps and puts the ribbon back. A volume that is missing or changed gets one
/// message; the rest is recovered.
class AutosaveController : public QObject
{
  Q_OBJECT
public:
  explicit AutosaveController(const WindowParts& parts);
  /// Waits for the copies beside the autosave that are being written.
  ~AutosaveController() override;

  /// Autosaves the session to `path` (empty: autosave.bender-session.json in the user's
  /// application data folder) with the window's part (fillSnapshot); when `offerRecovery` and
  /// an autosave is left from a crash, offers its recovery once the event loop runs.
  void startAutosave(const QString& path, bool offerRecovery);
  /// Asks whether to recover the autosaved session (Bender did not close cleanly): the dialog
  /// ("recoverSession") lists what the autosave holds. No: the autosave is discarded.
  void offerRecovery();
  /// Recovers a session file (an autosave or a saved session) on the worker: the volume, the
  /// segmentation parameters, the surface with its name, the warps and the ribbon. False when
  /// refused at once (busy, an unreadable session file: one message naming it).
  bool recoverSession(const QString& path);
  /// Adds the window's part to an autosave (see the class).
  void fillSnapshot(bender::SessionSnapshot& snapshot);
  /// Waits for the copies beside the autosave being written (closing the window, tests); then
  /// the autosave they end with is posted to the GUI thread.
  void waitForAutosaveCopies();
  /// Removes the autosave and what the window keeps beside it (the work was saved or
  /// discarded).
  void discardAutosave();
  /// Called on the copies' thread before each copy beside the autosave is written (tests).
  void setAutosaveCopyHook(std::function<void()> hook) { this->CopyHook = std::move(hook); }

signals:
  /// The volume or its mask changed (the slice views follow).
  void volumeChanged();
  /// The panel the user goes on with.
  void panelWanted(QWidget* panel);

private:
  /// Takes a recovery's results in: the volume (when it is still the session's), the
  /// parameters, the surface and warps, the ribbon; then one message for what was not.
  void finishRecovery(const bender::SessionSnapshot& snapshot,
    const bender::SegmentationSession::ReadJob* read,
    const std::string& volumeProblem,
    bender::SessionJob& recover);
  /// The path of the complete copy of `object` beside the autosave (written with `write` on
  /// the copies' thread when there is none yet); empty until then. A failed copy is said
  /// once: "Autosave: `what` is not kept (why)".
  std::string keepCopy(const std::shared_ptr<const void>& object,
    const std::string& path,
    const std::function<void(const std::string&)>& write,
    const std::string& what);

  bender::BenderSession& Session;
  bender::SegmentationSession& Segmentation;
  WorkRunner* Worker;
  BenderView* View;
  GestureController* Gesture;
  BendPanel* Bend;
  SegmentPanel* Segment;
  QWidget* Window;
  // The volume without a file and the mask, written beside the autosave (once each).
  std::unique_ptr<bender::AutosaveCopies> Copies;
  // Counts discarded autosaves: a copy finished before the last discard autosaves no more.
  std::atomic<int> CopiesGeneration{ 0 };
  std::function<void()> CopyHook;
};

#endif
