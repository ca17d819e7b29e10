#include "MainWindow.h"

#include "BendPanel.h"
#include "MeshIO.h"
#include "RibbonPlacement.h"
#include "SegmentationErrors.h"
#include "SliceViews.h"
#include "SurfaceExtraction.h"
#include "TrackersPanel.h"
#include "VesselSegmentation.h"
#include "VolumeConversion.h"
#include "VolumeIO.h"
#include "WarpPlanIO.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <algorithm>
#include <array>
#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QKeyEvent>
#include <QPointer>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QEventLoop>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QSplitter>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <QVTKOpenGLNativeWidget.h>
#include <QtConcurrent/QtConcurrent>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellPicker.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>
#include <exception>

namespace
{

QString Lower(const QString& s)
{
  return s.toLower();
}

bool IsMesh(const QString& path)
{
  const QString p = Lower(path);
  for (const char* ext : { ".stl", ".obj", ".ply", ".vtp", ".vtk", ".off" })
  {
    if (p.endsWith(ext))
    {
      return true;
    }
  }
  return false;
}

bool IsVolume(const QString& path)
{
  const QString p = Lower(path);
  if (QFileInfo(path).isDir())
  {
    return true;
  }
  for (const char* ext : { ".nrrd", ".nhdr", ".nii", ".nii.gz", ".mha", ".mhd", ".vti" })
  {
    if (p.endsWith(ext))
    {
      return true;
    }
  }
  return false;
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

  this->buildView();
  this->buildPanels();
  this->buildMenus();

  this->StatusText = new QLabel("Ready: open a mesh or a volume, or run the demo (Ctrl+D)", this);
  this->StatusText->setObjectName("statusText");
  this->statusBar()->addWidget(this->StatusText, 1);
  this->Progress = new QProgressBar(this);
  this->Progress->setRange(0, 100);
  this->Progress->setMaximumWidth(220);
  this->Progress->hide();
  this->statusBar()->addPermanentWidget(this->Progress);
  this->CancelButton = new QPushButton("Cancel", this);
  this->CancelButton->setObjectName("cancelWork");
  this->CancelButton->hide();
  this->statusBar()->addPermanentWidget(this->CancelButton);
  connect(this->CancelButton, &QPushButton::clicked, this, [this]() {
    this->CancelFlag = true;
    this->StatusText->setText("Cancelling...");
  });

  this->Watcher = new QFutureWatcher<Finisher>(this);
  connect(this->Watcher, &QFutureWatcher<Finisher>::finished, this, &MainWindow::finishWork);
  this->TrackerTimer = new QTimer(this);
  this->TrackerTimer->setInterval(16);
  connect(this->TrackerTimer, &QTimer::timeout, this, &MainWindow::pollTrackers);

  this->Session.SetMessageCallback([this](const bender::LogicMessage& m) { this->showMessage(m); });
  this->Session.SetChangeCallback([this]() { this->refresh(); });
  QString autosave = this->Options.autosavePath;
  if (autosave.isEmpty())
  {
    const QString folder = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
    QDir().mkpath(folder);
    autosave = folder + "/autosave.bender-session.json";
  }
  if (this->Options.offerRecovery && QFileInfo::exists(autosave))
  {
    this->Session.SetAutosavePath(autosave.toStdString());
    QTimer::singleShot(0, this, &MainWindow::offerRecovery);
  }
  else
  {
    this->Session.SetAutosavePath(autosave.toStdString());
  }
  this->refresh();
}

MainWindow::~MainWindow()
{
  this->CancelFlag = true;
  this->Watcher->waitForFinished();
  this->TrackerTimer->stop();
  this->Session.SetMessageCallback(nullptr);
  this->Session.SetChangeCallback(nullptr);
  this->Trackers.reset();
  this->RibbonWidget->Off();
}

void MainWindow::buildView()
{
  this->View = new QVTKOpenGLNativeWidget(this);
  this->View->setObjectName("view3d");
  this->View->setRenderWindow(this->RenderWindow);
  this->RenderWindow->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.12, 0.13, 0.16);
  this->Renderer->SetBackground2(0.32, 0.34, 0.40);
  this->Renderer->GradientBackgroundOn();
  // Multisampling with blended translucency draws stripes on software OpenGL (llvmpipe).
  this->RenderWindow->SetMultiSamples(0);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  this->RenderWindow->GetInteractor()->SetInteractorStyle(style);

  this->SurfaceMapper->SetInputData(this->Session.GetDisplaySurface());
  this->SurfaceMapper->ScalarVisibilityOff();
  this->SurfaceActor->SetMapper(this->SurfaceMapper);
  this->SurfaceActor->GetProperty()->SetColor(0.86, 0.36, 0.32);
  this->SurfaceActor->GetProperty()->SetSpecular(0.3);
  this->SurfaceActor->GetProperty()->SetSpecularPower(20);
  this->Renderer->AddActor(this->SurfaceActor);

