#include "ExportFlow.h"

#include "BenderSession.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "WorkRunner.h"

#include "BenderErrors.h"
#include "PrepareForCfd.h"

#include <vtkPolyData.h>

#include <QAction>
#include <QApplication>
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
  const QString suffix = QFileInfo(f).suffix().toLower();
  const std::pair<const char*, int> formats[] = { { "vtp", ExportOptionsForm::Vtp },
    { "ply", ExportOptionsForm::Ply },
    { "obj", ExportOptionsForm::Obj },
    { "smesh", ExportOptionsForm::TetgenSmesh } };
  this->setPath(f);
  for (const auto& [ext, format] : formats)
  {
    if (suffix == ext)
    {
      this->Form->Formats->setCurrentIndex(format);
    }
  }
  if (suffix == "stl" && !this->Form->suffix().endsWith("stl"))
  {
    this->Form->Formats->setCurrentIndex(ExportOptionsForm::StlBinary);
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
  const bool again =
    this->PreparedFrom && current == this->Prepared && current->GetMTime() == this->PreparedTime;
  if (!again)
  {
    this->Panel->clearEnds(); // the listed ends belong to another surface
  }
  vtkSmartPointer<vtkPolyData> source = again ? this->PreparedFrom : nullptr;
  if (!source)
  {
    source = vtkSmartPointer<vtkPolyData>::New();
    source->DeepCopy(current);
  }
  bender::PrepareForCfdOptions options = this->Panel->prepareOptions();
  const std::string name = this->Session.GetSurfaceName();
  options.InputName = name.empty() ? "the surface" : name;
  bender::PrepareForCfdResult result;
  QApplication::setOverrideCursor(Qt::WaitCursor);
  try
  {
    result = bender::PrepareForCfd(source, options);
  }
  catch (const std::exception& e)
  {
    QApplication::restoreOverrideCursor();
    this->Panel->showReport(QString("Prepare for CFD failed: ") + e.what());
    return false;
  }
  QApplication::restoreOverrideCursor();
  if (!this->Session.SetSurface(result.Surface, name, this->Session.GetSourcePath()))
  {
    this->Panel->showReport("Prepare for CFD: the prepared surface could not be loaded.");
    return false;
  }
  this->PreparedFrom = source;
  this->Prepared = this->Session.GetSurface();
  this->PreparedTime = this->Prepared ? this->Prepared->GetMTime() : 0;
  this->Panel->showEnds(result.Ends);
  QString report = QString("Prepared for CFD: %1 ends, capped and labelled (wall 1, ends 2..)\n")
                     .arg(result.Ends.size());
  for (const bender::CfdEnd& end : result.Ends)
  {
    report += QString("  %1 (%2, id %3): radius %4 mm, extension %5 mm\n")
                .arg(QString::fromStdString(end.Name))
                .arg(bender::PatchTypeName(end.Type))
                .arg(end.Id)
                .arg(end.Radius, 0, 'f', 2)
                .arg(end.ExtensionLength, 0, 'f', 1);
  }
  for (const std::string& warning : result.Warnings)
  {
    report += "  warning: " + QString::fromStdString(warning) + "\n";
  }
  this->Panel->showReport(report);
  return true;
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
