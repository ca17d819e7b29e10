#include "ExportFlow.h"

#include "BenderSession.h"
#include "BenderView.h"
#include "CfdEndsOverlay.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "VesselController.h"
#include "WorkRunner.h"

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "MeshFormats.h"
#include "PatchSidecar.h"
#include "PolyDataCopy.h"
#include "PrepareForCfd.h"
#include "SegmentationSession.h"

#include <vtkPolyData.h>

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPointer>
#include <QPushButton>
#include <QStandardPaths>
#include <QTimer>
#include <QVBoxLayout>

namespace
{
// A file name made of the data's name: ASCII letters and digits, '-', '.' and '_'; each run of
// anything else (spaces, parentheses) becomes one '_'. "vessel" when nothing is left.
QString FileStem(const QString& name)
{
  QString stem;
  for (const QChar c : name)
  {
    if ((c.unicode() < 128 && c.isLetterOrNumber()) || c == '-' || c == '_' || c == '.')
    {
      stem += c;
    }
    else if (!stem.isEmpty() && !stem.endsWith('_'))
    {
      stem += '_';
    }
  }
  while (stem.endsWith('_') || stem.endsWith('.'))
  {
    stem.chop(1);
  }
  return stem.isEmpty() ? QString("vessel") : stem;
}

// The files an export to `path` with `options` would replace: the file, its patches sidecar
// and, one STL file per patch, the folder's <stem>_*.stl.
QStringList ExistingFiles(const bender::ExportSurfaceOptions& options, const QString& path)
{
  QStringList existing;
  const QFileInfo file(path);
  if (file.exists())
  {
    existing << file.fileName();
  }
  const auto format = bender::FindMeshFormat(path.toStdString());
  if (!format)
  {
    return existing;
  }
  bender::MeshExportRequest request;
  request.encoding = options.stlEncoding;
  request.patches = options.patches;
  request.sidecar = options.patchesJson ? bender::SidecarChoice::On : bender::SidecarChoice::Off;
  const bender::MeshExportRules rules = bender::ResolveMeshExport(*format, request);
  const QFileInfo sidecar(QString::fromStdString(bender::PatchSidecarPath(path.toStdString())));
  if (rules.sidecar && sidecar.exists())
  {
    existing << sidecar.fileName();
  }
  if (rules.patches == bender::StlPatchMode::Files)
  {
    existing << file.absoluteDir().entryList({ file.completeBaseName() + "_*.stl" }, QDir::Files);
  }
  return existing;
}
} // namespace

ExportDialog::ExportDialog(const ExportOptionsForm& start, const QString& path, QWidget* parent)
  : QDialog(parent)
{
  this->setObjectName("exportDialog");
  this->setWindowTitle("Export surface");
  auto* layout = new QVBoxLayout(this);
  auto* file = new QHBoxLayout;
  this->Path = new QLineEdit(this);
  this->Path->setObjectName("exportPath");
  this->Path->setMinimumWidth(360);
  auto* browse = new QPushButton("Browse...", this);
  browse->setObjectName("exportBrowse");
  file->addWidget(new QLabel("File", this));
  file->addWidget(this->Path, 1);
  file->addWidget(browse);
  layout->addLayout(file);
  this->Form = new ExportOptionsForm(this);
  this->Form->copyFrom(start);
  layout->addWidget(this->Form);
  this->Problem = new QLabel(this);
  this->Problem->setObjectName("exportProblem");
  this->Problem->setStyleSheet("color: #b00020");
  layout->addWidget(this->Problem);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Cancel, this);
  auto* ok = buttons->addButton("Export", QDialogButtonBox::AcceptRole);
  ok->setObjectName("exportOk");
  ok->setDefault(true);
  layout->addWidget(buttons);
  this->setPath(path);
  connect(browse, &QPushButton::clicked, this, &ExportDialog::browse);
  connect(buttons, &QDialogButtonBox::accepted, this, &ExportDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &ExportDialog::reject);
  connect(this->Form->Formats,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    &ExportDialog::followFormat);
  this->followFormat();
}

