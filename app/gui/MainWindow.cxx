#include "MainWindow.h"

#include "AutosaveController.h"
#include "BendPanel.h"
#include "BenderView.h"
#include "DataPanel.h"
#include "ElidedLabel.h"
#include "ExportFlow.h"
#include "ExportPanel.h"
#include "FileOpener.h"
#include "FlowPanel.h"
#include "GestureController.h"
#include "MainActions.h"
#include "MeasurementsPanel.h"
#include "SegmentPanel.h"
#include "SliceViews.h"
#include "TrackersPanel.h"
#include "VesselController.h"
#include "VolumeConversion.h"
#include "WorkRunner.h"

#include <QAction>
#include <QCloseEvent>
#include <QCoreApplication>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QSplitter>
#include <QStatusBar>
#include <QTabWidget>

#include <vtkImageData.h>

#include <algorithm>

MainWindow::MainWindow(const MainWindowOptions& options, QWidget* parent)
  : QMainWindow(parent)
  , Options(options)
{
  this->setWindowTitle("Bender");
  this->setObjectName("BenderMainWindow");
  this->resize(1280, 860);
  this->Trackers = std::make_unique<bender::TrackerSession>(this->Session);
  this->Actions = new MainActions(this);

  this->View = new BenderView(this->Session.GetOutputPort(), this);
  this->Slices = new SliceViews(this);
  this->Slices->hide();
  this->Splitter = new QSplitter(Qt::Vertical, this);
  this->Splitter->addWidget(this->View);
  this->Splitter->addWidget(this->Slices);
  this->Splitter->setStretchFactor(0, 3);
  this->Splitter->setStretchFactor(1, 1);
  this->setCentralWidget(this->Splitter);
  // Long messages are drawn cut ("...") with the whole text as the tooltip: they never widen
  // the window or push the progress bar and Cancel out of sight.
  this->StatusText =
    new ElidedLabel("Ready: open a mesh or a volume, or run the demo (Ctrl+D)", this);
  this->StatusText->setObjectName("statusText");
  this->statusBar()->addWidget(this->StatusText, 1);
  this->Worker = new WorkRunner(
    this->statusBar(),
    this->StatusText,
    [this](int severity, const std::string& text)
    { this->Session.AddMessage(static_cast<bender::MessageSeverity>(severity), text); },
    this);
  this->Worker->Hook = this->Options.workHook;
  this->buildPanels();
  this->Actions->addMenus(this->menuBar());
  this->connectActions();

  this->Session.SetMessageCallback([this](const bender::LogicMessage& m) { this->showMessage(m); });
  this->Session.SetChangeCallback([this]() { this->refresh(); });
  this->Recovery->startAutosave(this->Options.autosavePath, this->Options.offerRecovery);
  this->refresh();
}

MainWindow::~MainWindow()
{
  this->Worker->cancelAndWait();
  // The copies beside the autosave end before the sessions they autosave go.
  this->Recovery->waitForAutosaveCopies();
  this->Session.SetMessageCallback(nullptr);
  this->Session.SetChangeCallback(nullptr);
  this->Session.SetAutosaveDecorator(nullptr);
  // Panels that drew into the 3D view take their actors out while it is still there (Qt would
  // delete the view, the central widget, before the dock's panels).
  delete this->TrackersUi;
  this->TrackersUi = nullptr;
  this->Gesture->setTrackers(nullptr);
  this->Trackers.reset();
}

