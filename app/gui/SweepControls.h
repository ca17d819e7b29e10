#ifndef SweepControls_h
#define SweepControls_h

#include "CfdCase.h"

#include <QGroupBox>
#include <QString>

#include <functional>

namespace bender
{
class BenderSession;
}
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;
class SweepWindow;
class WorkRunner;
class vtkRenderer;

/// The Flow panel's sweep (issue 24, "In the application"): a sweep folder opened (made by
/// bender-cli sweep on this machine or a cluster, finished or not), or a local sweep of the
/// current bend's fraction started into it as a job on the window's worker (progress in the
/// status bar, Cancel there or here; bender::RunSessionSweep with the panel's case settings).
/// Either way the sweep window (SweepWindow) shows its plot, its table and the chosen
/// candidate beside the original.
class SweepControls : public QGroupBox
{
  Q_OBJECT
public:
  SweepControls(bender::BenderSession& session,
    WorkRunner* worker,
    std::function<bender::CfdCaseOptions()> caseOptions,
    QWidget* parent = nullptr);
  ~SweepControls() override;

  /// Reads the folder of the folder box into the sweep window and shows it; false (the reason
  /// in the status line) when it is not a sweep folder.
  bool openSweep();
  /// Starts the local sweep of the bend's fraction (From, To, Count) into the folder box's
  /// folder; false (the reason in the status line) when there is no bend, no folder, or the
  /// worker is busy.
  bool startSweep();
  void cancel();
  bool isRunning() const { return this->Running; }
  /// The renderer whose camera the sweep's views take their viewpoint from (the main view's).
  void setViewRenderer(vtkRenderer* renderer);

  QLineEdit* folderBox() const { return this->Folder; }
  QDoubleSpinBox* fromBox() const { return this->From; }
  QDoubleSpinBox* toBox() const { return this->To; }
  QSpinBox* countBox() const { return this->Count; }
  QSpinBox* jobsBox() const { return this->Jobs; }
  QPushButton* openButton() const { return this->Open; }
  QPushButton* sweepButton() const { return this->Start; }
  QPushButton* cancelButton() const { return this->CancelButton; }
  QLabel* statusLabel() const { return this->Status; }
  SweepWindow* window() const { return this->Window; }

signals:
  /// The sweep job ended: every candidate solved or rejected (ok), or it failed or was
  /// cancelled (what it left is shown).
  void sweepFinished(bool ok);

private:
  void setStatus(const QString& text);
  /// Shows the folder's sweep; false with the reason in the status line.
  bool show(const QString& folder);
  void done(bool ok, const QString& why);

  bender::BenderSession& Session;
  WorkRunner* Worker;
  std::function<bender::CfdCaseOptions()> CaseOptions;
  bool Running = false;
  QLineEdit* Folder = nullptr;
  QDoubleSpinBox* From = nullptr;
  QDoubleSpinBox* To = nullptr;
  QSpinBox* Count = nullptr;
  QSpinBox* Jobs = nullptr;
  QPushButton* Open = nullptr;
  QPushButton* Start = nullptr;
  QPushButton* CancelButton = nullptr;
  QLabel* Status = nullptr;
  SweepWindow* Window = nullptr;
};

#endif
