#include "GestureController.h"

#include "BendPanel.h"
#include "BenderSession.h"
#include "BenderView.h"
#include "MainActions.h"
#include "ProblemOverlay.h"
#include "RadiusSearch.h"
#include "RibbonPlacement.h"
#include "TrackerSession.h"
#include "VesselController.h"
#include "VesselSession.h"
#include "WorkRunner.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAbstractSpinBox>
#include <QAction>
#include <QApplication>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QKeyEvent>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QTextEdit>
#include <QTimer>
#include <QVBoxLayout>

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <exception>

namespace
{
/// A widget the user types text into: its keys are its own.
bool IsTextField(QObject* object)
{
  return qobject_cast<QLineEdit*>(object) || qobject_cast<QAbstractSpinBox*>(object) ||
    qobject_cast<QTextEdit*>(object) || qobject_cast<QPlainTextEdit*>(object);
}
}

GestureController::GestureController(bender::BenderSession& session,
  BenderView* view,
  BendPanel* bend,
  WorkRunner* worker,
  MainActions* actions,
  QLabel* status,
  QWidget* window)
  : QObject(window)
  , Session(session)
  , View(view)
  , Bend(bend)
  , Worker(worker)
  , Status(status)
  , Window(window)
{
  this->RibbonRest = new QTimer(this);
  this->RibbonRest->setSingleShot(true);
  this->RibbonRest->setInterval(500);
  connect(this->RibbonRest, &QTimer::timeout, this, [this]() { this->Session.AutosaveRibbon(); });
  connect(actions->PlaceRibbon,
    &QAction::triggered,
    this,
    [this]()
    {
      this->setPlacing(true);
      this->Status->setStyleSheet("");
      if (this->Vessels && this->Vessels->vessels().HasCenterlines())
      {
        this->Status->setText("Click on the vessel where the ribbon starts, then where it ends: "
                              "the ribbon goes on the centerline (Esc cancels)");
      }
      else
      {
        this->Status->setText("Click on the vessel to place the ribbon along it (Esc cancels)");
      }
    });
  connect(actions->Grab,
    &QAction::triggered,
    this,
    [this]()
    {
      if (this->Session.GetState() == bender::GrabState::Grabbed)
        this->release();
      else
        this->grab();
    });
  connect(actions->CancelBend,
    &QAction::triggered,
    this,
    [this]()
    {
      this->setPlacing(false);
      this->cancelHeld();
    });
  // After an undo or a redo (the window's handlers run first) the ribbon lies on the surface.
  for (QAction* history : { actions->Undo, actions->Redo })
  {
    connect(history,
      &QAction::triggered,
      this,
      [this]() { QTimer::singleShot(0, this, &GestureController::showSessionRibbon); });
  }
  connect(
    this->View, &BenderView::ribbonInteraction, this, &GestureController::onRibbonInteraction);
  connect(this->View,
    &BenderView::surfacePicked,
    this,
    [this](double x, double y, double z)
    {
      const double point[3] = { x, y, z };
      this->onPick(point);
    });
  connect(this->View,
    &BenderView::pickMissed,
    this,
    [this]()
    {
      this->Session.AddMessage(
        bender::MessageSeverity::Warning, "Place ribbon: click on the surface");
    });
  connect(this->Bend, &BendPanel::parametersChanged, this, &GestureController::applyParameters);
  qApp->installEventFilter(this);
  // Big surfaces: the view draws the session's decimated copy while it is dragged (and while
  // the camera rotates), with the session's threshold.
  this->View->setLevelOfDetailThreshold(this->Session.GetLevelOfDetailThreshold());
  this->View->setLevelOfDetail(
    this->Session.GetProxyOutputPort(), [this]() { return this->Session.IsDraggingProxy(); });
  // The ghost of the original: only where the surface may differ from it.
  this->View->setOriginalInPlay([this]() { return this->Session.GetOriginalInPlay(); });

  this->Overlay =
    std::make_unique<ProblemOverlay>(this->View->renderer(), this->View->ribbonRenderer());
  // The lumen guard as the Bend panel sets it (on at 5 % unless changed).
  this->Session.SetLumenGuard(this->Bend->lumenGuard());
  connect(this->Bend,
    &BendPanel::lumenGuardChanged,
    this,
    [this]() { this->Session.SetLumenGuard(this->Bend->lumenGuard()); });
  this->GuardDialog = new QDialog(window);
  this->GuardDialog->setObjectName("commitGuard");
  this->GuardDialog->setWindowTitle("Commit held: check the bend");
  this->GuardDialog->setModal(false);
  auto* layout = new QVBoxLayout(this->GuardDialog);
  this->GuardText = new QLabel(this->GuardDialog);
  this->GuardText->setObjectName("commitGuardText");
  this->GuardText->setWordWrap(true);
  this->GuardText->setMinimumWidth(380);
  layout->addWidget(this->GuardText);
  auto* buttons = new QDialogButtonBox(this->GuardDialog);
  auto* reduce = buttons->addButton("Reduce R and retry", QDialogButtonBox::AcceptRole);
  reduce->setObjectName("guardReduce");
  reduce->setToolTip("The largest smaller region of influence, never below the vessel's "
                     "radius, whose bend passes the same checks; found by trying, then "
                     "released");
  auto* cancel = buttons->addButton("Cancel the bend", QDialogButtonBox::RejectRole);
  cancel->setObjectName("guardCancel");
  cancel->setToolTip("Nothing is committed; the surface and the ribbon go back (Esc)");
  auto* keep = buttons->addButton("Keep the warp", QDialogButtonBox::DestructiveRole);
  keep->setObjectName("guardKeep");
  keep->setToolTip("Commit the warp as it is, with the problems shown (undo with Ctrl+Z)");
  layout->addWidget(buttons);
  connect(reduce, &QPushButton::clicked, this, &GestureController::reduceRadiusAndRetry);
  connect(cancel, &QPushButton::clicked, this, &GestureController::cancelHeld);
  connect(keep, &QPushButton::clicked, this, &GestureController::keepHeld);
  // Closing the dialog is no choice: the commit stays held (the bend goes on).
  connect(this->GuardDialog, &QDialog::rejected, this, [this]() { this->Overlay->Hide(); });
}