  this->RibbonWidget->SetInteractor(this->RenderWindow->GetInteractor());
  this->RibbonWidget->SetCurrentRenderer(this->Renderer);
  this->RibbonWidget->CreateDefaultRepresentation();
  this->RibbonObserver->SetCallback(&MainWindow::RibbonCallback);
  this->RibbonObserver->SetClientData(this);
  this->RibbonWidget->AddObserver(vtkCommand::InteractionEvent, this->RibbonObserver);
  this->RibbonWidget->AddObserver(vtkCommand::EndInteractionEvent, this->RibbonObserver);
  this->PickObserver->SetCallback(&MainWindow::PickCallback);
  this->PickObserver->SetClientData(this);
  this->RenderWindow->GetInteractor()->AddObserver(
    vtkCommand::LeftButtonPressEvent, this->PickObserver, 10.0f);
  this->View->installEventFilter(this);

  this->Slices = new SliceViews(this);
  this->Slices->hide();
  this->Splitter = new QSplitter(Qt::Vertical, this);
  this->Splitter->addWidget(this->View);
  this->Splitter->addWidget(this->Slices);
  this->Splitter->setStretchFactor(0, 3);
  this->Splitter->setStretchFactor(1, 1);
  this->setCentralWidget(this->Splitter);
}

void MainWindow::buildPanels()
{
  this->Panels = new QTabWidget(this);
  this->Panels->setObjectName("panels");
  this->Panels->setMinimumWidth(330);

  // Data
  auto* data = new QWidget(this);
  auto* dataLayout = new QVBoxLayout(data);
  auto* openButton = new QPushButton("Open mesh, volume or plan... (Ctrl+O)", data);
  auto* demoButton = new QPushButton("Run the demo (Ctrl+D)", data);
  demoButton->setObjectName("demoButton");
  this->DataInfo = new QLabel("No data", data);
  this->DataInfo->setObjectName("dataInfo");
  this->DataInfo->setWordWrap(true);
  dataLayout->addWidget(openButton);
  dataLayout->addWidget(demoButton);
  dataLayout->addWidget(new QLabel("Or drop files on the window.", data));
  dataLayout->addWidget(this->DataInfo);
  dataLayout->addStretch(1);
  connect(openButton, &QPushButton::clicked, this, [this]() {
    const QString file = QFileDialog::getOpenFileName(this, "Open", QString(),
      "All supported (*.stl *.obj *.ply *.vtp *.vtk *.off *.json *.nrrd *.nhdr *.nii *.nii.gz "
      "*.mha *.mhd *.vti);;All files (*)");
    if (!file.isEmpty())
    {
      this->openFile(file);
    }
  });
  connect(demoButton, &QPushButton::clicked, this, &MainWindow::startDemo);
  this->Panels->addTab(data, "Data");

  // Segment
  auto* segment = new QWidget(this);
  auto* segmentLayout = new QVBoxLayout(segment);
  auto* segmentForm = new QFormLayout;
  segmentLayout->addLayout(segmentForm);
  this->MethodCombo = new QComboBox(segment);
  this->MethodCombo->addItems({ "Threshold", "Vesselness" });
  segmentForm->addRow("Method", this->MethodCombo);
  this->ThresholdSpin = new QDoubleSpinBox(segment);
  this->ThresholdSpin->setObjectName("lumenThreshold");
  this->ThresholdSpin->setRange(-1e6, 1e6);
  this->ThresholdSpin->setValue(250.0);
  segmentForm->addRow("Lumen above", this->ThresholdSpin);
  this->SmoothingSpin = new QDoubleSpinBox(segment);
  this->SmoothingSpin->setRange(0.0, 1.0);
  this->SmoothingSpin->setSingleStep(0.1);
  this->SmoothingSpin->setValue(0.5);
  segmentForm->addRow("Smoothing", this->SmoothingSpin);
  auto* segmentButton = new QPushButton("Segment the loaded volume", segment);
  segmentButton->setObjectName("segmentButton");
  segmentLayout->addWidget(segmentButton);
  segmentLayout->addStretch(1);
  connect(segmentButton, &QPushButton::clicked, this, &MainWindow::segmentLoadedVolume);
  this->Panels->addTab(segment, "Segment");

  // Bend
  this->Bend = new BendPanel(this);
  connect(this->Bend, &BendPanel::parametersChanged, this, &MainWindow::applyParameters);
  connect(this->Bend, &BendPanel::placeRibbonRequested, this, [this]() {
    this->PlacingRibbon = true;
    this->StatusText->setText("Click on the vessel to place the ribbon along it");
  });
  connect(this->Bend, &BendPanel::grabToggled, this, [this]() {
    if (this->Session.GetState() == bender::GrabState::Grabbed)
      this->release();
    else
      this->grab();
  });
  connect(this->Bend, &BendPanel::cancelRequested, this,
    [this]() { this->Session.CancelGrab("cancelled by the user"); });
  this->Panels->addTab(this->Bend, "Bend");

  // Trackers
  this->TrackersUi = new TrackersPanel(this);
  connect(this->TrackersUi, &TrackersPanel::connectRequested, this, &MainWindow::connectTrackers);
  connect(this->TrackersUi, &TrackersPanel::disconnectRequested, this, &MainWindow::disconnectTrackers);
  connect(this->TrackersUi, &TrackersPanel::clutchToggled, this,
    [this](bool engaged) { this->Trackers->SetClutch(engaged); });
  connect(this->TrackersUi, &TrackersPanel::alignRequested, this, &MainWindow::alignTrackers);
  this->Panels->addTab(this->TrackersUi, "Trackers");

  // Export
  auto* exportPanel = new QWidget(this);
  auto* exportLayout = new QVBoxLayout(exportPanel);
  auto* exportForm = new QFormLayout;
  exportLayout->addLayout(exportForm);
  this->FormatCombo = new QComboBox(exportPanel);
  this->FormatCombo->addItems({ "STL (binary)", "STL (ASCII)", "VTP", "PLY", "OBJ" });
  exportForm->addRow("Format", this->FormatCombo);
  this->CapCheck = new QCheckBox("Cap the open vessel ends (inlets and outlets)", exportPanel);
  this->CapCheck->setObjectName("capCheck");
  exportForm->addRow("Caps", this->CapCheck);
  this->PatchesCombo = new QComboBox(exportPanel);
  this->PatchesCombo->setObjectName("patchesCombo");
  this->PatchesCombo->addItems(
    { "One surface", "Named solids per patch (ASCII, snappyHexMesh)", "One STL file per patch" });
  exportForm->addRow("STL patches", this->PatchesCombo);
  this->FrameCombo = new QComboBox(exportPanel);
  this->FrameCombo->setObjectName("frameCombo");
  this->FrameCombo->addItems({ "LPS (DICOM, ITK)", "RAS (Slicer, NIfTI)" });
  exportForm->addRow("Frame", this->FrameCombo);
  exportForm->addRow("Unit", new QLabel("millimetres (frame and unit stated in the file header)"));
  auto* checkButton = new QPushButton("Check the surface", exportPanel);
  auto* exportButton = new QPushButton("Export... (Ctrl+E)", exportPanel);
  this->CheckReport = new QPlainTextEdit(exportPanel);
  this->CheckReport->setObjectName("checkReport");
  this->CheckReport->setReadOnly(true);
  exportLayout->addWidget(checkButton);
  exportLayout->addWidget(exportButton);
  exportLayout->addWidget(this->CheckReport, 1);
  connect(checkButton, &QPushButton::clicked, this, &MainWindow::runCheck);
  connect(exportButton, &QPushButton::clicked, this, [this]() {
    const QString file = QFileDialog::getSaveFileName(this, "Export surface", QString(), this->exportFilter());
    if (!file.isEmpty())
    {
      this->exportSurface(file);
    }
  });
  this->Panels->addTab(exportPanel, "Export");

  auto* dock = new QDockWidget("Panels", this);
  dock->setObjectName("panelsDock");
  dock->setWidget(this->Panels);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  this->addDockWidget(Qt::RightDockWidgetArea, dock);
}