QString ExportDialog::path() const
{
  return this->Path->text().trimmed();
}

void ExportDialog::setPath(const QString& path)
{
  this->Path->setText(path);
}

void ExportDialog::followFormat()
{
  // The file's extension follows the format (vessel.stl -> vessel.smesh).
  const QString path = this->path();
  if (path.isEmpty())
  {
    return;
  }
  const QFileInfo info(path);
  const QString stem =
    info.suffix().isEmpty() ? path : path.left(path.size() - info.suffix().size() - 1);
  this->setPath(stem + this->Form->suffix());
}

void ExportDialog::browse()
{
  // Replacing is asked once, in accept(), for every file the export would write.
  const QString f = QFileDialog::getSaveFileName(this,
    "Export surface",
    this->path(),
    ExportPanel::fileFilter(),
    nullptr,
    QFileDialog::DontConfirmOverwrite);
  if (f.isEmpty())
  {
    return;
  }
  // The format follows the file chosen (the encoding stays when the format does).
  const auto chosen = bender::FindMeshFormat(f.toStdString());
  this->setPath(f);
  if (chosen && chosen->name != this->Form->format().name)
  {
    this->Form->Formats->setCurrentIndex(this->Form->formatIndex(chosen->name));
  }
  this->followFormat();
}

void ExportDialog::accept()
{
  const QString path = this->path();
  if (path.isEmpty())
  {
    this->Problem->setText("Choose the file to write.");
    return;
  }
  const QStringList existing = ExistingFiles(this->Form->options(path), path);
  if (!existing.isEmpty())
  {
    QMessageBox question(QMessageBox::Warning,
      "Replace files?",
      "These files exist in " + QDir::toNativeSeparators(QFileInfo(path).absolutePath()) + ":\n  " +
        existing.join("\n  ") + "\n\nReplace them?",
      QMessageBox::Yes | QMessageBox::No,
      this);
    question.setObjectName("replaceQuestion");
    question.setDefaultButton(QMessageBox::No);
    if (question.exec() != QMessageBox::Yes)
    {
      this->Problem->setText("Not replaced: choose another file.");
      return;
    }
  }
  QDialog::accept();
}

ExportFlow::ExportFlow(bender::BenderSession& session,
  WorkRunner* worker,
  MainActions* actions,
  ExportPanel* panel,
  bool interactive,
  QWidget* window)
  : QObject(window)
  , Session(session)
  , Worker(worker)
  , Actions(actions)
  , Panel(panel)
  , Interactive(interactive)
  , Window(window)
{
  connect(actions->Check, &QAction::triggered, this, &ExportFlow::checkSurface);
  connect(actions->Export, &QAction::triggered, this, &ExportFlow::openExportDialog);
  connect(panel, &ExportPanel::prepareRequested, this, &ExportFlow::prepareForCfd);
  connect(actions->SavePlan,
    &QAction::triggered,
    this,
    [this]()
    {
      const auto [folder, stem] = this->dataFolderAndStem();
      const QString f = QFileDialog::getSaveFileName(this->Window,
        "Save plan",
        QDir(folder).filePath(stem + ".bender.json"),
        "Plans (*.bender.json)");
      if (!f.isEmpty() && this->Session.SavePlan(f.toStdString()))
      {
        this->rememberFolder(f);
      }
    });
}

void ExportFlow::setSegmentation(const bender::SegmentationSession* segmentation)
{
  this->Segmentation = segmentation;
}

QString ExportFlow::dataKey() const
{
  const QString volume = this->Segmentation && this->Segmentation->HasVolume()
    ? QString::fromStdString(this->Segmentation->GetVolumeSource().path)
    : QString();
  return QString::fromStdString(this->Session.GetSourcePath()) + '\n' + volume + '\n' +
    QString::fromStdString(this->Session.GetSurfaceName());
}