void MainWindow::buildPanels()
{
  this->Panels = new QTabWidget(this);
  this->Panels->setObjectName("panels");
  this->Panels->setMinimumWidth(330);
  this->Data = new DataPanel(this->Actions, this);
  this->Segment = new SegmentPanel(this->Actions, this);
  this->Bend = new BendPanel(this->Actions, this);
  this->TrackersUi = new TrackersPanel(this);
  this->Export = new ExportPanel(this->Actions, this);
  this->Measurements = new MeasurementsPanel(this->Actions, this);
  this->addPanel(this->Data, "Data");
  this->addPanel(this->Segment, "Segment");
  this->addPanel(this->Bend, "Bend");
  this->addPanel(this->TrackersUi, "Trackers");
  this->addPanel(this->Export, "Export");
  this->addPanel(this->Measurements, "Measure");
  this->Flow = new FlowPanel(this->Session, this->Worker, this->Actions, this);
  this->Flow->setViewRenderer(this->View->renderer());
  this->addPanel(this->Flow, "Flow");
  auto* dock = new QDockWidget("Panels", this);
  dock->setObjectName("panelsDock");
  dock->setWidget(this->Panels);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  this->addDockWidget(Qt::RightDockWidgetArea, dock);

  this->Gesture = new GestureController(
    this->Session, this->View, this->Bend, this->Worker, this->Actions, this->StatusText, this);
  this->Vessels = new VesselController(
    this->Session, this->View, this->Worker, this->Actions, this->Measurements, this);
  this->Gesture->setVessels(this->Vessels);
  this->Gesture->setTrackers(this->Trackers.get());
  const WindowParts parts{ this->Session,
    this->Segmentation,
    this->Worker,
    this->Actions,
    this->View,
    this->Gesture,
    this->Bend,
    this->Segment,
    this };
  this->Recovery = new AutosaveController(parts);
  this->Recovery->setAutosaveCopyHook(this->Options.autosaveCopyHook);
  this->Files = new FileOpener(parts, this->Recovery);
  this->Files->setInteractive(this->Options.interactive);
  this->Gesture->setInteractive(this->Options.interactive);
  this->Exports = new ExportFlow(
    this->Session, this->Worker, this->Actions, this->Export, this->Options.interactive, this);
  this->Exports->attachView(this->View, this->Vessels); // the CFD ends in the view (H2)
  this->Exports->setSegmentation(&this->Segmentation);
  GestureController* gesture = this->Gesture;
  this->TrackersUi->attach(
    this->Trackers.get(), &this->Session, this->View, [gesture]() { return gesture->release(); });
  // A tracker's bend is measured live as the mouse's is (H5).
  connect(
    this->TrackersUi, &TrackersPanel::trackerGrabbed, this->Vessels, &VesselController::grabbed);
  connect(this->TrackersUi, &TrackersPanel::trackerMoved, this->Vessels, &VesselController::moved);
  // The slice views' cursor in the 3D view; Shift+click there moves it (H5).
  this->Slices->linkView(this->View);
}

void MainWindow::addPanel(QWidget* panel, const QString& title)
{
  this->Panels->addTab(panel, title);
}

void MainWindow::connectActions()
{
  MainActions* a = this->Actions;
  connect(a->Screenshot,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString f =
        QFileDialog::getSaveFileName(this, "Screenshot", "bender.png", "PNG (*.png)");
      if (!f.isEmpty())
        this->saveScreenshot(f);
    });
  connect(a->Quit, &QAction::triggered, this, &QWidget::close);
  connect(a->Undo, &QAction::triggered, this, [this]() { this->Session.Undo(); });
  connect(a->Redo, &QAction::triggered, this, [this]() { this->Session.Redo(); });
  this->View->attachActions(a);
  connect(this->Files, &FileOpener::volumeChanged, this, &MainWindow::showSlices);
  connect(this->Recovery, &AutosaveController::volumeChanged, this, &MainWindow::showSlices);
  connect(this->Files, &FileOpener::panelWanted, this->Panels, &QTabWidget::setCurrentWidget);
  connect(
    this->Recovery, &AutosaveController::panelWanted, this->Panels, &QTabWidget::setCurrentWidget);
  // A job begun: the busy session's refusals show (undo and redo disabled).
  connect(this->Worker, &WorkRunner::started, this, &MainWindow::refresh);
  connect(this->Worker,
    &WorkRunner::finished,
    this,
    [this](bool ok)
    {
      this->refresh();
      emit this->workFinished(ok);
    });
}

void MainWindow::showMessage(const bender::LogicMessage& message)
{
  const auto severity = message.severity;
  this->StatusText->setStyleSheet(severity == bender::MessageSeverity::Error
      ? "color: #e55;"
      : (severity == bender::MessageSeverity::Warning ? "color: #d90;" : ""));
  this->StatusText->setText(QString::fromStdString(message.text));
  this->StatusText->setToolTip(QString::fromStdString(message.text));
}

void MainWindow::refresh()
{
  this->Gesture->sessionChanged();
  this->Data->showState(this->Session, this->Segmentation);
  this->Actions->Undo->setEnabled(this->Session.CanUndo() && !this->Session.IsBusy());
  this->Actions->Redo->setEnabled(this->Session.CanRedo() && !this->Session.IsBusy());
  // A new committed surface (load, segmentation, release, undo): its centerlines.
  this->Vessels->update();
  this->TrackersUi->sessionChanged(); // "Send to Slicer"
  this->Flow->sessionChanged();
  // The original shape as a ghost once the surface differs from it; the camera reframed when
  // the surface is another scene (a new mesh of another size or place).
  const bool bent = this->Session.GetHistoryPosition() > 0 ||
    this->Session.GetState() == bender::GrabState::Grabbed;
  this->View->setOriginalSurface(this->Session.GetOriginalSurface(), bent);
  if (this->Session.GetState() != bender::GrabState::Grabbed && this->Session.HasSurface())
  {
    this->View->frameIfNewScene();
  }
  // Inside a widget interaction or a tracker poll the view draws once itself (quietly).
  this->render();
}