void MainWindow::buildMenus()
{
  QMenu* file = this->menuBar()->addMenu("&File");
  file->addAction("&Open...", this, [this]() {
    const QString f = QFileDialog::getOpenFileName(this, "Open");
    if (!f.isEmpty())
      this->openFile(f);
  }, QKeySequence::Open);
  this->RecentMenu = file->addMenu("Open &Recent");
  file->addAction("Run the &demo", this, &MainWindow::startDemo, QKeySequence("Ctrl+D"));
  file->addSeparator();
  file->addAction("&Load plan and replay...", this, [this]() {
    const QString f = QFileDialog::getOpenFileName(this, "Load plan", QString(), "Plans (*.bender.json *.json)");
    if (!f.isEmpty() && this->Session.LoadPlan(f.toStdString()))
      this->addRecentFile(f);
  }, QKeySequence("Ctrl+L"));
  file->addAction("&Save plan...", this, [this]() {
    const QString f = QFileDialog::getSaveFileName(this, "Save plan", "plan.bender.json", "Plans (*.bender.json)");
    if (!f.isEmpty())
      this->Session.SavePlan(f.toStdString());
  }, QKeySequence::Save);
  file->addAction("&Export surface...", this, [this]() {
    const QString f = QFileDialog::getSaveFileName(this, "Export surface", QString(), this->exportFilter());
    if (!f.isEmpty())
      this->exportSurface(f);
  }, QKeySequence("Ctrl+E"));
  file->addAction("Screens&hot...", this, [this]() {
    const QString f = QFileDialog::getSaveFileName(this, "Screenshot", "bender.png", "PNG (*.png)");
    if (!f.isEmpty())
      this->saveScreenshot(f);
  }, QKeySequence("F12"));
  file->addSeparator();
  file->addAction("&Quit", this, &QWidget::close, QKeySequence::Quit);

  QMenu* edit = this->menuBar()->addMenu("&Edit");
  this->UndoAction = edit->addAction("&Undo warp", this, [this]() { this->Session.Undo(); },
    QKeySequence("Ctrl+Z"));
  this->RedoAction = edit->addAction("&Redo warp", this, [this]() { this->Session.Redo(); },
    QKeySequence("Ctrl+Shift+Z"));

  QMenu* bend = this->menuBar()->addMenu("&Bend");
  bend->addAction("&Place ribbon on surface", this, [this]() {
    this->PlacingRibbon = true;
    this->StatusText->setText("Click on the vessel to place the ribbon along it");
  }, QKeySequence("P"));
  bend->addAction("&Grab / release", this, [this]() {
    if (this->Session.GetState() == bender::GrabState::Grabbed)
      this->release();
    else
      this->grab();
  }, QKeySequence("G"));
  bend->addAction("&Cancel bend", this, [this]() {
    this->PlacingRibbon = false;
    this->Session.CancelGrab("cancelled by the user");
  }, QKeySequence("Esc"));

  QMenu* view = this->menuBar()->addMenu("&View");
  view->addAction("&Reset camera", this, &MainWindow::resetCamera, QKeySequence("Ctrl+R"));
  this->updateRecentMenu();
}