std::pair<QString, QString> ExportFlow::dataFolderAndStem() const
{
  // Where the data came from: the surface's file, else the volume's file (or DICOM folder)
  // it was segmented from; data made here (the demo): the user's documents.
  const QFileInfo source(QString::fromStdString(this->Session.GetSourcePath()));
  const QFileInfo volume(this->Segmentation && this->Segmentation->HasVolume()
      ? QString::fromStdString(this->Segmentation->GetVolumeSource().path)
      : QString());
  QString folder, name;
  if (!source.filePath().isEmpty())
  {
    folder = source.absolutePath();
    name = source.completeBaseName();
  }
  else if (!volume.filePath().isEmpty())
  {
    folder = volume.absolutePath(); // a DICOM folder's parent: never into the series
    name = volume.isDir() ? volume.fileName() : volume.baseName();
  }
  else
  {
    folder = QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation);
    if (folder.isEmpty() || !QDir(folder).exists())
    {
      folder = QDir::homePath();
    }
    name = QString::fromStdString(this->Session.GetSurfaceName());
  }
  // The same data saved or exported again: where it went last time.
  if (!this->LastFolder.isEmpty() && this->LastFolderData == this->dataKey())
  {
    folder = this->LastFolder;
  }
  return { folder, FileStem(name) };
}

QString ExportFlow::defaultExportPath() const
{
  const auto [folder, stem] = this->dataFolderAndStem();
  return QDir(folder).filePath(stem + "_export" + this->Panel->form()->suffix());
}

void ExportFlow::rememberFolder(const QString& path)
{
  this->LastFolder = QFileInfo(path).absolutePath();
  this->LastFolderData = this->dataKey();
}

ExportDialog* ExportFlow::openExportDialog()
{
  auto* dialog = new ExportDialog(*this->Panel->form(), this->defaultExportPath(), this->Window);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  connect(dialog,
    &QDialog::accepted,
    this,
    [this, dialog]()
    {
      this->Panel->form()->copyFrom(*dialog->form());
      this->rememberFolder(dialog->path());
      this->exportSurface(dialog->path());
    });
  dialog->open();
  return dialog;
}

void ExportFlow::attachView(BenderView* view, VesselController* vessels)
{
  this->View = view;
  this->Vessels = vessels;
  delete this->Overlay;
  this->Overlay = new CfdEndsOverlay(view->renderer(), view->ribbonRenderer(), this);
  connect(vessels, &VesselController::centerlinesChanged, this, &ExportFlow::listEnds);
  connect(this->Worker, &WorkRunner::finished, this, &ExportFlow::followSurface);
  // Undo and redo change the surface without a job: after the window has applied them.
  for (QAction* action : { this->Actions->Undo, this->Actions->Redo })
  {
    connect(action, &QAction::triggered, this, &ExportFlow::followSurface, Qt::QueuedConnection);
  }
  // Shown with the Export panel; the discs only while the ends are to be clipped.
  connect(this->Panel, &ExportPanel::shownChanged, this, &ExportFlow::showOverlay);
  connect(this->Panel->Clip, &QCheckBox::toggled, this, &ExportFlow::showOverlay);
  // The disc dragged in the view and the cut typed in the table: one distance per end.
  connect(this->Overlay,
    &CfdEndsOverlay::distanceChanged,
    this,
    [this](int end, double distance)
    {
      if (this->Panel->listsCenterlineEnds())
      {
        this->Panel->setCutDistance(end, distance);
      }
    });
  connect(this->Panel,
    &ExportPanel::cutDistanceEdited,
    this,
    [this](int row, double distance)
    {
      if (this->Panel->listsCenterlineEnds() && !this->Overlay->showsPatches())
      {
        this->Overlay->setDistance(row, distance);
        this->renderView();
      }
    });
  connect(this->Panel,
    &ExportPanel::endNamesChanged,
    this,
    [this]()
    {
      if (!this->Panel->listsCenterlineEnds())
      {
        return;
      }
      for (int k = 0; k < this->Overlay->numberOfEnds(); ++k)
      {
        this->Overlay->setLabel(k, this->Panel->endName(k), this->Panel->endIsInlet(k));
      }
      this->renderView();
    });
  this->listEnds();
}

