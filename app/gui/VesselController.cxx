#include "VesselController.h"

#include "BenderSession.h"
#include "BenderView.h"
#include "MainActions.h"
#include "MeasurementsPanel.h"
#include "WorkRunner.h"

#include <QAction>

VesselController::VesselController(bender::BenderSession& session,
  BenderView* view,
  WorkRunner* worker,
  MainActions* actions,
  MeasurementsPanel* panel,
  QObject* parent)
  : QObject(parent)
  , Session(session)
  , View(view)
  , Worker(worker)
  , Actions(actions)
  , Panel(panel)
{
  connect(actions->ShowCenterline,
    &QAction::toggled,
    this,
    [this](bool shown) { this->View->setCenterlinesVisible(shown); });
  this->showState();
}

bool VesselController::isComputing() const
{
  return this->Worker->isBackgroundBusy() ||
    (this->Session.HasSurface() && !this->Vessels.IsUpToDate(this->Session));
}

bool VesselController::waitForCenterlines(int milliseconds)
{
  // update() starts the job: also after a change that came without one.
  return this->Worker->waitUntilIdle(milliseconds,
    [this]()
    {
      this->update();
      return this->isComputing();
    });
}

void VesselController::update()
{
  if (this->LinesWarped && this->Session.GetState() != bender::GrabState::Grabbed &&
    this->Vessels.IsUpToDate(this->Session))
  {
    // The bend was cancelled: the committed surface's centerline again.
    this->LinesWarped = false;
    this->View->setCenterlines(this->Vessels.GetPaths());
  }
  if (this->Worker->isBackgroundBusy() || this->Vessels.IsUpToDate(this->Session) ||
    this->Session.GetState() == bender::GrabState::Grabbed)
  {
    return;
  }
  std::shared_ptr<bender::CenterlineJob> job = this->Vessels.BeginCenterlines(this->Session);
  if (!this->Vessels.HasCenterlines())
  {
    this->View->setCenterlines(nullptr); // those of another surface
  }
  if (!this->Vessels.IsHolding())
  {
    // Another surface: the last bend's measures are not this one's.
    this->Before = {};
    this->Now = {};
  }
  if (!job)
  {
    this->State = "No centerlines: open a vessel surface";
    this->View->setCenterlines(nullptr);
    this->showState();
    return;
  }
  this->State = "Computing the centerlines...";
  this->showState();
  this->Worker->runInBackground(
    [this, job](const bender::ProgressReporter& progress) -> WorkRunner::Finisher
    {
      job->Run(progress);
      return [this, job]()
      {
        std::string message;
        const bool ok = this->Vessels.Finish(*job, message);
        this->State = QString::fromStdString(message);
        this->LinesWarped = false;
        this->View->setCenterlines(ok ? this->Vessels.GetPaths() : nullptr);
        this->showState();
        emit this->centerlinesChanged(ok);
        // The surface may have changed meanwhile (a release, an undo): its turn now.
        this->update();
      };
    },
    [this](const std::string& what)
    {
      this->State = QString::fromStdString("Centerlines: " + what);
      this->showState();
      emit this->centerlinesChanged(false);
    });
}

void VesselController::showState()
{
  this->Panel->showState(this->Vessels, this->State);
  this->Panel->showHeld(this->Before, this->Now);
}

void VesselController::ribbonPlaced(const bender::RibbonSpec& ribbon)
{
  this->Before = {};
  this->Now = {};
  if (this->Vessels.HoldBranch(ribbon, this->Session.GetSurface()))
  {
    this->Before = this->Vessels.MeasureHeld();
  }
  this->Panel->showHeld(this->Before, this->Now);
}

void VesselController::grabbed()
{
  this->ribbonPlaced(this->Session.GetInitialRibbon());
  this->Now = this->Before;
  this->Panel->showHeld(this->Before, this->Now);
}

void VesselController::moved()
{
  if (this->Session.GetState() != bender::GrabState::Grabbed || !this->Vessels.HasCenterlines())
  {
    return;
  }
  const bender::WarpSpec warp = bender::LiveWarpOf(this->Session);
  // The drawn centerline follows the surface (the widget's interaction draws the frame).
  if (auto lines = this->Vessels.WarpedPaths(warp))
  {
    this->View->moveCenterlines(lines);
    this->LinesWarped = true;
  }
  const bender::HeldBranchMeasures live = this->Vessels.MeasureHeld(warp);
  if (live.valid && this->Vessels.IsHolding())
  {
    this->Now = live;
  }
  this->Panel->showHeld(this->Before, this->Now);
}