void MainWindow::showMessage(const bender::LogicMessage& message)
{
  QString text = QString::fromStdString(message.text);
  if (message.severity == bender::MessageSeverity::Error)
  {
    this->StatusText->setStyleSheet("color: #e55;");
  }
  else if (message.severity == bender::MessageSeverity::Warning)
  {
    this->StatusText->setStyleSheet("color: #d90;");
  }
  else
  {
    this->StatusText->setStyleSheet("");
  }
  this->StatusText->setText(text);
  this->StatusText->setToolTip(text);
}

void MainWindow::refresh()
{
  this->Bend->showState(this->Session);
  this->UndoAction->setEnabled(this->Session.CanUndo());
  this->RedoAction->setEnabled(this->Session.CanRedo());
  if (this->Session.HasSurface())
  {
    vtkPolyData* surface = this->Session.GetSurface();
    this->DataInfo->setText(QString("%1\n%2 points, %3 triangles (LPS mm)\n%4 warps committed")
                              .arg(QString::fromStdString(this->Session.GetSurfaceName()))
                              .arg(surface->GetNumberOfPoints())
                              .arg(surface->GetNumberOfPolys())
                              .arg(this->Session.GetHistoryPosition()));
  }
  if (this->RenderSuppressed == 0)
  {
    this->render();
  }
}

void MainWindow::render()
{
  this->SurfaceMapper->Modified();
  this->RenderWindow->Render();
}

void MainWindow::resetCamera()
{
  this->Renderer->ResetCamera();
  this->render();
}

bool MainWindow::isBusy() const
{
  return this->WorkPending;
}

bool MainWindow::waitUntilIdle(int milliseconds)
{
  QElapsedTimer timer;
  timer.start();
  while (this->WorkPending)
  {
    if (timer.elapsed() > milliseconds)
    {
      return false;
    }
    QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
  }
  return true;
}

void MainWindow::runInBackground(const QString& title, Work work)
{
  if (this->isBusy())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      "Busy: wait for the current task or cancel it");
    return;
  }
  this->CancelFlag = false;
  this->WorkPending = true;
  this->Progress->setValue(0);
  this->Progress->setFormat(title + " %p%");
  this->Progress->show();
  this->CancelButton->show();
  this->StatusText->setText(title + "...");
  bender::ProgressReporter reporter;
  reporter.cancel = &this->CancelFlag;
  QPointer<MainWindow> self(this);
  reporter.onProgress = [self, title](const std::string& stage, double fraction) {
    QMetaObject::invokeMethod(qApp, [self, title, stage, fraction]() {
      if (self)
      {
        self->Progress->setValue(static_cast<int>(std::lround(100.0 * fraction)));
        self->Progress->setFormat(title + ": " + QString::fromStdString(stage) + " %p%");
      }
    }, Qt::QueuedConnection);
  };
  this->Watcher->setFuture(QtConcurrent::run([this, work, reporter]() -> Finisher {
    try
    {
      return work(reporter);
    }
    catch (const bender::SegmentationCancelled&)
    {
      return [this]() { this->Session.AddMessage(bender::MessageSeverity::Warning, "Cancelled"); };
    }
    catch (const std::exception& e)
    {
      const std::string what = e.what();
      return [this, what]() { this->Session.AddMessage(bender::MessageSeverity::Error, what); };
    }
  }));
}