void ExportFlow::showOverlay()
{
  if (!this->Overlay)
  {
    return;
  }
  const bool shown =
    this->Panel->isVisible() && (this->Overlay->showsPatches() || this->Panel->Clip->isChecked());
  if (shown != this->Overlay->isVisible())
  {
    this->Overlay->setVisible(shown);
    this->renderView();
  }
}

void ExportFlow::renderView()
{
  if (this->View)
  {
    this->View->render();
  }
}

void ExportFlow::listEnds()
{
  if (!this->Overlay)
  {
    return;
  }
  vtkPolyData* current = this->Session.HasSurface() ? this->Session.GetSurface() : nullptr;
  if (this->showsPrepared(current))
  {
    if (!this->Overlay->showsPatches())
    {
      this->showPreparedEnds();
    }
    return; // the prepared surface: its caps stay shown
  }
  const bender::VesselSession& vessels = this->Vessels->vessels();
  std::vector<bender::CenterlineEndPath> paths;
  if (current && vessels.HasCenterlines() && vessels.IsUpToDate(this->Session) &&
    vessels.GetPaths())
  {
    try
    {
      paths = bender::FindCenterlineEndPaths(vessels.GetPaths());
    }
    catch (const std::exception&)
    {
      paths.clear(); // no vessel end to show (the Measurements panel says why)
    }
  }
  if (paths.empty())
  {
    this->EndCenterlines = nullptr;
    this->EndsFor = nullptr;
    this->Overlay->clear();
    if (this->Panel->listsCenterlineEnds())
    {
      this->Panel->clearEnds();
    }
    this->renderView();
    return;
  }
  this->EndCenterlines = vtkSmartPointer<vtkPolyData>::New();
  this->EndCenterlines->DeepCopy(vessels.GetPaths());
  this->EndsFor = current;
  this->EndsForTime = current->GetMTime();
  this->Panel->showCenterlineEnds(paths);
  this->Overlay->setEnds(paths);
  for (int k = 0; k < this->Overlay->numberOfEnds(); ++k)
  {
    this->Overlay->setLabel(k, this->Panel->endName(k), this->Panel->endIsInlet(k));
  }
  this->showOverlay();
  this->renderView();
}

bool ExportFlow::showsPrepared(vtkPolyData* surface) const
{
  return surface && surface == this->Prepared && surface->GetMTime() == this->PreparedTime;
}

void ExportFlow::showPreparedEnds()
{
  this->Panel->showEnds(this->PreparedEnds);
  if (this->Overlay)
  {
    this->Overlay->setPatches(this->Prepared, this->PreparedEnds);
    this->showOverlay();
    this->renderView();
  }
}

void ExportFlow::followSurface()
{
  if (!this->Overlay)
  {
    return;
  }
  vtkPolyData* current = this->Session.HasSurface() ? this->Session.GetSurface() : nullptr;
  const bool prepared = this->showsPrepared(current);
  if (prepared && !this->Overlay->showsPatches())
  {
    this->showPreparedEnds(); // back by a redo
    return;
  }
  const bool listed =
    current && current == this->EndsFor && current->GetMTime() == this->EndsForTime;
  if ((this->Overlay->showsPatches() && !prepared) ||
    (this->Overlay->numberOfEnds() > 0 && !listed))
  {
    this->Overlay->clear(); // the new surface's ends come with its centerlines
    this->renderView();
  }
}