GestureController::~GestureController()
{
  qApp->removeEventFilter(this);
}

void GestureController::setPlacing(bool on)
{
  this->View->setPicking(on);
  this->HasFirstPick = false;
  this->Bend->showState(this->Session, on);
}

bool GestureController::isPlacingRibbon() const
{
  return this->View->isPicking();
}

bool GestureController::grab()
{
  if (this->Trackers && this->Trackers->IsConnected())
  {
    // The hands hold the ribbon: the key is their button.
    if (!this->Trackers->PressHands())
    {
      return false;
    }
    if (this->Vessels)
    {
      this->Vessels->grabbed();
    }
    return true;
  }
  auto* widget = this->View->ribbonWidget();
  auto* rep = widget->GetRibbonRepresentation();
  if (!widget->GetEnabled() || !rep->GetValid())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      widget->GetEnabled() ? "Grab refused: the ribbon is invalid (" + rep->GetLastError() + ")"
                           : "Grab: place the ribbon first (P, then click on the vessel)");
    return false;
  }
  if (!this->Session.Grab(rep->GetRibbon()))
  {
    return false;
  }
  this->RadiusBeforeReduce = 0.0;
  if (this->Vessels)
  {
    this->Vessels->grabbed();
  }
  return true;
}

bool GestureController::release()
{
  if (this->Trackers && this->Trackers->HandsPressed())
  {
    // The hands let go: the stylus release's path, which commits through release() again.
    return this->Trackers->ReleaseHands();
  }
  if (this->Session.GetState() != bender::GrabState::Grabbed ||
    this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  return this->Worker->runSessionJob(this->Session,
    this->Session.BeginRelease(),
    [this](bender::SessionJob&, bool ok)
    {
      if (ok)
      {
        // The ribbon stays where the hands left it: the committed (final) ribbon.
        this->hideCommitGuard();
        this->View->ribbonWidget()->GetRibbonRepresentation()->SetRibbon(
          this->Session.GetFinalRibbon());
      }
      else if (this->Session.IsCommitHeld())
      {
        this->showCommitGuard();
      }
      else
      {
        this->hideCommitGuard();
        this->showSessionRibbon();
      }
      this->View->render();
    });
}

void GestureController::showCommitGuard()
{
  const bender::CommitCheck& check = this->Session.GetHeldCheck();
  QString text = "<b>The bend was not committed.</b> The check of the region it changed found:<ul>";
  for (const std::string& problem : check.problems)
  {
    text += "<li>" + QString::fromStdString(problem).toHtmlEscaped() + "</li>";
  }
  text += "</ul>";
  if (!check.problemCells.empty())
  {
    text += QString("The %1 triangles concerned are drawn in yellow and red on the vessel.<br>")
              .arg(check.problemCells.size());
  }
  const bender::LumenCheck& lumen = check.lumen;
  const bender::BranchLumenChange* narrowed =
    lumen.worst >= 0 && lumen.branches[static_cast<std::size_t>(lumen.worst)].tooNarrow
    ? &lumen.branches[static_cast<std::size_t>(lumen.worst)]
    : nullptr;
  if (narrowed)
  {
    text += "The branch's narrowest point is marked in magenta on the vessel.<br>";
  }
  const double rmin = check.minimumRadius;
  text += QString("R = %1 mm, r_min = %2.")
            .arg(check.radius, 0, 'f', 2)
            .arg(std::isfinite(rmin) && rmin < 1e6 ? QString("%1 mm").arg(rmin, 0, 'f', 2)
                                                   : QString("none (straight wire)"));
  this->GuardText->setText(text);
  this->Overlay->Show(check.problemTriangles);
  if (narrowed)
  {
    this->Overlay->ShowNarrowing(narrowed->narrowest.data(),
      narrowed->afterMinRadius,
      QString("-%1 %: %2 -> %3 mm")
        .arg(100.0 * narrowed->narrowing, 0, 'f', 1)
        .arg(narrowed->beforeMinRadius, 0, 'f', 2)
        .arg(narrowed->afterMinRadius, 0, 'f', 2)
        .toStdString());
  }
  this->GuardDialog->show();
  this->GuardDialog->raise();
  this->View->render();
}

void GestureController::hideCommitGuard()
{
  this->Overlay->Hide();
  this->GuardDialog->hide();
}

bool GestureController::reduceRadiusAndRetry()
{
  if (this->Session.GetState() != bender::GrabState::Grabbed)
  {
    this->hideCommitGuard();
    return false;
  }
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  const double radius = this->Session.GetParameters().radius;
  const double lowest = this->vesselRadius();
  if (!(lowest > 0.0))
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      "Reduce R: the vessel's radius is unknown (place the ribbon on the vessel with P); R "
      "stays");
    return false;
  }
  bender::RadiusSearchOptions options;
  options.lowest = lowest;
  options.step = 0.01; // the Bend panel sets R to 0.01 mm
  options.check.spaceInversionRule = this->Session.GetCommitGuardRule();
  options.check.lumen = this->Session.GetLumenGuard();
  options.lumenBefore = this->Session.LumenBaselineOf(this->Session.GetSurface());
  vtkSmartPointer<vtkPolyData> surface = vtkSmartPointer<vtkPolyData>::New();
  surface->DeepCopy(this->Session.GetSurface());
  const bender::WarpSpec warp = bender::LiveWarpOf(this->Session);
  this->hideCommitGuard();
  return this->Worker->runReporting(this->Session,
    "Searching for an R that passes",
    [this, surface, warp, options, radius, lowest](
      const bender::ProgressReporter& progress) -> WorkRunner::Finisher
    {
      bender::RadiusSearchOptions search = options;
      search.progress = progress;
      const bender::RadiusSearchResult result = bender::FindPassingRadius(surface, warp, search);
      return [this, result, radius, lowest]()
      {
        if (this->Session.GetState() != bender::GrabState::Grabbed)
        {
          return;
        }
        if (!result.found)
        {
          this->Session.AddMessage(bender::MessageSeverity::Warning,
            QString("Reduce R: no R from %1 down to the vessel's radius %2 mm passes the "
                    "checks (%3); R stays: cancel the bend, change it, or keep it")
              .arg(radius, 0, 'f', 2)
              .arg(lowest, 0, 'f', 2)
              .arg(QString::fromStdString(result.check.Summary()))
              .toStdString());
          if (this->Session.IsCommitHeld())
          {
            this->showCommitGuard();
          }
          return;
        }
        if (this->RadiusBeforeReduce <= 0.0)
        {
          this->RadiusBeforeReduce = radius;
        }
        bender::WarpParameters parameters = this->Bend->parameters();
        parameters.radius = result.radius;
        this->Bend->setParameters(parameters);
        this->applyParameters();
        this->Session.AddMessage(bender::MessageSeverity::Info,
          QString("R reduced from %1 to %2 mm, the largest that passes the checks; releasing")
            .arg(radius, 0, 'f', 2)
            .arg(result.radius, 0, 'f', 2)
            .toStdString());
        // The worker is still finishing this job: the release starts right after.
        QTimer::singleShot(0, this, [this]() { this->release(); });
      };
    });
}

