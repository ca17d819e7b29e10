#include "MainWindow.h"

#include "BendPanel.h"
#include "BenderView.h"
#include "DataPanel.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "MeshIO.h"
#include "RibbonPlacement.h"
#include "SegmentPanel.h"
#include "SliceViews.h"
#include "TrackersPanel.h"
#include "VolumeConversion.h"
#include "WorkRunner.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QKeyEvent>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QSplitter>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>

#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>

#include <algorithm>
#include <cmath>
#include <exception>

namespace
{
bool EndsWithAny(const QString& path, std::initializer_list<const char*> extensions)
{
  const QString p = path.toLower();
  return std::any_of(
    extensions.begin(), extensions.end(), [&](const char* e) { return p.endsWith(e); });
}

bool IsMesh(const QString& path)
{
  return EndsWithAny(path, { ".stl", ".obj", ".ply", ".vtp", ".vtk", ".off" });
}

bool IsVolume(const QString& path)
{
  return QFileInfo(path).isDir() ||
    EndsWithAny(path, { ".nrrd", ".nhdr", ".nii", ".nii.gz", ".mha", ".mhd", ".vti" });
}

std::string Name(const QString& path)
{
  return QFileInfo(path).fileName().toStdString();
}
}

MainWindow::MainWindow(const MainWindowOptions& options, QWidget* parent)
  : QMainWindow(parent)
  , Options(options)
{
  this->setWindowTitle("Bender");
  this->setObjectName("BenderMainWindow");
  this->setAcceptDrops(true);
  this->resize(1280, 860);
  this->Trackers = std::make_unique<bender::TrackerSession>(this->Session);
  this->Actions = new MainActions(this);

  this->View = new BenderView(this->Session.GetOutputPort(), this);
  this->View->installEventFilter(this);
  this->Slices = new SliceViews(this);
  this->Slices->hide();
  this->Splitter = new QSplitter(Qt::Vertical, this);
  this->Splitter->addWidget(this->View);
  this->Splitter->addWidget(this->Slices);
  this->Splitter->setStretchFactor(0, 3);
  this->Splitter->setStretchFactor(1, 1);
  this->setCentralWidget(this->Splitter);
  this->buildPanels();
  this->Actions->addMenus(this->menuBar());
  this->StatusText = new QLabel("Ready: open a mesh or a volume, or run the demo (Ctrl+D)", this);
  this->StatusText->setObjectName("statusText");
  this->statusBar()->addWidget(this->StatusText, 1);
  this->Worker = new WorkRunner(
    this->statusBar(),
    this->StatusText,
    [this](int severity, const std::string& text)
    { this->Session.AddMessage(static_cast<bender::MessageSeverity>(severity), text); },
    this);
  this->Worker->Hook = this->Options.workHook;
  connect(this->Worker,
    &WorkRunner::finished,
    this,
    [this](bool ok)
    {
      this->refresh();
      emit this->workFinished(ok);
    });
  this->connectActions();

  this->Session.SetMessageCallback([this](const bender::LogicMessage& m) { this->showMessage(m); });
  this->Session.SetChangeCallback([this]() { this->refresh(); });
  QString autosave = this->Options.autosavePath;
  if (autosave.isEmpty())
  {
    const QString folder = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
    QDir().mkpath(folder);
    autosave = folder + "/autosave.bender-session.json";
  }
  this->Session.SetAutosavePath(autosave.toStdString());
  if (this->Options.offerRecovery && QFileInfo::exists(autosave))
  {
    QTimer::singleShot(0, this, &MainWindow::offerRecovery);
  }
  this->refresh();
}