void MainWindow::finishWork()
{
  this->Progress->hide();
  this->CancelButton->hide();
  const std::size_t before = this->Session.GetMessages().size();
  Finisher finisher = this->Watcher->result();
  if (finisher)
  {
    finisher();
  }
  bool failed = false;
  const auto& messages = this->Session.GetMessages();
  for (std::size_t i = before; i < messages.size(); ++i)
  {
    failed |= messages[i].severity == bender::MessageSeverity::Error || messages[i].text == "Cancelled";
  }
  this->WorkPending = false;
  emit this->workFinished(!failed);
}

bool MainWindow::openFile(const QString& path)
{
  const QString lower = Lower(path);
  const std::string file = path.toStdString();
  if (lower.endsWith(".bender-session.json"))
  {
    return this->Session.Recover(file);
  }
  if (lower.endsWith(".json"))
  {
    const bool ok = this->Session.LoadPlan(file);
    if (ok)
      this->addRecentFile(path);
    return ok;
  }
  if (IsMesh(path))
  {
    this->addRecentFile(path);
    this->runInBackground("Reading " + QFileInfo(path).fileName(), [this, file](const bender::ProgressReporter&) {
      vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(file);
      return Finisher([this, mesh, file]() {
        const std::string name = QFileInfo(QString::fromStdString(file)).fileName().toStdString();
        if (this->Session.SetSurface(mesh, name, QFileInfo(QString::fromStdString(file)).absoluteFilePath().toStdString()))
        {
          // A mesh file has no volume behind it.
          this->LoadedVolume.reset();
          this->Slices->setVolume(nullptr, nullptr);
          this->Slices->hide();
          this->resetCamera();
        }
      });
    });
    return true;
  }
  if (IsVolume(path))
  {
    this->addRecentFile(path);
    this->runInBackground("Reading " + QFileInfo(path).fileName(), [this, file](const bender::ProgressReporter& progress) {
      auto volume = std::make_shared<bender::Volume>(bender::ReadVolume(file, {}, progress));
      return Finisher([this, volume, file]() {
        this->LoadedVolume = std::make_unique<bender::Volume>(*volume);
        this->showSlices(ToImageData(*volume), nullptr);
        this->Panels->setCurrentIndex(1);
        const auto& size = volume->geometry.size;
        this->Session.AddMessage(bender::MessageSeverity::Info,
          QString("Loaded volume %1: %2x%3x%4; segment it in the Segment panel")
            .arg(QFileInfo(QString::fromStdString(file)).fileName())
            .arg(size[0]).arg(size[1]).arg(size[2]).toStdString());
      });
    });
    return true;
  }
  this->Session.AddMessage(bender::MessageSeverity::Error,
    QFileInfo(path).fileName().toStdString() +
      ": unknown file type (meshes: stl obj ply vtp vtk off; volumes: nrrd nii mha vti or a "
      "DICOM folder; plans: .bender.json)");
  return false;
}

void MainWindow::segmentLoadedVolume()
{
  if (!this->LoadedVolume)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, "Segment: open a volume first");
    return;
  }
  auto volume = std::make_shared<bender::Volume>(*this->LoadedVolume);
  bender::SegmentationParameters parameters;
  parameters.method = this->MethodCombo->currentIndex() == 1 ? bender::SegmentationMethod::Vesselness
                                                             : bender::SegmentationMethod::Threshold;
  parameters.lower = this->ThresholdSpin->value();
  bender::SurfaceParameters surfaceParameters;
  surfaceParameters.smoothing = this->SmoothingSpin->value();
  this->runInBackground("Segmenting", [this, volume, parameters, surfaceParameters](
                                        const bender::ProgressReporter& progress) {
    auto mask = std::make_shared<bender::LabelMap>(bender::SegmentVessels(*volume, parameters, progress));
    bender::SurfaceResult surface = bender::ExtractSurface(*mask, surfaceParameters, progress);
    return Finisher([this, volume, mask, surface]() {
      this->showSlices(ToImageData(*volume), ToImageData(*mask));
      if (this->Session.SetSurface(surface.surface, "segmented vessel"))
      {
        this->resetCamera();
        this->Panels->setCurrentIndex(2);
      }
    });
  });
}