double GestureController::vesselRadius() const
{
  if (this->PlacedVesselRadius > 0.0)
  {
    return this->PlacedVesselRadius;
  }
  const bender::LumenCheck& lumen = this->Session.GetHeldCheck().lumen;
  double smallest = 0.0;
  for (const bender::BranchLumenChange& branch : lumen.branches)
  {
    if (branch.moved && (smallest == 0.0 || branch.beforeMinRadius < smallest))
    {
      smallest = branch.beforeMinRadius;
    }
  }
  return smallest;
}

void GestureController::cancelHeld()
{
  this->hideCommitGuard();
  const bool grabbed = this->Session.GetState() == bender::GrabState::Grabbed;
  this->Session.CancelGrab("cancelled by the user");
  if (grabbed && this->RadiusBeforeReduce > 0.0)
  {
    // Nothing of the bend stays, the R that "Reduce R" set included.
    bender::WarpParameters parameters = this->Bend->parameters();
    parameters.radius = this->RadiusBeforeReduce;
    this->Bend->setParameters(parameters);
    this->applyParameters();
  }
  this->RadiusBeforeReduce = 0.0;
  this->showSessionRibbon();
}

bool GestureController::keepHeld()
{
  this->hideCommitGuard();
  if (!this->Session.KeepHeldCommit())
  {
    return false;
  }
  this->View->ribbonWidget()->GetRibbonRepresentation()->SetRibbon(this->Session.GetFinalRibbon());
  this->View->render();
  return true;
}

