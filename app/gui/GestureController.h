#ifndef GestureController_h
#define GestureController_h

#include "Ribbon.h"

#include <QObject>

namespace bender
{
class BenderSession;
}
class BendPanel;
class BenderView;
class MainActions;
class QLabel;
class QWidget;
class WorkRunner;

/// The bend gesture as the user does it in a window: grab, the ribbon widget's moves while
/// grabbed (the live warp), release (the commit, a job on the window's worker, the same for the
/// G key, the Grab button, Space and a tracker's stylus), cancel, "place ribbon" (P, then a
/// click on the surface) and the Bend panel's parameters.
///
/// Keys: G, P and Esc are the shared actions (application-wide shortcuts, so they work whatever
/// widget of the window has the focus, floating panels included; a text field being typed in
/// keeps its letters). Space held grabs and its release releases: an application event filter
/// takes Space for every widget of the window but text fields, and ignores key auto-repeat, so
/// one press is one grab and one release one commit.
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
  bool isPlacingRibbon() const;
  /// Sets the widget's ribbon (and moves the live warp when grabbed).
  void setRibbon(const bender::RibbonSpec& ribbon);
  /// Shows `ribbon` in the widget with handles sized for a vessel of `vesselRadius`.
  void showRibbon(const bender::RibbonSpec& ribbon, double vesselRadius);
  /// Takes the Bend panel's parameters into the session.
  void applyParameters();
  /// True while Space is held down after a grab it started.
  bool isSpaceHeld() const { return this->SpaceHeld; }

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  void onRibbonInteraction();
  bool isOurs(QObject* watched) const;

  bender::BenderSession& Session;
  BenderView* View;
  BendPanel* Bend;
  WorkRunner* Worker;
  QLabel* Status;
  QWidget* Window;
  bool SpaceHeld = false;
};

#endif