void MainWindow::startDemo()
{
  this->runInBackground("Demo", [this](const bender::ProgressReporter& progress) {
    auto demo = std::make_shared<bender::DemoVessel>();
    std::string fallback;
    try
    {
      *demo = bender::SegmentDemoVessel(bender::DemoVesselPath(), {}, progress);
    }
    catch (const bender::SegmentationCancelled&)
    {
      throw;
    }
    catch (const std::exception& e)
    {
      // Without the segmentation the demo still bends the vessel surface itself.
      fallback = e.what();
      demo->surface = bender::ReadMesh(bender::DemoVesselPath());
    }
    auto plan = std::make_shared<bender::WarpPlan>(bender::ReadWarpPlan(bender::DemoPlanPath()));
    return Finisher([this, demo, plan, fallback]() {
      if (!fallback.empty())
      {
        this->Session.AddMessage(bender::MessageSeverity::Warning,
          "Demo: segmentation unavailable (" + fallback + "); using the vessel surface");
      }
      if (demo->volume.voxels.size() > 0)
      {
        this->LoadedVolume = std::make_unique<bender::Volume>(demo->volume);
        this->showSlices(ToImageData(demo->volume), ToImageData(demo->mask));
      }
      if (!this->Session.SetSurface(demo->surface, fallback.empty() ? "demo vessel (segmented)" : "demo vessel"))
      {
        return;
      }
      if (!plan->warps.empty())
      {
        const bender::WarpSpec& warp = plan->warps.front();
        bender::WarpParameters parameters = this->Bend->parameters();
        parameters.radius = warp.radius;
        parameters.decay = warp.decay;
        this->Bend->setParameters(parameters);
        this->applyParameters();
        auto* rep = this->RibbonWidget->GetRibbonRepresentation();
        rep->SetHandleLength(4.0);
        rep->SetHandleRadius(0.8);
        rep->SetStripWidth(1.2);
        this->setRibbon(warp.initial);
        this->RibbonWidget->On();
      }
      this->resetCamera();
      this->Panels->setCurrentIndex(2);
      this->Session.AddMessage(bender::MessageSeverity::Info,
        (fallback.empty() ? demo->summary + ". " : std::string()) +
          "Ribbon placed on a branch: press G (or hold Space), drag the end handles, press G to release");
    });
  });
}

void MainWindow::showSlices(vtkImageData* volume, vtkImageData* mask)
{
  const bool wasHidden = this->Slices->isHidden();
  this->Slices->show();
  if (wasHidden)
  {
    const int height = std::max(400, this->Splitter->height());
    this->Splitter->setSizes({ height * 7 / 10, height * 3 / 10 });
  }
  this->Slices->setVolume(volume, mask);
}

void MainWindow::applyParameters()
{
  const bender::WarpParameters parameters = this->Bend->parameters();
  if (this->Session.SetParameters(parameters))
  {
    this->RibbonWidget->GetRibbonRepresentation()->SetRadius(parameters.radius);
  }
  this->Bend->showState(this->Session);
  this->render();
}

void MainWindow::setRibbon(const bender::RibbonSpec& ribbon)
{
  this->RibbonWidget->GetRibbonRepresentation()->SetRibbon(ribbon);
  this->RibbonWidget->GetRibbonRepresentation()->SetRadius(this->Session.GetParameters().radius);
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    this->Session.MoveFinal(ribbon);
  }
  this->render();
}

bool MainWindow::grab()
{
  if (!this->RibbonWidget->GetEnabled())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      "Grab: place the ribbon first (P, then click on the vessel)");
    return false;
  }
  auto* rep = this->RibbonWidget->GetRibbonRepresentation();
  if (!rep->GetValid())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error,
      "Grab refused: the ribbon is invalid (" + rep->GetLastError() + ")");
    return false;
  }
  return this->Session.Grab(rep->GetRibbon());
}

bool MainWindow::release()
{
  if (this->Session.GetState() != bender::GrabState::Grabbed)
  {
    return false;
  }
  const bool ok = this->Session.Release();
  if (ok)
  {
    // The ribbon stays where the hands left it: the committed (final) ribbon.
    this->RibbonWidget->GetRibbonRepresentation()->SetRibbon(this->Session.GetFinalRibbon());
  }
  this->render();
  return ok;
}

