#ifndef WorkRunner_h
#define WorkRunner_h

#include "Progress.h"

#include <QFutureWatcher>
#include <QObject>
#include <QString>

#include <atomic>
#include <functional>
#include <memory>

namespace bender
{
class BenderSession;
class SessionJob;
}

class QLabel;
class QProgressBar;
class QPushButton;
class QStatusBar;

/// The window's worker: one job at a time on a pool thread, with a progress bar and a Cancel
/// button in the status bar. A job computes on the worker and returns a finisher that runs on
/// the GUI thread (where the sessions are changed). Errors are typed: bender::Cancelled (the
/// Cancel button) and other exceptions end the job as failed, with a message through `report`.
/// The GUI thread never waits for a job.
class WorkRunner : public QObject
{
  Q_OBJECT
public:
  using Finisher = std::function<void()>;
  using Work = std::function<Finisher(const bender::ProgressReporter&)>;
  /// severity 0 info, 1 warning, 2 error (bender::MessageSeverity's order).
  using Reporter = std::function<void(int severity, const std::string& text)>;

  WorkRunner(QStatusBar* bar, QLabel* status, Reporter report, QObject* parent);
  ~WorkRunner() override;

  /// Starts `work`; false (nothing started) while another job runs.
  bool run(const QString& title, Work work);
  bool isBusy() const { return this->Pending; }
  /// Marks the running job as failed (its finisher found a problem).
  void markFailed() { this->Failed = true; }
  /// For tests and scripts: waits (processing events) until no job runs and `busy` (when
  /// given) is false; false on timeout. The window itself never waits.
  bool waitUntilIdle(int milliseconds, const std::function<bool()>& busy = {});
  /// Asks the running job to stop, as the Cancel button does (a panel's own Cancel).
  void cancel();
  /// Asks the running job to stop and waits for the worker (closing the window).
  void cancelAndWait();
  /// Called on the worker at the start of every job (tests).
  std::function<void(const bender::ProgressReporter&)> Hook;

  /// A second lane for analysis that the user does not wait for (the vessel centerlines): one
  /// such job at a time, beside the main job, no progress bar and no Cancel button (it does not
  /// block the main job: a release is never refused because the centerlines are computing).
  /// Its finisher runs on the GUI thread; an exception ends it with `failed(what)` called there.
  /// False (nothing started) while one runs.
  bool runInBackground(Work work, std::function<void(const std::string&)> failed);
  bool isBackgroundBusy() const { return this->BackgroundPending; }

  ///@{ Jobs of a session (its messages say why a job failed)
  /// True, with an error message in `session`, while a job runs.
  bool refuseWhenBusy(bender::BenderSession& session);
  /// Like run(); the job also fails when its finisher adds an error message to `session`.
  bool runReporting(bender::BenderSession& session, const QString& title, Work work);
  /// A SessionJob: Run on the worker, BenderSession::Finish on the GUI thread, then `then`
  /// (with whether it succeeded). False when `job` is null (the session refused it).
  bool runSessionJob(bender::BenderSession& session,
    const std::shared_ptr<bender::SessionJob>& job,
    std::function<void(bender::SessionJob&, bool)> then = {});
  ///@}

signals:
  /// The background job's finisher ran (or its failure was reported).
  void backgroundFinished();
  /// A job started (the window disables what a busy session refuses).
  void started();
  void finished(bool succeeded);

private:
  void finish();

  QFutureWatcher<Finisher> Watcher;
  QFutureWatcher<Finisher> BackgroundWatcher;
  std::atomic<bool> BackgroundCancel{ false };
  bool BackgroundPending = false;
  QProgressBar* Progress;
  QPushButton* Cancel;
  QLabel* Status;
  Reporter Report;
  std::atomic<bool> CancelFlag{ false };
  bool Pending = false;
  bool Failed = false;
};

#endif
