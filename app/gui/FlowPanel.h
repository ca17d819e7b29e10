#ifndef FlowPanel_h
#define FlowPanel_h

#include "CfdComparison.h"
#include "FlowCacheTrim.h"
#include "FlowStudy.h"

#include <QString>
#include <QWidget>

#include <vtkWeakPointer.h>

#include <memory>

namespace bender
{
class BenderSession;
}
class FlowComparisonTable;
class FlowReportSaver;
class FlowResidualPlot;
class FlowViews;
class MainActions;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;
class QToolButton;
class SweepControls;
class WorkRunner;
class vtkRenderer;

/// The Flow panel (issue 23, "original vs candidate, side by side"): "Run flow for the original
/// and the current shape" runs bender::RunFlowStudy as one job on the window's worker: both
/// shapes at once where the machine has a core for each case, else one after the other
/// (progress in the status bar from the Allrun's steps and the solver's iterations, named after
/// the shape; Cancel there or here; the window keeps drawing), with both residuals plotted live.
/// The cases go to the flow cache (FlowCaseCache.h): a shape solved before is not solved again.
/// When both are in, the comparison window shows the two shapes in linked views (FlowViews) and the
/// table of bender::CompareCfdResults (FlowComparisonTable), the same table bender-cli compare
/// prints for the two case folders. The panel keeps only what it shows: the last results and the
/// input of the run under way. Results of a shape the session no longer has (a later bend, an undo,
/// another surface) are marked stale, in the panel and the comparison window, until the session is
/// back at that shape or the flow is run again. "Save report" writes the report of the two cases
/// shown (FlowReportSaver). After a run the flow cache is trimmed to its limits (FlowCacheTrim.h),
/// never removing the cases shown.
class FlowPanel : public QWidget
{
  Q_OBJECT
public:
  FlowPanel(bender::BenderSession& session,
    WorkRunner* worker,
    MainActions* actions,
    QWidget* parent = nullptr);
  ~FlowPanel() override;

  /// Starts the two jobs; false (with the reason in the panel) when there is no surface, a
  /// bend is held, the worker is busy or a run is under way.
  bool runFlow();
  /// Asks the job under way to stop (as the status bar's Cancel).
  void cancel();
  bool isRunning() const { return this->Running; }
  /// Enables Run for a session that can run (a surface, no grab, not running); marks the
  /// results stale when the session's shape is no longer the one they are of.
  void sessionChanged();
  /// The results shown are of a shape the session no longer has.
  bool isStale() const { return this->Stale; }
  /// Saves the report of the cases shown into `folder` (FlowReportSaver::save: asks before
  /// replacing files there); false when nothing was started.
  bool saveReport(const QString& folder);

  /// The renderer whose camera the comparison's views take their viewpoint from (the main 3D
  /// view's); the sweep's views too.
  void setViewRenderer(vtkRenderer* renderer);
  /// Where the cases are kept; default: the user's cache folder, "flow" in it.
  void setCacheFolder(const QString& folder);
  QString cacheFolder() const { return this->CacheFolder; }
  /// How much the flow cache may hold; trimmed to it after each run.
  void setCacheLimits(const bender::FlowCacheLimits& limits) { this->CacheLimits = limits; }
  /// The case settings from the panel's fields (iterations, cell size in mm; the rest
  /// CfdCaseOptions' defaults).
  bender::CfdCaseOptions caseOptions() const;

  /// 0 the original, 1 the current shape: the last run's results (null until in).
  const bender::FlowShapeResult* result(int which) const;
  const bender::CfdComparison* comparison() const;
  FlowResidualPlot* plot() const { return this->Plot; }
  FlowViews* views() const { return this->Views; }
  FlowComparisonTable* table() const { return this->Table; }
  /// The window of the two views and the table (shown when both results are in).
  QWidget* comparisonWindow() const { return this->Comparison; }
  QLabel* statusLabel() const { return this->Status; }
  QSpinBox* iterationsBox() const { return this->Iterations; }
  QDoubleSpinBox* cellSizeBox() const { return this->CellSize; }
  QToolButton* runButton() const { return this->Run; }
  QPushButton* cancelButton() const { return this->CancelButton; }
  QPushButton* saveReportButton() const { return this->SaveReport; }
  FlowReportSaver* reportSaver() const { return this->Reports; }
  /// The sweep: a sweep folder opened, or the bend's fraction swept with the case above.
  SweepControls* sweepControls() const { return this->Sweep; }

signals:
  /// Both shapes' results are shown (ok), or the run stopped (failed or cancelled).
  void flowFinished(bool ok);

private:
  void startStudy();
  void studyDone(const bender::FlowStudyResult& study);
  void stop(const QString& why);
  void showComparison();
  void setStatus(const QString& text);
  void showStale(bool stale);
  /// Trims the flow cache to CacheLimits; what it removed, for the status bar ("" for none).
  std::string trimCache();

  bender::BenderSession& Session;
  WorkRunner* Worker;
  MainActions* Actions;
  QString CacheFolder;
  vtkRenderer* ViewRenderer = nullptr; ///< not owned
  bool Running = false;
  std::shared_ptr<const bender::FlowStudyInput> Input; ///< of the run under way
  std::shared_ptr<bender::FlowShapeResult> Results[2];
  std::unique_ptr<bender::CfdComparison> Compared;
  /// The session's shapes the results are of (not owned: gone when the session drops them).
  vtkWeakPointer<vtkPolyData> RunFirst, RunCurrent;
  bender::WarpPlan RunPlan; ///< the plan of the results' run (for the report)
  bool Stale = false;
  QString DoneText; ///< the status line of the results
  bender::FlowCacheLimits CacheLimits;

  QSpinBox* Iterations = nullptr;
  QDoubleSpinBox* CellSize = nullptr;
  QToolButton* Run = nullptr;
  QPushButton* CancelButton = nullptr;
  QPushButton* ShowComparison = nullptr;
  QPushButton* SaveReport = nullptr;
  FlowReportSaver* Reports = nullptr;
  QLabel* StaleNote = nullptr; ///< in the comparison window
  QLabel* Status = nullptr;
  FlowResidualPlot* Plot = nullptr;
  QLabel* Summary = nullptr;
  QWidget* Comparison = nullptr;
  FlowViews* Views = nullptr;
  FlowComparisonTable* Table = nullptr;
  QLabel* Cases = nullptr;
  SweepControls* Sweep = nullptr;
};

#endif