bool MainWindow::placeRibbonAt(const double point[3])
{
  try
  {
    const bender::RibbonPlacement placement =
      bender::PlaceRibbonOnSurface(this->Session.GetSurface(), { point[0], point[1], point[2] });
    auto* rep = this->RibbonWidget->GetRibbonRepresentation();
    rep->SetHandleLength(1.2 * placement.vesselRadius);
    rep->SetHandleRadius(0.22 * placement.vesselRadius);
    rep->SetStripWidth(0.3 * placement.vesselRadius);
    bender::WarpParameters parameters = this->Bend->parameters();
    parameters.radius = placement.suggestedRadius;
    this->Bend->setParameters(parameters);
    this->applyParameters();
    this->setRibbon(placement.ribbon);
    this->RibbonWidget->On();
    this->PlacingRibbon = false;
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

void MainWindow::RibbonCallback(vtkObject*, unsigned long, void* clientData, void*)
{
  static_cast<MainWindow*>(clientData)->onRibbonInteraction();
}

void MainWindow::onRibbonInteraction()
{
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    // The widget renders after this event: one frame per move, not two.
    ++this->RenderSuppressed;
    this->Session.MoveFinal(this->RibbonWidget->GetRibbonRepresentation()->GetRibbon());
    --this->RenderSuppressed;
  }
}

void MainWindow::PickCallback(vtkObject*, unsigned long, void* clientData, void*)
{
  static_cast<MainWindow*>(clientData)->onPickForPlacement();
}

void MainWindow::onPickForPlacement()
{
  if (!this->PlacingRibbon || !this->Session.HasSurface())
  {
    return;
  }
  vtkRenderWindowInteractor* interactor = this->RenderWindow->GetInteractor();
  const int* position = interactor->GetEventPosition();
  vtkNew<vtkCellPicker> picker;
  picker->SetTolerance(0.002);
  picker->PickFromListOn();
  picker->AddPickList(this->SurfaceActor);
  if (picker->Pick(position[0], position[1], 0, this->Renderer))
  {
    double point[3];
    picker->GetPickPosition(point);
    this->placeRibbonAt(point);
  }
  else
  {
    this->Session.AddMessage(bender::MessageSeverity::Warning, "Place ribbon: click on the surface");
  }
  this->PickObserver->SetAbortFlag(1);
}

bool MainWindow::exportSurface(const QString& path, bool proceedOnProblems)
{
  if (!this->Session.HasSurface())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, "Export: there is no surface");
    return false;
  }
  // The check runs on the worker, on copies, while the window stays responsive.
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->DeepCopy(this->Session.GetSurface());
  auto original = vtkSmartPointer<vtkPolyData>::New();
  original->DeepCopy(this->Session.GetOriginalSurface());
  auto report = std::make_shared<bender::MeshCheckReport>();
  this->runInBackground("Checking", [surface, original, report](const bender::ProgressReporter&) {
    *report = bender::CheckForExport(surface, original);
    return Finisher([]() {});
  });
  if (!this->waitUntilIdle(600000))
  {
    return false;
  }
  this->CheckReport->setPlainText(
    QString::fromStdString(bender::FormatReportText(*report, QFileInfo(path).fileName().toStdString())));
  if (!report->Clean())
  {
    QString problems;
    for (const auto& problem : report->problems)
    {
      problems += "- " + QString::fromStdString(problem) + "\n";
    }
    bool goOn = proceedOnProblems;
    if (this->Options.interactive)
    {
      goOn = QMessageBox::warning(this, "The surface has problems",
               "The check found:\n" + problems + "\nExport anyway?",
               QMessageBox::Yes | QMessageBox::No, QMessageBox::No) == QMessageBox::Yes;
    }
    if (!goOn)
    {
      this->Session.AddMessage(bender::MessageSeverity::Warning,
        "Export not written: the check found problems");
      return false;
    }
  }
  bender::ExportOptions options;
  const QString lower = Lower(path);
  options.stlEncoding = (lower.endsWith(".stl") && this->FormatCombo->currentIndex() == 1)
    ? bender::StlEncoding::Ascii
    : bender::StlEncoding::Binary;
  options.cap = this->CapCheck->isChecked();
  options.patches = this->PatchesCombo->currentIndex() == 1
    ? bender::StlPatchMode::Solids
    : (this->PatchesCombo->currentIndex() == 2 ? bender::StlPatchMode::Files
                                                : bender::StlPatchMode::Single);
  options.frame = this->FrameCombo->currentIndex() == 1 ? "RAS" : "LPS";
  const bool ok = this->Session.Export(path.toStdString(), options);
  if (ok)
  {
    this->addRecentFile(path);
  }
  return ok;
}

