#ifndef VesselController_h
#define VesselController_h

#include "VesselSession.h"

#include <QObject>
#include <QString>

namespace bender
{
class BenderSession;
}
class BenderView;
class MainActions;
class MeasurementsPanel;
class WorkRunner;

/// The vessel side of the window: keeps bender::VesselSession's centerlines those of the
/// session's committed surface (after a load, a segmentation, a release, an undo: a job on the
/// worker's background lane, so that a release is never refused for it; not while grabbed),
/// draws them in the 3D view (MainActions::ShowCenterline), and feeds the Measurements panel:
/// the branch under the ribbon before the grab and live while bending (its centerline stretch
/// warped with the live warp), and the plan's before/after table when the committed surface's
/// centerlines arrive.
class VesselController : public QObject
{
  Q_OBJECT
public:
  VesselController(bender::BenderSession& session,
    BenderView* view,
    WorkRunner* worker,
    MainActions* actions,
    MeasurementsPanel* panel,
    QObject* parent);

  bender::VesselSession& vessels() { return this->Vessels; }
  const bender::VesselSession& vessels() const { return this->Vessels; }
  /// Starts the centerline job when the committed surface changed (the window calls it on
  /// every change of the session; cheap when up to date).
  void update();
  /// True while centerlines are being computed or are due (the surface changed).
  bool isComputing() const;
  /// For tests and scripts: waits (processing events) until the centerlines of the committed
  /// surface have been computed (or failed) and the worker is idle; false on timeout.
  bool waitForCenterlines(int milliseconds);

  ///@{ The gesture's steps (GestureController calls them)
  /// A ribbon was placed: its branch is held and measured as it is.
  void ribbonPlaced(const bender::RibbonSpec& ribbon);
  /// Grabbed: the held branch is (re)taken under the grabbed ribbon.
  void grabbed();
  /// The live warp moved: the held branch is measured through it.
  void moved();
  ///@}

  const bender::HeldBranchMeasures& heldBefore() const { return this->Before; }
  const bender::HeldBranchMeasures& heldNow() const { return this->Now; }

signals:
  /// New centerlines are shown (or the last computation failed).
  void centerlinesChanged(bool ok);

private:
  void showState();

  bender::BenderSession& Session;
  bender::VesselSession Vessels;
  BenderView* View;
  WorkRunner* Worker;
  MainActions* Actions;
  MeasurementsPanel* Panel;
  QString State = "No centerlines: open a vessel surface";
  bool LinesWarped = false; // the drawn centerline is the live warp's
  bender::HeldBranchMeasures Before;
  bender::HeldBranchMeasures Now;
};

#endif
