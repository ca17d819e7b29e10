#include "FlowReportSaver.h"

#include "FileOpener.h"
#include "WorkRunner.h"

#include "BenderErrors.h"
#include "BenderSession.h"
#include "CfdCaseComparison.h"
#include "FlowPictures.h"
#include "FlowReport.h"
#include "WarpPlanIO.h"

#include <QAbstractButton>
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QPointer>

#include <memory>

namespace
{
const char* const PdfName = "flow-report.pdf";
const char* const PlanName = "flow-plan.bender.json";
} // namespace

FlowReportSaver::FlowReportSaver(bender::BenderSession& session,
  WorkRunner* worker,
  QWidget* dialogParent)
  : QObject(dialogParent)
  , Session(session)
  , Worker(worker)
  , DialogParent(dialogParent)
{
}

QString FlowReportSaver::pdfIn(const QString& folder)
{
  return QDir(folder).filePath(PdfName);
}

QStringList FlowReportSaver::filesIn(const QString& folder)
{
  QStringList files{ pdfIn(folder) };
  const bender::FlowPictureOptions pictures;
  for (const bender::FlowQuantity& quantity : bender::FlowQuantities())
  {
    for (const bender::RenderView view : pictures.views)
    {
      files << QDir(folder).filePath(
        QString::fromStdString(quantity.key + "-" + bender::RenderViewName(view) + ".png"));
    }
  }
  files << QDir(folder).filePath(PlanName);
  return files;
}

void FlowReportSaver::saveAsked(const Source& source)
{
  const QString folder = QFileDialog::getExistingDirectory(
    this->DialogParent, "Save the flow report into a folder", FileOpener::lastFolder("report"));
  if (folder.isEmpty())
  {
    return;
  }
  FileOpener::rememberFolder("report", QDir(folder).filePath(PdfName));
  this->save(folder, source);
}

bool FlowReportSaver::replaceAllowed(const QString& folder) const
{
  QStringList there;
  for (const QString& file : filesIn(folder))
  {
    if (QFileInfo::exists(file))
    {
      there << QFileInfo(file).fileName();
    }
  }
  if (there.isEmpty())
  {
    return true;
  }
  QMessageBox question(QMessageBox::Question,
    "Replace the flow report?",
    QString("%1 already holds a flow report (%2). Replace it?")
      .arg(QDir::toNativeSeparators(folder), there.join(", ")),
    QMessageBox::Yes | QMessageBox::No,
    this->DialogParent);
  question.setObjectName("replaceFlowReport");
  question.button(QMessageBox::Yes)->setText("Replace");
  question.button(QMessageBox::No)->setText("Keep them");
  question.setDefaultButton(QMessageBox::No);
  return question.exec() == QMessageBox::Yes;
}

bool FlowReportSaver::save(const QString& folder, const Source& source)
{
  if (source.caseA.empty() || source.caseB.empty())
  {
    this->Session.AddMessage(
      bender::MessageSeverity::Error, "Flow report: run the flow of both shapes first");
    return false;
  }
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    return false;
  }
  if (!this->replaceAllowed(folder))
  {
    this->Session.AddMessage(bender::MessageSeverity::Info,
      "Flow report: not saved; the files in " + folder.toStdString() + " were kept");
    return false;
  }
  const std::string dir = QDir(folder).absolutePath().toStdString();
  const std::string pdf = pdfIn(QString::fromStdString(dir)).toStdString();
  const std::string plan = QDir(QString::fromStdString(dir)).filePath(PlanName).toStdString();
  QPointer<FlowReportSaver> self(this);
  // The comparison (reading both cases, measuring the bends) runs on the worker; the pictures
  // and the PDF are drawn on this thread when it is done: VTK's rendering and text drawing are
  // not thread-safe, and the window's own views render here at the same time.
  const bool started = this->Worker->run("Flow report",
    [self, source, dir, pdf, plan](const bender::ProgressReporter& progress) -> WorkRunner::Finisher
    {
      std::string problem;
      auto comparison = std::make_shared<bender::CfdCaseComparison>();
      const bool planThere = QFileInfo::exists(QString::fromStdString(plan));
      try
      {
        QDir().mkpath(QString::fromStdString(dir));
        if (!QFileInfo(QString::fromStdString(dir)).isDir())
        {
          throw bender::InputError(dir + ": the report's folder cannot be made");
        }
        bender::WriteWarpPlan(source.plan, plan);
        bender::CompareCfdCasesOptions compare;
        compare.caseA = source.caseA;
        compare.caseB = source.caseB;
        compare.plan = plan;
        compare.progress = progress;
        *comparison = bender::CompareCfdCases(compare);
        progress.ThrowIfCancelled("pictures");
      }
      catch (const bender::Cancelled&)
      {
        throw; // the worker says so
      }
      catch (const std::exception& e)
      {
        // The boundary of the job: every failure is one line in the status bar.
        problem = std::string("Flow report not saved: ") + e.what();
      }
      return [self, problem, comparison, dir, pdf, plan, planThere]()
      {
        std::string failed = problem;
        bender::FlowReportResult written;
        if (failed.empty())
        {
          QApplication::setOverrideCursor(Qt::WaitCursor);
          try
          {
            bender::FlowReportOptions report;
            report.output = pdf;
            report.pngFolder = dir;
            written = bender::WriteFlowReport(*comparison, report);
          }
          catch (const std::exception& e)
          {
            // The boundary of the drawing: one line in the status bar.
            failed = std::string("Flow report not saved: ") + e.what();
          }
          QApplication::restoreOverrideCursor();
        }
        if (!failed.empty() && !planThere)
        {
          // A plan written for a report that failed does not stay behind.
          QFile::remove(QString::fromStdString(plan));
        }
        if (!self)
        {
          return;
        }
        if (!failed.empty())
        {
          self->Session.AddMessage(bender::MessageSeverity::Error, failed);
          self->Worker->markFailed();
          emit self->saved(false, QString());
          return;
        }
        self->Session.AddMessage(bender::MessageSeverity::Info,
          "Flow report saved: " + written.pdf + " (" + std::to_string(written.pages) +
            " pages), its " + std::to_string(written.pngs.size()) +
            " pictures and the plan beside it");
        emit self->saved(true, QString::fromStdString(written.pdf));
      };
    });
  return started;
}