void MainWindow::runCheck()
{
  if (!this->Session.HasSurface())
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, "Check: there is no surface");
    return;
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->DeepCopy(this->Session.GetSurface());
  auto original = vtkSmartPointer<vtkPolyData>::New();
  original->DeepCopy(this->Session.GetOriginalSurface());
  const std::string name = this->Session.GetSurfaceName();
  this->runInBackground("Checking", [this, surface, original, name](const bender::ProgressReporter&) {
    auto report = std::make_shared<bender::MeshCheckReport>(bender::CheckForExport(surface, original));
    return Finisher([this, report, name]() {
      this->CheckReport->setPlainText(QString::fromStdString(bender::FormatReportText(*report, name)));
      this->Session.AddMessage(report->Clean() ? bender::MessageSeverity::Info : bender::MessageSeverity::Warning,
        report->Clean() ? "Check: no problems found" : "Check: problems found, see the Export panel");
    });
  });
}

QString MainWindow::exportFilter() const
{
  return "STL (*.stl);;VTK XML polydata (*.vtp);;PLY (*.ply);;Wavefront OBJ (*.obj)";
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
  this->Session.AddMessage(bender::MessageSeverity::Info, "Screenshot saved to " + path.toStdString());
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
  bender::TrackerDeviceOptions options;
  options.stations = { this->TrackersUi->leftStation(), this->TrackersUi->rightStation() };
  options.realtime = true;
  options.simulatorRealtime = true;
  bender::HandMapping hands;
  hands.leftStation = this->TrackersUi->leftStation();
  hands.rightStation = this->TrackersUi->rightStation();
  bender::TrackerCalibration calibration;
  try
  {
    calibration = bender::TrackerCalibration(bender::Quaternion{}, bender::Vec3{}, this->TrackersUi->motionScale());
  }
  catch (const std::exception& e)
  {
    this->Session.AddMessage(bender::MessageSeverity::Error, e.what());
    return false;
  }
  if (!this->Trackers->Connect(this->TrackersUi->deviceSpec().toStdString(), options, hands, calibration))
  {
    return false;
  }
  this->TrackersUi->setConnected(true);
  this->TrackerTimer->start();
  return true;
}

void MainWindow::disconnectTrackers()
{
  this->TrackerTimer->stop();
  this->Trackers->Disconnect();
  this->TrackersUi->setConnected(false);
  this->TrackersUi->setStatus("not connected");
}

void MainWindow::pollTrackers()
{
  if (!this->Trackers->IsConnected())
  {
    return;
  }
  ++this->RenderSuppressed;
  const bender::TrackerSession::PollResult result = this->Trackers->Poll();
  --this->RenderSuppressed;
  if (const auto ribbon = this->Trackers->CurrentRibbon())
  {
    // The widget shows what the hands hold; the live warp already moved in Poll.
    this->RibbonWidget->GetRibbonRepresentation()->SetRibbon(*ribbon);
    if (!this->RibbonWidget->GetEnabled() && this->Session.HasSurface())
    {
      this->RibbonWidget->On();
    }
  }
  if (result.released)
  {
    this->RibbonWidget->GetRibbonRepresentation()->SetRibbon(this->Session.GetFinalRibbon());
  }
  this->TrackersUi->setStatus(QString::fromStdString(this->Trackers->StatusText()));
  if (result.ended)
  {
    this->TrackerTimer->stop();
    this->TrackersUi->setConnected(false);
  }
  this->render();
}

void MainWindow::alignTrackers()
{
  this->Trackers->AlignTo(this->RibbonWidget->GetRibbonRepresentation()->GetRibbon());
}

void MainWindow::offerRecovery()
{
  const QString path = QString::fromStdString(this->Session.GetAutosavePath());
  const auto answer = QMessageBox::question(this, "Recover the last session?",
    "Bender did not close cleanly last time. Recover the surface and the warps of that session?",
    QMessageBox::Yes | QMessageBox::No, QMessageBox::Yes);
  if (answer == QMessageBox::Yes)
  {
    if (this->Session.Recover(path.toStdString()))
    {
      this->resetCamera();
    }
  }
  else
  {
    this->Session.DiscardAutosave();
  }
}

void MainWindow::addRecentFile(const QString& path)
{
  QSettings settings;
  QStringList files = settings.value("recentFiles").toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  files.removeAll(absolute);
  files.prepend(absolute);
  while (files.size() > 10)
  {
    files.removeLast();
  }
  settings.setValue("recentFiles", files);
  this->updateRecentMenu();
}

void MainWindow::updateRecentMenu()
{
  this->RecentMenu->clear();
  const QStringList files = QSettings().value("recentFiles").toStringList();
  for (const QString& file : files)
  {
    this->RecentMenu->addAction(QFileInfo(file).fileName(), this, [this, file]() { this->openFile(file); })
      ->setToolTip(file);
  }
  this->RecentMenu->setEnabled(!files.isEmpty());
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
  this->CancelFlag = true;
  this->Watcher->waitForFinished();
  this->disconnectTrackers();
  // A clean exit: nothing to recover next time.
  this->Session.DiscardAutosave();
  event->accept();
}