MainWindow::~MainWindow()
{
  this->Worker->cancelAndWait();
  this->Session.SetMessageCallback(nullptr);
  this->Session.SetChangeCallback(nullptr);
  this->Trackers.reset();
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

bool MainWindow::isPlacingRibbon() const
{
  return this->View->isPicking();
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
  this->addPanel(this->Data, "Data");
  this->addPanel(this->Segment, "Segment");
  this->addPanel(this->Bend, "Bend");
  this->addPanel(this->TrackersUi, "Trackers");
  this->addPanel(this->Export, "Export");
  connect(this->Bend, &BendPanel::parametersChanged, this, &MainWindow::applyParameters);
  this->TrackersUi->attach(
    this->Trackers.get(),
    &this->Session,
    this->ribbonWidget(),
    [this]() { this->render(); },
    [this](const std::function<void()>& call)
    {
      ++this->RenderSuppressed; // the poll renders once at its end
      call();
      --this->RenderSuppressed;
    });
  auto* dock = new QDockWidget("Panels", this);
  dock->setObjectName("panelsDock");
  dock->setWidget(this->Panels);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  this->addDockWidget(Qt::RightDockWidgetArea, dock);
}

void MainWindow::addPanel(QWidget* panel, const QString& title)
{
  this->Panels->addTab(panel, title);
}

void MainWindow::connectActions()
{
  MainActions* a = this->Actions;
  connect(a->Open,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString file = QFileDialog::getOpenFileName(this,
        "Open",
        QString(),
        "All supported (*.stl *.obj *.ply *.vtp *.vtk *.off *.json *.nrrd *.nhdr *.nii *.nii.gz "
        "*.mha *.mhd *.vti);;All files (*)");
      if (!file.isEmpty())
        this->openFile(file);
    });
  connect(a, &MainActions::recentFileChosen, this, &MainWindow::openFile);
  connect(a->Demo, &QAction::triggered, this, &MainWindow::startDemo);
  connect(a->LoadPlan,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString f =
        QFileDialog::getOpenFileName(this, "Load plan", QString(), "Plans (*.bender.json *.json)");
      if (!f.isEmpty())
        this->openFile(f);
    });
  connect(a->SavePlan,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString f = QFileDialog::getSaveFileName(
        this, "Save plan", "plan.bender.json", "Plans (*.bender.json)");
      if (!f.isEmpty())
        this->Session.SavePlan(f.toStdString());
    });
  connect(a->Check, &QAction::triggered, this, &MainWindow::checkSurface);
  connect(a->Export,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString f =
        QFileDialog::getSaveFileName(this, "Export surface", QString(), ExportPanel::fileFilter());
      if (!f.isEmpty())
        this->exportSurface(f);
    });
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
  connect(a->PlaceRibbon,
    &QAction::triggered,
    this,
    [this]()
    {
      this->View->setPicking(true);
      this->StatusText->setText("Click on the vessel to place the ribbon along it");
    });
  connect(a->Grab,
    &QAction::triggered,
    this,
    [this]()
    {
      if (this->Session.GetState() == bender::GrabState::Grabbed)
        this->release();
      else
        this->grab();
    });
  connect(a->CancelBend,
    &QAction::triggered,
    this,
    [this]()
    {
      this->View->setPicking(false);
      this->Session.CancelGrab("cancelled by the user");
    });
  connect(a->Segment, &QAction::triggered, this, &MainWindow::segmentVolume);
  connect(a->ResetCamera, &QAction::triggered, this->View, &BenderView::resetCamera);
  connect(this->View, &BenderView::ribbonInteraction, this, &MainWindow::onRibbonInteraction);
  connect(this->View,
    &BenderView::surfacePicked,
    this,
    [this](double x, double y, double z)
    {
      const double point[3] = { x, y, z };
      this->placeRibbonAt(point);
    });
  connect(this->View,
    &BenderView::pickMissed,
    this,
    [this]()
    {
      this->Session.AddMessage(
        bender::MessageSeverity::Warning, "Place ribbon: click on the surface");
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
  this->Bend->showState(this->Session);
  this->Data->showState(this->Session, this->Segmentation);
  this->Actions->Undo->setEnabled(this->Session.CanUndo() && !this->Session.IsBusy());
  this->Actions->Redo->setEnabled(this->Session.CanRedo() && !this->Session.IsBusy());
  if (this->RenderSuppressed == 0)
  {
    this->render();
  }
}

void MainWindow::render()
{
  // The mapper is connected to the session's pipeline: no Modified() needed here.
  this->View->render();
}

bool MainWindow::isBusy() const
{
  return this->Worker->isBusy();
}

bool MainWindow::waitUntilIdle(int milliseconds)
{
  QElapsedTimer timer;
  timer.start();
  while (this->Worker->isBusy())
  {
    if (timer.elapsed() > milliseconds)
    {
      return false;
    }
    QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
  }
  return true;
}

bool MainWindow::refuseWhenBusy()
{
  if (!this->isBusy())
  {
    return false;
  }
  this->Session.AddMessage(
    bender::MessageSeverity::Error, "Busy: wait for the current task or cancel it");
  return true;
}

bool MainWindow::runInBackground(const QString& title, Work work)
{
  return this->Worker->run(title,
    [this, work](const bender::ProgressReporter& progress)
    {
      Finisher finisher = work(progress);
      // A finisher that reports an error (a surface refused, ...) fails the job.
      return Finisher(
        [this, finisher]()
        {
          const std::size_t before = this->Session.GetMessages().size();
          finisher();
          const auto& messages = this->Session.GetMessages();
          if (std::any_of(messages.begin() + static_cast<std::ptrdiff_t>(before),
                messages.end(),
                [](const bender::LogicMessage& m)
                { return m.severity == bender::MessageSeverity::Error; }))
          {
            this->Worker->markFailed();
          }
        });
    });
}

bool MainWindow::runSessionJob(const std::shared_ptr<bender::SessionJob>& job,
  std::function<void(bender::SessionJob&, bool)> then)
{
  if (!job)
  {
    return false;
  }
  this->refresh(); // the session is busy: actions disabled
  return this->runInBackground(QString::fromStdString(job->GetTitle()),
    [this, job, then](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return Finisher(
        [this, job, then]()
        {
          const bool ok = this->Session.Finish(*job);
          if (!ok)
          {
            this->Worker->markFailed();
          }
          if (then)
          {
            then(*job, ok);
          }
        });
    });
}

bool MainWindow::openFile(const QString& path)
{
  if (this->refuseWhenBusy())
  {
    return false;
  }
  const std::string file = path.toStdString();
  if (path.toLower().endsWith(".bender-session.json"))
  {
    return this->runSessionJob(this->Session.BeginRecover(file),
      [this](bender::SessionJob&, bool ok)
      {
        if (ok)
          this->View->resetCamera();
      });
  }
  if (path.toLower().endsWith(".json"))
  {
    return this->runSessionJob(this->Session.BeginLoadPlan(file),
      [this, path](bender::SessionJob&, bool ok)
      {
        if (ok)
          this->Actions->addRecentFile(path);
      });
  }
  if (IsMesh(path))
  {
    this->Actions->addRecentFile(path);
    return this->runInBackground("Reading " + QFileInfo(path).fileName(),
      [this, path](const bender::ProgressReporter&)
      {
        vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(path.toStdString());
        return Finisher(
          [this, mesh, path]()
          {
            if (this->Session.SetSurface(
                  mesh, Name(path), QFileInfo(path).absoluteFilePath().toStdString()))
            {
              // A mesh file has no volume behind it.
              this->Segmentation.Clear();
              this->showSlices();
              this->View->resetCamera();
            }
          });
      });
  }
  if (IsVolume(path))
  {
    this->Actions->addRecentFile(path);
    auto job = this->Segmentation.BeginRead(file);
    return this->runInBackground("Reading " + QFileInfo(path).fileName(),
      [this, job, path](const bender::ProgressReporter& progress)
      {
        job->Run(progress);
        return Finisher(
          [this, job, path]()
          {
            this->Segmentation.FinishRead(*job);
            this->showSlices();
            this->Panels->setCurrentWidget(this->Segment);
            const auto& size = job->volume->geometry.size;
            this->Session.AddMessage(bender::MessageSeverity::Info,
              QString("Loaded volume %1: %2x%3x%4; segment it in the Segment panel")
                .arg(QFileInfo(path).fileName())
                .arg(size[0])
                .arg(size[1])
                .arg(size[2])
                .toStdString());
          });
      });
  }
  this->Session.AddMessage(bender::MessageSeverity::Error,
    Name(path) +
      ": unknown file type (meshes: stl obj ply vtp vtk off; volumes: nrrd nii mha vti or a "
      "DICOM folder; plans: .bender.json)");
  return false;
}

bool MainWindow::segmentVolume()
{
  std::string problem;
  if (this->refuseWhenBusy() || !this->Segmentation.SetSettings(this->Segment->settings(), problem))
  {
    if (!problem.empty())
      this->Session.AddMessage(bender::MessageSeverity::Error, "Segment: " + problem);
    return false;
  }
  auto job = this->Segmentation.BeginSegment(problem);
  if (!job)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, problem);
    return false;
  }
  return this->runInBackground("Segmenting",
    [this, job](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return Finisher(
        [this, job]()
        {
          this->Segmentation.FinishSegment(*job);
          this->showSlices();
          if (this->Session.SetSurface(job->surface, "segmented vessel"))
          {
            this->View->resetCamera();
            this->Panels->setCurrentWidget(this->Bend);
          }
        });
    });
}