bool ExportFlow::prepareForCfd()
{
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  vtkPolyData* current = this->Session.HasSurface() ? this->Session.GetSurface() : nullptr;
  if (!current)
  {
    this->Panel->showReport("Prepare for CFD: open or segment a surface first.");
    return false;
  }
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    this->Panel->showReport("Prepare for CFD: release the bend first.");
    return false;
  }
  // Pressed again on the surface a Prepare made: from the surface before it, the new step taking
  // the old one's place in the history.
  const bool again = this->Session.GetCurrentCfdStep() != nullptr;
  vtkPolyData* from = again ? this->Session.GetPreviousSurface() : current;
  const bool listed = this->Panel->listsCenterlineEnds() && this->EndCenterlines &&
    current == this->EndsFor && current->GetMTime() == this->EndsForTime;
  if (!again && !listed && !this->showsPrepared(current))
  {
    this->Panel->clearEnds(); // the listed ends belong to another surface
  }
  // The step clips by the centerlines ComputeCenterlines gives for the surface, as the plan's
  // replay does (ApplyCfdStep); those the discs were placed on are passed when they are those:
  // the centerlines of an unbent surface (the vessels' "before"), or those of the last Prepare.
  vtkSmartPointer<vtkPolyData> centerlines;
  if (again && from == this->PreparedFrom && this->PreparedCenterlines)
  {
    centerlines = bender::DeepCopyOf(this->PreparedCenterlines);
  }
  else if (!again && listed && current == this->Session.GetOriginalSurface())
  {
    centerlines = bender::DeepCopyOf(this->EndCenterlines);
  }
  const bender::PrepareForCfdOptions options = this->Panel->prepareOptions();
  const bender::CfdStep step = bender::CfdStepOf(options, 0);
  const vtkSmartPointer<vtkPolyData> source = bender::DeepCopyOf(from);
  const std::string name = this->Session.GetSurfaceName();
  const vtkMTimeType time = current->GetMTime();
  QPointer<ExportFlow> self(this);
  return this->Worker->run("Prepare for CFD",
    [self, source, step, centerlines, name, again, current, time](
      const bender::ProgressReporter& progress) -> WorkRunner::Finisher
    {
      auto result = std::make_shared<bender::PrepareForCfdResult>();
      try
      {
        bender::ApplyPlanOptions apply;
        apply.planName = name.empty() ? "the surface" : name;
        apply.progress = progress;
        *result = bender::ApplyCfdStep(source, step, apply, centerlines);
      }
      catch (const bender::Cancelled&)
      {
        throw; // the worker says so; nothing changed
      }
      catch (const std::exception& e)
      {
        const QString what = QString("Prepare for CFD failed: ") + e.what();
        return [self, what]()
        {
          if (self)
          {
            self->Panel->showReport(what);
            self->Session.AddMessage(bender::MessageSeverity::Error, what.toStdString());
            self->Worker->markFailed();
          }
        };
      }
      // The plan keeps what was made: every end's cut, name and extension factor.
      auto made = std::make_shared<bender::CfdStep>(bender::ResolvedCfdStep(step, *result));
      return [self, result, made, again, current, time]()
      {
        if (self)
        {
          self->applyPrepared(result, *made, again, current, time);
        }
      };
    });
}