void GestureController::sessionChanged()
{
  // The status bar's space-inversion warning quotes the session's r_min as it is now (the Bend
  // panel's), not as it was when the warning was first given in this grab.
  const QString inversionPrefix = "space inversion possible";
  if (this->Status->text().startsWith(inversionPrefix) && this->Session.GetSpaceInversionRisk())
  {
    const QString now = QString::fromStdString(this->Session.GetSpaceInversionWarning());
    if (now != this->Status->text())
    {
      this->Status->setText(now);
      this->Status->setToolTip(now);
    }
  }
  this->Bend->showState(this->Session, this->isPlacingRibbon());
  if (this->Session.HasUnsavedRibbon())
  {
    this->RibbonRest->start();
  }
}

void GestureController::showSessionRibbon()
{
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    return;
  }
  auto* widget = this->View->ribbonWidget();
  const auto& ribbon = this->Session.GetRibbon();
  if (ribbon && widget->GetEnabled())
  {
    widget->GetRibbonRepresentation()->SetRibbon(*ribbon);
  }
  this->View->render();
}

void GestureController::showRibbon(const bender::RibbonSpec& ribbon, double vesselRadius)
{
  this->PlacedVesselRadius = vesselRadius;
  auto* rep = this->View->ribbonWidget()->GetRibbonRepresentation();
  rep->SetHandleLength(1.2 * vesselRadius);
  rep->SetHandleRadius(0.22 * vesselRadius);
  rep->SetStripWidth(0.3 * vesselRadius);
  this->setRibbon(ribbon);
  this->View->ribbonWidget()->On();
}