void MainWindow::startDemo()
{
  if (this->refuseWhenBusy())
  {
    return;
  }
  auto job = std::make_shared<bender::SegmentationSession::DemoJob>();
  this->runInBackground("Demo",
    [this, job](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return Finisher(
        [this, job]()
        {
          if (!job->fallback.empty())
          {
            this->Session.AddMessage(bender::MessageSeverity::Warning,
              "Demo: segmentation unavailable (" + job->fallback + "); using the vessel surface");
          }
          this->Segmentation.FinishDemo(*job);
          this->showSlices();
          if (!this->Session.SetSurface(
                job->surface, job->fallback.empty() ? "demo vessel (segmented)" : "demo vessel"))
          {
            return;
          }
          if (!job->plan.warps.empty())
          {
            // The ribbon and parameters of the demo plan's first warp, ready to grab.
            const bender::WarpSpec& warp = job->plan.warps.front();
            bender::WarpParameters parameters = this->Bend->parameters();
            parameters.radius = warp.radius;
            parameters.decay = warp.decay;
            this->Bend->setParameters(parameters);
            this->applyParameters();
            auto* rep = this->ribbonWidget()->GetRibbonRepresentation();
            rep->SetHandleLength(4.0);
            rep->SetHandleRadius(0.8);
            rep->SetStripWidth(1.2);
            this->setRibbon(warp.initial);
            this->ribbonWidget()->On();
          }
          this->View->resetCamera();
          this->Panels->setCurrentWidget(this->Bend);
          this->Session.AddMessage(bender::MessageSeverity::Info,
            (job->fallback.empty() ? job->summary + ". " : std::string()) +
              "Ribbon placed on a branch: press G (or hold Space), drag the end handles, press G "
              "to "
              "release");
        });
    });
}