void MainWindow::showSlices()
{
  const auto& volume = this->Segmentation.GetVolume();
  this->Segment->showVolume(volume);
  if (!volume)
  {
    this->Slices->setVolume(nullptr, nullptr);
    this->Slices->hide();
    return;
  }
  if (this->Slices->isHidden())
  {
    this->Slices->show();
    const int height = std::max(400, this->Splitter->height());
    this->Splitter->setSizes({ height * 7 / 10, height * 3 / 10 });
  }
  const auto& mask = this->Segmentation.GetMask();
  this->Slices->setVolume(ToImageData(*volume), mask ? ToImageData(*mask) : nullptr);
}

void MainWindow::render()
{
  // The mapper is connected to the session's pipeline: no Modified() needed here.
  this->View->render();
}

vtkBenderRibbonWidget* MainWindow::ribbonWidget()
{
  return this->View->ribbonWidget();
}

vtkRenderer* MainWindow::renderer()
{
  return this->View->renderer();
}

QVTKOpenGLNativeWidget* MainWindow::view()
{
  return this->View;
}

bool MainWindow::isBusy() const
{
  return this->Worker->isBusy();
}

bool MainWindow::waitForCenterlines(int milliseconds)
{
  return this->Vessels->waitForCenterlines(milliseconds);
}

bool MainWindow::waitUntilIdle(int milliseconds)
{
  return this->Worker->waitUntilIdle(milliseconds);
}

// The window's commands, done by its parts.
bool MainWindow::openFile(const QString& path)
{
  return this->Files->openFile(path);
}

void MainWindow::startDemo()
{
  this->Files->startDemo();
}

bool MainWindow::segmentVolume()
{
  return this->Files->segmentVolume();
}

bool MainWindow::grab()
{
  return this->Gesture->grab();
}

bool MainWindow::release()
{
  return this->Gesture->release();
}

bool MainWindow::placeRibbonAt(const double point[3])
{
  return this->Gesture->placeRibbonAt(point);
}

bool MainWindow::isPlacingRibbon() const
{
  return this->Gesture->isPlacingRibbon();
}

void MainWindow::setRibbon(const bender::RibbonSpec& ribbon)
{
  this->Gesture->setRibbon(ribbon);
}

bool MainWindow::exportSurface(const QString& path, bool proceedOnProblems)
{
  return this->Exports->exportSurface(path, proceedOnProblems);
}

bool MainWindow::checkSurface()
{
  return this->Exports->checkSurface();
}

bool MainWindow::connectTrackers()
{
  return this->TrackersUi->connectDevice();
}

void MainWindow::disconnectTrackers()
{
  this->TrackersUi->disconnectDevice();
}

void MainWindow::pollTrackers()
{
  this->TrackersUi->poll();
}

QImage MainWindow::grabWindowImage()
{
  // Pending layout (slice views just shown) first, then a fresh frame.
  QCoreApplication::processEvents();
  this->render();
  return this->QWidget::grab().toImage();
}

bool MainWindow::saveScreenshot(const QString& path)
{
  const QImage image = this->grabWindowImage();
  if (image.isNull() || !image.save(path, "PNG"))
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      QFileInfo(path).fileName().toStdString() + ": the screenshot could not be written");
    return false;
  }
  this->Session.AddMessage(
    bender::MessageSeverity::Info, "Screenshot saved to " + path.toStdString());
  return true;
}

bool MainWindow::saveViewScreenshot(const QString& path)
{
  this->render();
  const QImage image = this->View->grabFramebuffer();
  return !image.isNull() && image.save(path, "PNG");
}

void MainWindow::closeEvent(QCloseEvent* event)
{
  // Unsaved warps: Save plan / Discard / Cancel (interactive windows only).
  if (!this->Files->confirmDiscard("Quit"))
  {
    event->ignore();
    return;
  }
  this->Worker->cancelAndWait();
  this->disconnectTrackers();
  // The autosave goes only once the work was saved or explicitly discarded (an interactive
  // window asked just now): otherwise the next start offers to recover it.
  if (!this->Session.HasUnsavedChanges() || this->Files->isInteractive())
  {
    this->Recovery->discardAutosave();
  }
  event->accept();
}