void GestureController::showRibbon(const bender::RibbonSpec& ribbon,
  double radius,
  const bender::DecaySpec& decay,
  double vesselRadius)
{
  bender::WarpParameters parameters = this->Bend->parameters();
  parameters.radius = radius;
  parameters.decay = decay;
  this->Bend->setParameters(parameters);
  this->applyParameters();
  if (vesselRadius > 0.0)
  {
    this->showRibbon(ribbon, vesselRadius);
  }
  else
  {
    this->PlacedVesselRadius = 0.0;
    this->setRibbon(ribbon);
    this->View->ribbonWidget()->On();
  }
}

void GestureController::onPick(const double point[3])
{
  if (!this->Vessels || !this->Vessels->vessels().HasCenterlines())
  {
    this->placeRibbonAt(point);
    return;
  }
  const bender::Vec3 picked{ point[0], point[1], point[2] };
  if (!this->Vessels->vessels().IsOnVessel(picked))
  {
    // Still picking: the user clicks again, on the vessel.
    this->Session.AddMessage(bender::MessageSeverity::Error,
      "Place ribbon: that click is not on a vessel (an aneurysm's sac or a bulge has no "
      "centerline): click on the vessel's wall");
    return;
  }
  if (!this->HasFirstPick)
  {
    std::copy(point, point + 3, this->FirstPick);
    this->HasFirstPick = true;
    this->Status->setStyleSheet("");
    this->Status->setText("Now click on the vessel where the ribbon ends (Esc cancels)");
    return;
  }
  if (!this->placeRibbonOnCenterline(this->FirstPick, point))
  {
    this->setPlacing(true); // try again from the first click
  }
}

bool GestureController::placeRibbonOnCenterline(const double first[3], const double second[3])
{
  this->setPlacing(false);
  if (!this->Vessels)
  {
    this->Session.AddMessage(
      bender::MessageSeverity::Error, "Place ribbon on the centerline: no centerlines");
    return false;
  }
  try
  {
    const bender::RibbonPlacement placement = this->Vessels->vessels().PlaceRibbon(
      { first[0], first[1], first[2] }, { second[0], second[1], second[2] });
    this->placeSettled(placement, "on the centerline (inscribed radius");
    return true;
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(
      bender::MessageSeverity::Error, std::string("Place ribbon: ") + e.what());
    return false;
  }
}

void GestureController::placeSettled(const bender::RibbonPlacement& placement, const QString& where)
{
  const double vesselRadius = placement.vesselRadius;
  const double radius = placement.suggestedRadius;
  bender::DecaySpec decay = this->Bend->parameters().decay;
  // The held vessel moves as a whole: a plateau reaching 1.2 vessel radii keeps its whole
  // cross-section at full weight, so the lumen follows the ribbon instead of pinching (with the
  // bell, the wall at r = R / 2.2 moved about half as far as the centerline).
  if (vesselRadius > 0.0 && radius > 0.0)
  {
    decay.shape = bender::DecayShape::Plateau;
    decay.plateau = std::clamp(1.2 * vesselRadius / radius, 0.3, 0.8);
  }
  this->showRibbon(placement.ribbon, radius, decay, vesselRadius);
  if (this->Vessels)
  {
    this->Vessels->ribbonPlaced(placement.ribbon);
  }
  this->Session.AddMessage(bender::MessageSeverity::Info,
    QString("Ribbon placed %1 %2 mm, R = %3 mm): press G to grab")
      .arg(where)
      .arg(vesselRadius, 0, 'f', 2)
      .arg(radius, 0, 'f', 2)
      .toStdString());
  this->View->render();
}

