#include "WorkRunner.h"

#include "BenderSession.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QLabel>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QStatusBar>
#include <QtConcurrent/QtConcurrent>

#include <algorithm>
#include <cmath>
#include <exception>

WorkRunner::WorkRunner(QStatusBar* bar, QLabel* status, Reporter report, QObject* parent)
  : QObject(parent)
  , Status(status)
  , Report(std::move(report))
{
  this->Progress = new QProgressBar(bar);
  this->Progress->setRange(0, 100);
  // The text ("Segmenting: surface 40%") is longer than a bar: wider, and whole in the tooltip.
  this->Progress->setMinimumWidth(200);
  this->Progress->setMaximumWidth(380);
  connect(this->Progress,
    &QProgressBar::valueChanged,
    this->Progress,
    [progress = this->Progress]() { progress->setToolTip(progress->text()); });
  this->Progress->hide();
  bar->addPermanentWidget(this->Progress);
  this->Cancel = new QPushButton("Cancel", bar);
  this->Cancel->setObjectName("cancelWork");
  this->Cancel->hide();
  bar->addPermanentWidget(this->Cancel);
  connect(this->Cancel, &QPushButton::clicked, this, &WorkRunner::cancel);
  connect(&this->Watcher, &QFutureWatcher<Finisher>::finished, this, &WorkRunner::finish);
  connect(&this->BackgroundWatcher,
    &QFutureWatcher<Finisher>::finished,
    this,
    [this]()
    {
      Finisher finisher = this->BackgroundWatcher.result();
      this->BackgroundPending = false;
      if (finisher)
      {
        finisher();
      }
      emit this->backgroundFinished();
    });
}

WorkRunner::~WorkRunner()
{
  this->cancelAndWait();
}

bool WorkRunner::waitUntilIdle(int milliseconds, const std::function<bool()>& busy)
{
  QElapsedTimer timer;
  timer.start();
  while ((busy && busy()) || this->Pending)
  {
    if (timer.elapsed() > milliseconds)
    {
      return false;
    }
    QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
  }
  return true;
}

void WorkRunner::cancel()
{
  if (this->Pending)
  {
    this->CancelFlag = true;
    this->Status->setText("Cancelling...");
  }
}

void WorkRunner::cancelAndWait()
{
  this->CancelFlag = true;
  this->BackgroundCancel = true;
  this->Watcher.waitForFinished();
  this->BackgroundWatcher.waitForFinished();
}

bool WorkRunner::runInBackground(Work work, std::function<void(const std::string&)> failed)
{
  if (this->BackgroundPending)
  {
    return false;
  }
  this->BackgroundCancel = false;
  this->BackgroundPending = true;
  bender::ProgressReporter reporter;
  reporter.cancel = &this->BackgroundCancel;
  this->BackgroundWatcher.setFuture(QtConcurrent::run(
    [work, reporter, failed]() -> Finisher
    {
      try
      {
        return work(reporter);
      }
      catch (const std::exception& e)
      {
        const std::string what = e.what();
        return [failed, what]()
        {
          if (failed)
          {
            failed(what);
          }
        };
      }
    }));
  return true;
}

bool WorkRunner::run(const QString& title, Work work)
{
  if (this->Pending)
  {
    this->Report(2, "Busy: wait for the current task or cancel it");
    return false;
  }
  this->CancelFlag = false;
  this->Pending = true;
  this->Failed = false;
  this->Progress->setValue(0);
  this->Progress->setFormat(title + " %p%");
  this->Progress->show();
  this->Cancel->show();
  this->Status->setStyleSheet("");
  this->Status->setText(title + "...");
  bender::ProgressReporter reporter;
  reporter.cancel = &this->CancelFlag;
  QPointer<QProgressBar> bar(this->Progress);
  reporter.onProgress = [bar, title](const std::string& stage, double fraction)
  {
    QMetaObject::invokeMethod(
      qApp,
      [bar, title, stage, fraction]()
      {
        if (bar)
        {
          bar->setValue(static_cast<int>(std::lround(100.0 * fraction)));
          bar->setFormat(title + ": " + QString::fromStdString(stage) + " %p%");
        }
      },
      Qt::QueuedConnection);
  };
  auto hook = this->Hook;
  this->Watcher.setFuture(QtConcurrent::run(
    [this, work, reporter, hook]() -> Finisher
    {
      try
      {
        if (hook)
        {
          hook(reporter);
        }
        return work(reporter);
      }
      catch (const bender::Cancelled& e)
      {
        const std::string what = e.what();
        return [this, what]()
        {
          this->Failed = true;
          this->Report(1, "Cancelled: " + what + "; nothing was changed");
        };
      }
      catch (const std::exception& e)
      {
        const std::string what = e.what();
        return [this, what]()
        {
          this->Failed = true;
          this->Report(2, what);
        };
      }
    }));
  emit this->started();
  return true;
}

bool WorkRunner::refuseWhenBusy(bender::BenderSession& session)
{
  if (!this->Pending)
  {
    return false;
  }
  session.AddMessage(
    bender::MessageSeverity::Error, "Busy: wait for the current task or cancel it");
  return true;
}

bool WorkRunner::runReporting(bender::BenderSession& session, const QString& title, Work work)
{
  bender::BenderSession* s = &session;
  return this->run(title,
    [this, s, work](const bender::ProgressReporter& progress)
    {
      Finisher finisher = work(progress);
      // A finisher that reports an error (a surface refused, ...) fails the job.
      return Finisher(
        [this, s, finisher]()
        {
          const std::size_t before = s->GetMessages().size();
          finisher();
          const auto& messages = s->GetMessages();
          if (std::any_of(messages.begin() + static_cast<std::ptrdiff_t>(before),
                messages.end(),
                [](const bender::LogicMessage& m)
                { return m.severity == bender::MessageSeverity::Error; }))
          {
            this->markFailed();
          }
        });
    });
}

bool WorkRunner::runSessionJob(bender::BenderSession& session,
  const std::shared_ptr<bender::SessionJob>& job,
  std::function<void(bender::SessionJob&, bool)> then)
{
  if (!job)
  {
    return false;
  }
  bender::BenderSession* s = &session;
  return this->runReporting(session,
    QString::fromStdString(job->GetTitle()),
    [this, s, job, then](const bender::ProgressReporter& progress)
    {
      job->Run(progress);
      return Finisher(
        [this, s, job, then]()
        {
          const bool ok = s->Finish(*job);
          if (!ok)
          {
            this->markFailed();
          }
          if (then)
          {
            then(*job, ok);
          }
        });
    });
}

void WorkRunner::finish()
{
  this->Progress->hide();
  this->Cancel->hide();
  Finisher finisher = this->Watcher.result();
  if (finisher)
  {
    finisher();
  }
  this->Pending = false;
  emit this->finished(!this->Failed);
}