void MainWindow::showSlices()
{
  const auto& volume = this->Segmentation.GetVolume();
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

void MainWindow::applyParameters()
{
  const bender::WarpParameters parameters = this->Bend->parameters();
  if (this->Session.SetParameters(parameters))
  {
    this->ribbonWidget()->GetRibbonRepresentation()->SetRadius(parameters.radius);
  }
  this->Bend->showState(this->Session);
  this->render();
}

void MainWindow::setRibbon(const bender::RibbonSpec& ribbon)
{
  this->ribbonWidget()->GetRibbonRepresentation()->SetRibbon(ribbon);
  this->ribbonWidget()->GetRibbonRepresentation()->SetRadius(this->Session.GetParameters().radius);
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    this->Session.MoveFinal(ribbon);
  }
  this->render();
}

bool MainWindow::grab()
{
  auto* rep = this->ribbonWidget()->GetRibbonRepresentation();
  if (!this->ribbonWidget()->GetEnabled() || !rep->GetValid())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      this->ribbonWidget()->GetEnabled()
        ? "Grab refused: the ribbon is invalid (" + rep->GetLastError() + ")"
        : "Grab: place the ribbon first (P, then click on the vessel)");
    return false;
  }
  return this->Session.Grab(rep->GetRibbon());
}

bool MainWindow::release()
{
  if (this->Session.GetState() != bender::GrabState::Grabbed || this->refuseWhenBusy())
  {
    return false;
  }
  return this->runSessionJob(this->Session.BeginRelease(),
    [this](bender::SessionJob&, bool ok)
    {
      if (ok)
      {
        // The ribbon stays where the hands left it: the committed (final) ribbon.
        this->ribbonWidget()->GetRibbonRepresentation()->SetRibbon(this->Session.GetFinalRibbon());
      }
      this->render();
    });
}

bool MainWindow::placeRibbonAt(const double point[3])
{
  this->View->setPicking(false);
  try
  {
    const bender::RibbonPlacement placement =
      bender::PlaceRibbonOnSurface(this->Session.GetSurface(), { point[0], point[1], point[2] });
    auto* rep = this->ribbonWidget()->GetRibbonRepresentation();
    rep->SetHandleLength(1.2 * placement.vesselRadius);
    rep->SetHandleRadius(0.22 * placement.vesselRadius);
    rep->SetStripWidth(0.3 * placement.vesselRadius);
    bender::WarpParameters parameters = this->Bend->parameters();
    parameters.radius = placement.suggestedRadius;
    this->Bend->setParameters(parameters);
    this->applyParameters();
    this->setRibbon(placement.ribbon);
    this->ribbonWidget()->On();
    this->Session.AddMessage(bender::MessageSeverity::Info,
      QString("Ribbon placed along the vessel (local radius %1 mm, R = %2 mm): press G to grab")
        .arg(placement.vesselRadius, 0, 'f', 2)
        .arg(placement.suggestedRadius, 0, 'f', 2)
        .toStdString());
    this->render();
    return true;
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, e.what());
    return false;
  }
}

void MainWindow::onRibbonInteraction()
{
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    // The widget renders after this event: one frame per move, not two.
    ++this->RenderSuppressed;
    this->Session.MoveFinal(this->ribbonWidget()->GetRibbonRepresentation()->GetRibbon());
    --this->RenderSuppressed;
  }
}

