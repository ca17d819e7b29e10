#ifndef GestureController_h
#define GestureController_h

#include "Ribbon.h"

#include <QObject>
#include <QString>

#include <memory>

namespace bender
{
class BenderSession;
struct RibbonPlacement;
class TrackerSession;
}
class BendPanel;
class BenderView;
class MainActions;
class ProblemOverlay;
class QDialog;
class QLabel;
class QPushButton;
class QTimer;
class QWidget;
class VesselController;
class WorkRunner;

/// The bend gesture as the user does it in a window: grab, the ribbon widget's moves while
/// grabbed (the live warp), release (the commit, a job on the window's worker, the same for the
/// G key, the Grab button, Space and a tracker's stylus), cancel, "place ribbon" (P, then a
/// click on the surface) and the Bend panel's parameters.
///
/// With the vessel's centerlines (setVessels), "place ribbon" takes two clicks on the vessel's
/// wall, the ribbon's start and end, and places the ribbon with its end frames on the
/// centerline (bender::PlaceRibbonOnCenterline, R from the suggested radius); a click off the
/// vessels (an aneurysm's sac) is refused with the reason in the status bar. Without
/// centerlines, one click places a straight ribbon along the surface's local axis.
///
/// Keys: G, P and Esc are the shared actions (application-wide shortcuts, so they work whatever
/// widget of the window has the focus, floating panels included; a text field being typed in
/// keeps its letters). Space held grabs and its release releases: an application event filter
/// takes Space for every widget of the window but text fields, and ignores key auto-repeat, so
/// one press is one grab and one release one commit. With a tracker connected (setTrackers),
/// G and Space press the hands' button instead (TrackerSession::PressHands): the hands bend the
/// ribbon from where it is, as a stylus press does, for devices that send no button (PLUS) and
/// foot pedals that send Space.
///
/// The commit guard: when the session holds a release (BenderSession::IsCommitHeld: flipped or
/// crossing triangles, or R >= r_min), the problem triangles are drawn over the surface
/// (ProblemOverlay) and a non-modal dialog ("commitGuard") offers: reduce R and retry, cancel
/// the bend, keep the warp. The ribbon widget always shows the session's ribbon when nothing is
/// grabbed: back where it was after a cancel or an undo, the final one after a release or redo.
class GestureController : public QObject
{
  Q_OBJECT
public:
  /// `window` is the top-level widget whose keys are watched; `status` shows hints.
  GestureController(bender::BenderSession& session,
    BenderView* view,
    BendPanel* bend,
    WorkRunner* worker,
    MainActions* actions,
    QLabel* status,
    QWidget* window);
  ~GestureController() override;

  bool grab();
  /// Starts the commit on the worker; false when nothing is grabbed or the worker is busy.
  bool release();
  /// Places a straight ribbon along the vessel at a model point, R from the local radius.
  bool placeRibbonAt(const double point[3]);
  /// Places the ribbon on the centerline between two picks on the wall; false, with the reason
  /// as an error message, without centerlines or for a pick off the vessels.
  bool placeRibbonOnCenterline(const double first[3], const double second[3]);
  /// The vessel side (centerlines, measurements); may be null.
  void setVessels(VesselController* vessels) { this->Vessels = vessels; }
  /// The window's trackers: while one is connected, grab() and release() are the hands'.
  void setTrackers(bender::TrackerSession* trackers) { this->Trackers = trackers; }
  /// True after the first of the two clicks of "place ribbon" on a centerline.
  bool hasFirstPick() const { return this->HasFirstPick; }
  bool isPlacingRibbon() const;
  /// Sets the widget's ribbon (and moves the live warp when grabbed).
  void setRibbon(const bender::RibbonSpec& ribbon);
  /// Shows `ribbon` in the widget with handles sized for a vessel of `vesselRadius`.
  void showRibbon(const bender::RibbonSpec& ribbon, double vesselRadius);
  /// The same with the Bend panel's R and decay set to `radius` and `decay` (and taken into
  /// the session); `vesselRadius` <= 0 (unknown) keeps the handles' size.
  void showRibbon(const bender::RibbonSpec& ribbon,
    double radius,
    const bender::DecaySpec& decay,
    double vesselRadius);
  /// Takes the Bend panel's parameters into the session.
  void applyParameters();
  /// True while Space is held down after a grab it started.
  bool isSpaceHeld() const { return this->SpaceHeld; }
  /// Dialogs may be shown (the window's MainWindowOptions::interactive); the guard's dialog
  /// is non-modal and shown either way.
  void setInteractive(bool interactive) { this->Interactive = interactive; }
  /// The commit guard's dialog and overlay (for tests): null / hidden when nothing is held.
  QDialog* commitGuardDialog() const { return this->GuardDialog; }
  ProblemOverlay* problemOverlay() const { return this->Overlay.get(); }
  /// The guard's choices, as its buttons do them. reduceRadiusAndRetry searches, on the
  /// worker, the largest R below the held one and not below the vessel's radius whose warp
  /// passes the same checks (bender::FindPassingRadius: both guards), sets it and releases
  /// again; when none passes, R stays and the commit stays held. Cancel puts back the R that
  /// "Reduce R" changed.
  bool reduceRadiusAndRetry();
  /// The floor of "Reduce R": the vessel's radius where the ribbon was placed (or, without a
  /// placement, the held branch's minimal radius before the bend); 0 when unknown.
  double vesselRadius() const;
  void cancelHeld();
  bool keepHeld();
  /// Puts the widget's ribbon back to the session's ribbon (nothing grabbed).
  void showSessionRibbon();
  /// The window calls this after every change of the session: the Bend panel shows it, the
  /// status bar's space-inversion warning quotes the r_min of now, and a ribbon placed (or put
  /// back by undo, cancel, redo: no warp, so no autosave of its own) is autosaved by the
  /// session (BenderSession::AutosaveRibbon) once it has rested for half a second, not on every
  /// move of a handle (each autosave is flushed to disk).
  void sessionChanged();

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  /// "Place ribbon" on (the next clicks on the surface place it) or off; the first of two
  /// clicks is forgotten either way.
  void setPlacing(bool on);
  void onRibbonInteraction();
  void onPick(const double point[3]);
  /// Shows a placed ribbon with the Bend parameters it suggests (R, a plateau holding the
  /// vessel's cross-section), tells the vessel side, and says where it went: `where` is "on
  /// the centerline (inscribed radius" or "along the vessel (local radius".
  void placeSettled(const bender::RibbonPlacement& placement, const QString& where);
  bool isOurs(QObject* watched) const;
  void showCommitGuard();
  void hideCommitGuard();

  bender::BenderSession& Session;
  BenderView* View;
  BendPanel* Bend;
  WorkRunner* Worker;
  QLabel* Status;
  QWidget* Window;
  bool SpaceHeld = false;
  VesselController* Vessels = nullptr;
  bender::TrackerSession* Trackers = nullptr;
  bool HasFirstPick = false;
  double FirstPick[3] = { 0, 0, 0 };
  bool Interactive = false;
  std::unique_ptr<ProblemOverlay> Overlay;
  QDialog* GuardDialog = nullptr;
  QLabel* GuardText = nullptr;
  QTimer* RibbonRest = nullptr;
  double PlacedVesselRadius = 0.0; // the placement's inscribed (or local) radius
  double RadiusBeforeReduce = 0.0; // R before "Reduce R" changed it in this grab (0: it did not)
};

#endif