bool GestureController::placeRibbonAt(const double point[3])
{
  this->setPlacing(false);
  try
  {
    const bender::RibbonPlacement placement =
      bender::PlaceRibbonOnSurface(this->Session.GetSurface(), { point[0], point[1], point[2] });
    this->placeSettled(placement, "along the vessel (local radius");
    return true;
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, e.what());
    return false;
  }
}

void GestureController::setRibbon(const bender::RibbonSpec& ribbon)
{
  auto* rep = this->View->ribbonWidget()->GetRibbonRepresentation();
  rep->SetRibbon(ribbon);
  rep->SetRadius(this->Session.GetParameters().radius);
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    this->Session.MoveFinal(ribbon);
    if (this->Vessels)
    {
      this->Vessels->moved();
    }
  }
  else if (rep->GetValid())
  {
    // The ribbon on the surface: its r_min, the trackers' anchor.
    this->Session.PlaceRibbon(ribbon);
  }
  this->View->render();
}

void GestureController::applyParameters()
{
  const bender::WarpParameters parameters = this->Bend->parameters();
  if (this->Session.SetParameters(parameters))
  {
    this->View->ribbonWidget()->GetRibbonRepresentation()->SetRadius(parameters.radius);
  }
  this->Bend->showState(this->Session, this->isPlacingRibbon());
  this->View->render();
}

void GestureController::onRibbonInteraction()
{
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    // The widget renders after this event: one frame per move, not two.
    auto* rep = this->View->ribbonWidget()->GetRibbonRepresentation();
    this->View->quietly([this, rep]() { this->Session.MoveFinal(rep->GetRibbon()); });
    if (this->Vessels)
    {
      this->Vessels->moved();
    }
  }
  else if (!this->Session.IsBusy())
  {
    // A handle moved before the grab: the session's ribbon follows (r_min, trackers).
    auto* rep = this->View->ribbonWidget()->GetRibbonRepresentation();
    if (rep->GetValid())
    {
      this->View->quietly([this, rep]() { this->Session.PlaceRibbon(rep->GetRibbon()); });
    }
  }
}

bool GestureController::isOurs(QObject* watched) const
{
  // A widget of the window or of a floating panel dock; not of a dialog.
  for (auto* widget = qobject_cast<QWidget*>(watched); widget; widget = widget->parentWidget())
  {
    if (widget == this->Window)
    {
      return true;
    }
    if (widget->isWindow() && !qobject_cast<QDockWidget*>(widget))
    {
      return false; // a dialog of the window: its keys are its own
    }
  }
  return false;
}

bool GestureController::eventFilter(QObject* watched, QEvent* event)
{
  if (event->type() != QEvent::KeyPress && event->type() != QEvent::KeyRelease)
  {
    return QObject::eventFilter(watched, event);
  }
  auto* key = static_cast<QKeyEvent*>(event);
  if (key->key() != Qt::Key_Space || key->modifiers() != Qt::NoModifier || !this->isOurs(watched) ||
    IsTextField(watched))
  {
    return QObject::eventFilter(watched, event);
  }
  // Space is the gesture's, whatever has the focus (a focused button would click instead).
  // Auto-repeat sends press/release pairs while the key is held: none of them is a new grab
  // or a release.
  if (key->isAutoRepeat())
  {
    return true;
  }
  if (event->type() == QEvent::KeyPress)
  {
    if (!this->SpaceHeld && this->Session.GetState() != bender::GrabState::Grabbed)
    {
      this->SpaceHeld = this->grab();
    }
  }
  else if (this->SpaceHeld)
  {
    this->SpaceHeld = false;
    this->release();
  }
  return true;
}
