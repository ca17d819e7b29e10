#include "ExportFlow.h"

#include "BenderSession.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "WorkRunner.h"

#include <QAction>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QTimer>

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
  connect(actions->Export,
    &QAction::triggered,
    this,
    [this]()
    {
      const QString f = QFileDialog::getSaveFileName(
        this->Window, "Export surface", QString(), ExportPanel::fileFilter());
      if (!f.isEmpty())
        this->exportSurface(f);
    });
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