void ExportFlow::applyPrepared(const std::shared_ptr<bender::PrepareForCfdResult>& result,
  const bender::CfdStep& step,
  bool again,
  vtkPolyData* from,
  vtkMTimeType fromTime)
{
  vtkPolyData* current = this->Session.HasSurface() ? this->Session.GetSurface() : nullptr;
  if (current != from || !current || current->GetMTime() != fromTime ||
    this->Session.GetState() == bender::GrabState::Grabbed)
  {
    this->Panel->showReport(
      "Prepare for CFD: the surface changed while it was prepared; nothing was applied.");
    this->Worker->markFailed();
    return;
  }
  if (!this->Session.CommitCfdStep(step, result->surface, again))
  {
    this->Panel->showReport("Prepare for CFD: the prepared surface could not be committed.");
    this->Worker->markFailed();
    return;
  }
  this->PreparedFrom = this->Session.GetPreviousSurface();
  this->PreparedCenterlines = result->centerlines;
  this->Prepared = this->Session.GetSurface();
  this->PreparedTime = this->Prepared->GetMTime();
  this->PreparedEnds = result->ends;
  this->showPreparedEnds();
  QString report = QString("Prepared for CFD: %1 ends, capped and labelled (wall 1, ends 2..)\n")
                     .arg(result->ends.size());
  for (const bender::CfdEnd& end : result->ends)
  {
    report += QString("  %1 (%2, id %3): radius %4 mm, extension %5 mm")
                .arg(QString::fromStdString(end.name))
                .arg(bender::PatchTypeName(end.type))
                .arg(end.id)
                .arg(end.radius, 0, 'f', 2)
                .arg(end.extensionLength, 0, 'f', 1);
    if (end.clipDistance >= 0)
    {
      report += QString(", cut %1 mm from the end").arg(end.clipDistance, 0, 'f', 2);
    }
    report += "\n";
  }
  for (const std::string& warning : result->warnings)
  {
    report += "  warning: " + QString::fromStdString(warning) + "\n";
  }
  this->Panel->showReport(report + "Undo (Ctrl+Z) gives back the surface before.");
  bool extended = false;
  for (const bender::CfdEnd& end : result->ends)
  {
    extended = extended || end.extensionLength > 0;
  }
  this->Session.AddMessage(bender::MessageSeverity::Info,
    "Prepared for CFD: " + std::to_string(result->ends.size()) + " ends" +
      (result->ends.front().clipDistance >= 0 ? " clipped," : "") + (extended ? " extended," : "") +
      " capped and labelled (Export panel; Ctrl+Z undoes it)");
}

bool ExportFlow::exportSurface(const QString& path, bool proceedOnProblems)
{
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  // Interactive: check first, ask on problems, then write (a second job); no result is claimed
  // while the question is open.
  const bool proceed = proceedOnProblems && !this->Interactive;
  const std::string name = QFileInfo(path).fileName().toStdString();
  return this->Worker->runSessionJob(this->Session,
    this->Session.BeginExport(
      path.toStdString(), this->Panel->options(path), proceed, this->Interactive),
    [this, path, name](bender::SessionJob& job, bool ok)
    {
      this->Panel->showReport(
        QString::fromStdString(bender::FormatReportText(job.GetReport(), name)));
      if (ok)
      {
        this->Actions->addRecentFile(path);
        return;
      }
      if (job.GetOutcome() != bender::SessionJob::Outcome::Done || job.GetReport().Clean() ||
        !this->Interactive)
      {
        return;
      }
      QString problems;
      for (const auto& problem : job.GetReport().problems)
        problems += "- " + QString::fromStdString(problem) + "\n";
      // After this job has ended (the worker takes one job at a time).
      QTimer::singleShot(
        0, this, [this, path, problems]() { this->askToExportAnyway(path, problems); });
    });
}

void ExportFlow::askToExportAnyway(const QString& path, const QString& problems)
{
  QMessageBox question(QMessageBox::Warning,
    "The surface has problems",
    "The check found:\n" + problems + "\nExport anyway?",
    QMessageBox::Yes | QMessageBox::No,
    this->Window);
  question.setObjectName("exportAnywayQuestion");
  question.setDefaultButton(QMessageBox::No);
  if (question.exec() == QMessageBox::Yes)
  {
    this->Worker->runSessionJob(this->Session,
      this->Session.BeginExport(path.toStdString(), this->Panel->options(path), true));
    return;
  }
  this->Session.AddMessage(
    bender::MessageSeverity::Warning, "Export not written: the check found problems");
}

bool ExportFlow::checkSurface()
{
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  const std::string name = this->Session.GetSurfaceName();
  return this->Worker->runSessionJob(this->Session,
    this->Session.BeginCheck(),
    [this, name](bender::SessionJob& job, bool)
    {
      this->Panel->showReport(
        QString::fromStdString(bender::FormatReportText(job.GetReport(), name)));
    });
}
