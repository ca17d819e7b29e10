#include "ExportFlow.h"

#include "BenderSession.h"
#include "BenderView.h"
#include "CfdEndsOverlay.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "VesselController.h"
#include "WorkRunner.h"

#include "BenderErrors.h"
#include "PrepareForCfd.h"

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
#include <QTimer>
#include <QVBoxLayout>

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
  const QString f =
    QFileDialog::getSaveFileName(this, "Export surface", this->path(), ExportPanel::fileFilter());
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
  if (this->path().isEmpty())
  {
    this->Problem->setText("Choose the file to write.");
    return;
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
      const QString f = QFileDialog::getSaveFileName(
        this->Window, "Save plan", "plan.bender.json", "Plans (*.bender.json)");
      if (!f.isEmpty())
        this->Session.SavePlan(f.toStdString());
    });
}

ExportDialog* ExportFlow::openExportDialog()
{
  QString path = this->LastPath;
  if (path.isEmpty())
  {
    const QString name =
      QFileInfo(QString::fromStdString(this->Session.GetSurfaceName())).completeBaseName();
    path = QDir::current().filePath(
      (name.isEmpty() ? QString("vessel") : name) + "_export" + this->Panel->form()->suffix());
  }
  auto* dialog = new ExportDialog(*this->Panel->form(), path, this->Window);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  connect(dialog,
    &QDialog::accepted,
    this,
    [this, dialog]()
    {
      this->Panel->form()->copyFrom(*dialog->form());
      this->LastPath = dialog->path();
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
  if (current && current == this->Prepared && current->GetMTime() == this->PreparedTime)
  {
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

void ExportFlow::followSurface()
{
  if (!this->Overlay)
  {
    return;
  }
  vtkPolyData* current = this->Session.HasSurface() ? this->Session.GetSurface() : nullptr;
  const bool prepared =
    current && current == this->Prepared && current->GetMTime() == this->PreparedTime;
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
  const bool again =
    this->PreparedFrom && current == this->Prepared && current->GetMTime() == this->PreparedTime;
  const bool listed = this->Panel->listsCenterlineEnds() && this->EndCenterlines &&
    current == this->EndsFor && current->GetMTime() == this->EndsForTime;
  if (!again && !listed)
  {
    this->Panel->clearEnds(); // the listed ends belong to another surface
  }
  vtkSmartPointer<vtkPolyData> source = again ? this->PreparedFrom : nullptr;
  if (!source)
  {
    source = vtkSmartPointer<vtkPolyData>::New();
    source->DeepCopy(current);
  }
  // The centerlines the discs were placed on (the cuts are arc lengths on them); computed in
  // the job when there are none yet.
  vtkSmartPointer<vtkPolyData> centerlines;
  vtkPolyData* known = again ? this->PreparedCenterlines.GetPointer()
                             : (listed ? this->EndCenterlines.GetPointer() : nullptr);
  if (known)
  {
    centerlines = vtkSmartPointer<vtkPolyData>::New();
    centerlines->DeepCopy(known); // the job's own copy
  }
  bender::PrepareForCfdOptions options = this->Panel->prepareOptions();
  options.centerlines = centerlines;
  const std::string name = this->Session.GetSurfaceName();
  options.inputName = name.empty() ? "the surface" : name;
  const vtkMTimeType time = current->GetMTime();
  QPointer<ExportFlow> self(this);
  return this->Worker->run("Prepare for CFD",
    [self, source, options, centerlines, current, time](
      const bender::ProgressReporter& progress) -> WorkRunner::Finisher
    {
      auto result = std::make_shared<bender::PrepareForCfdResult>();
      try
      {
        *result = bender::PrepareForCfd(source, options, progress);
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
      return [self, result, source, centerlines, current, time]()
      {
        if (self)
        {
          self->applyPrepared(result, source, centerlines, current, time);
        }
      };
    });
}

void ExportFlow::applyPrepared(const std::shared_ptr<bender::PrepareForCfdResult>& result,
  const vtkSmartPointer<vtkPolyData>& source,
  const vtkSmartPointer<vtkPolyData>& centerlines,
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
  const std::string name = this->Session.GetSurfaceName();
  if (!this->Session.SetSurface(result->surface, name, this->Session.GetSourcePath()))
  {
    this->Panel->showReport("Prepare for CFD: the prepared surface could not be loaded.");
    this->Worker->markFailed();
    return;
  }
  this->PreparedFrom = source;
  this->PreparedCenterlines = centerlines;
  this->Prepared = this->Session.GetSurface();
  this->PreparedTime = this->Prepared ? this->Prepared->GetMTime() : 0;
  this->Panel->showEnds(result->ends);
  if (this->Overlay)
  {
    this->Overlay->setPatches(this->Prepared, result->ends);
    this->showOverlay();
    this->renderView();
  }
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
  this->Panel->showReport(report);
  bool extended = false;
  for (const bender::CfdEnd& end : result->ends)
  {
    extended = extended || end.extensionLength > 0;
  }
  this->Session.AddMessage(bender::MessageSeverity::Info,
    "Prepared for CFD: " + std::to_string(result->ends.size()) + " ends" +
      (result->ends.front().clipDistance >= 0 ? " clipped," : "") + (extended ? " extended," : "") +
      " capped and labelled (Export panel)");
}

bool ExportFlow::exportSurface(const QString& path, bool proceedOnProblems)
{
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  // Interactive: check first, ask on problems, then write (a second job).
  const bool proceed = proceedOnProblems && !this->Interactive;
  const std::string name = QFileInfo(path).fileName().toStdString();
  return this->Worker->runSessionJob(this->Session,
    this->Session.BeginExport(path.toStdString(), this->Panel->options(path), proceed),
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
  if (QMessageBox::warning(this->Window,
        "The surface has problems",
        "The check found:\n" + problems + "\nExport anyway?",
        QMessageBox::Yes | QMessageBox::No,
        QMessageBox::No) == QMessageBox::Yes)
  {
    this->Worker->runSessionJob(this->Session,
      this->Session.BeginExport(path.toStdString(), this->Panel->options(path), true));
  }
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