bool MainWindow::exportSurface(const QString& path, bool proceedOnProblems)
{
  if (this->refuseWhenBusy())
  {
    return false;
  }
  // Interactive: check first, ask on problems, then write (a second job).
  const bool proceed = proceedOnProblems && !this->Options.interactive;
  return this->runSessionJob(
    this->Session.BeginExport(path.toStdString(), this->Export->options(path), proceed),
    [this, path](bender::SessionJob& job, bool ok)
    {
      this->Export->showReport(
        QString::fromStdString(bender::FormatReportText(job.GetReport(), Name(path))));
      if (ok)
      {
        this->Actions->addRecentFile(path);
        return;
      }
      if (job.GetOutcome() != bender::SessionJob::Outcome::Done || job.GetReport().Clean() ||
        !this->Options.interactive)
      {
        return;
      }
      QString problems;
      for (const auto& problem : job.GetReport().problems)
        problems += "- " + QString::fromStdString(problem) + "\n";
      QTimer::singleShot(0,
        this,
        [this, path, problems]()
        {
          if (QMessageBox::warning(this,
                "The surface has problems",
                "The check found:\n" + problems + "\nExport anyway?",
                QMessageBox::Yes | QMessageBox::No,
                QMessageBox::No) == QMessageBox::Yes)
          {
            this->runSessionJob(
              this->Session.BeginExport(path.toStdString(), this->Export->options(path), true));
          }
        });
    });
}

bool MainWindow::checkSurface()
{
  if (this->refuseWhenBusy())
  {
    return false;
  }
  const std::string name = this->Session.GetSurfaceName();
  return this->runSessionJob(this->Session.BeginCheck(),
    [this, name](bender::SessionJob& job, bool)
    {
      this->Export->showReport(
        QString::fromStdString(bender::FormatReportText(job.GetReport(), name)));
    });
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
    this->Session.AddMessage(
      bender::MessageSeverity::Error, Name(path) + ": the screenshot could not be written");
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

void MainWindow::offerRecovery()
{
  const auto answer = QMessageBox::question(this,
    "Recover the last session?",
    "Bender did not close cleanly last time. Recover the surface and the warps of that session?",
    QMessageBox::Yes | QMessageBox::No,
    QMessageBox::Yes);
  if (answer == QMessageBox::Yes)
  {
    this->openFile(QString::fromStdString(this->Session.GetAutosavePath()));
  }
  else
  {
    this->Session.DiscardAutosave();
  }
}
void MainWindow::dragEnterEvent(QDragEnterEvent* event)
{
  if (event->mimeData()->hasUrls())
  {
    event->acceptProposedAction();
  }
}

void MainWindow::dropEvent(QDropEvent* event)
{
  for (const QUrl& url : event->mimeData()->urls())
  {
    if (url.isLocalFile())
    {
      this->openFile(url.toLocalFile());
      // One file at a time: the worker takes one task.
      break;
    }
  }
  event->acceptProposedAction();
}

bool MainWindow::eventFilter(QObject* watched, QEvent* event)
{
  // Space held grabs, released releases (the 3D view has the focus while dragging).
  if (event->type() == QEvent::KeyPress || event->type() == QEvent::KeyRelease)
  {
    auto* key = static_cast<QKeyEvent*>(event);
    if (key->key() == Qt::Key_Space && !key->isAutoRepeat())
    {
      if (event->type() == QEvent::KeyPress)
        this->keyPressEvent(key);
      else
        this->keyReleaseEvent(key);
      return true;
    }
  }
  return QMainWindow::eventFilter(watched, event);
}

void MainWindow::keyPressEvent(QKeyEvent* event)
{
  if (event->key() == Qt::Key_Space && !event->isAutoRepeat())
  {
    if (!this->SpaceHeld && this->Session.GetState() != bender::GrabState::Grabbed)
    {
      this->SpaceHeld = this->grab();
    }
    event->accept();
    return;
  }
  QMainWindow::keyPressEvent(event);
}

void MainWindow::keyReleaseEvent(QKeyEvent* event)
{
  if (event->key() == Qt::Key_Space && !event->isAutoRepeat())
  {
    if (this->SpaceHeld)
    {
      this->SpaceHeld = false;
      this->release();
    }
    event->accept();
    return;
  }
  QMainWindow::keyReleaseEvent(event);
}

void MainWindow::closeEvent(QCloseEvent* event)
{
  this->Worker->cancelAndWait();
  this->disconnectTrackers();
  // A clean exit: nothing to recover next time.
  this->Session.DiscardAutosave();
  event->accept();
}
