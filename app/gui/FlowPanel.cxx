#include "FlowPanel.h"

#include "FlowComparisonTable.h"
#include "FlowReportSaver.h"
#include "FlowResidualPlot.h"
#include "FlowViews.h"
#include "MainActions.h"
#include "SweepControls.h"
#include "WorkRunner.h"

#include "BenderSession.h"
#include "PolyDataCopy.h"

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPointer>
#include <QPushButton>
#include <QSpinBox>
#include <QStandardPaths>
#include <QToolButton>
#include <QVBoxLayout>

#include <thread>

#include <vtkRenderer.h>

namespace
{
QString ShapeTitle(int which)
{
  return which == 0 ? "original" : "current shape";
}

/// "converged in 212 iterations" / "stopped at 300 iterations, ..." with "(from the cache)".
QString RunLine(int which, const bender::FlowShapeResult& result)
{
  QString line = ShapeTitle(which) + ": " + QString::fromStdString(result.results.run.status);
  if (result.results.run.status.empty())
  {
    line += QString("%1 iterations").arg(result.results.run.iterations);
  }
  return line + (result.cached ? " (from the cache)" : "");
}
} // namespace

FlowPanel::FlowPanel(bender::BenderSession& session,
  WorkRunner* worker,
  MainActions* actions,
  QWidget* parent)
  : QWidget(parent)
  , Session(session)
  , Worker(worker)
  , Actions(actions)
{
  this->setObjectName("flowPanel");
  this->CacheFolder =
    QDir(QStandardPaths::writableLocation(QStandardPaths::CacheLocation)).filePath("flow");
  auto* layout = new QVBoxLayout(this);

  auto* settings = new QGroupBox("Case (both shapes)", this);
  auto* form = new QFormLayout(settings);
  const bender::CfdCaseOptions defaults;
  this->Iterations = new QSpinBox(settings);
  this->Iterations->setObjectName("flowIterations");
  this->Iterations->setRange(10, 20000);
  this->Iterations->setValue(defaults.iterations);
  this->Iterations->setToolTip("simpleFoam's iteration limit; the residual control may stop it "
                               "earlier (then the run is converged)");
  form->addRow("Iterations", this->Iterations);
  this->CellSize = new QDoubleSpinBox(settings);
  this->CellSize->setObjectName("flowCellSize");
  this->CellSize->setRange(0.0, 20.0);
  this->CellSize->setDecimals(2);
  this->CellSize->setSingleStep(0.05);
  this->CellSize->setSpecialValueText("auto");
  this->CellSize->setSuffix(" mm");
  this->CellSize->setToolTip("The mesh's cell size at the wall; auto: from the smallest end");
  form->addRow("Cell size", this->CellSize);
  layout->addWidget(settings);

  this->Run = ActionButton(this->Actions->RunFlow, this, "runFlow");
  layout->addWidget(this->Run);
  this->CancelButton = new QPushButton("Cancel the flow run", this);
  this->CancelButton->setObjectName("cancelFlow");
  this->CancelButton->setEnabled(false);
  layout->addWidget(this->CancelButton);
  this->Status = new QLabel("Prepare for CFD (Export panel), bend, then run the flow of both "
                            "shapes.",
    this);
  this->Status->setObjectName("flowStatus");
  this->Status->setWordWrap(true);
  layout->addWidget(this->Status);
  this->Plot = new FlowResidualPlot(this);
  layout->addWidget(this->Plot, 1);
  this->Summary = new QLabel(this);
  this->Summary->setObjectName("flowSummary");
  this->Summary->setWordWrap(true);
  this->Summary->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(this->Summary);
  this->ShowComparison = new QPushButton("Show the shapes and the table", this);
  this->ShowComparison->setObjectName("showFlowComparison");
  this->ShowComparison->setEnabled(false);
  layout->addWidget(this->ShowComparison);
  this->SaveReport = new QPushButton("Save report...", this);
  this->SaveReport->setObjectName("saveFlowReport");
  this->SaveReport->setToolTip("The report of the two cases shown (the PDF of bender-cli "
                               "compare), a PNG of each picture and the plan, into a folder");
  this->SaveReport->setEnabled(false);
  layout->addWidget(this->SaveReport);
  this->Sweep = new SweepControls(
    session, worker, [this]() { return this->caseOptions(); }, this);
  layout->addWidget(this->Sweep);
  layout->addStretch(0);
  this->Reports = new FlowReportSaver(this->Session, this->Worker, this);

  // The comparison: its own window, beside the main one (a second screen in the theatre).
  this->Comparison = new QWidget(this, Qt::Window);
  this->Comparison->setObjectName("flowComparisonWindow");
  this->Comparison->setWindowTitle("Bender - flow: original and current shape");
  this->Comparison->resize(1000, 760);
  auto* compareLayout = new QVBoxLayout(this->Comparison);
  this->StaleNote = new QLabel(this->Comparison);
  this->StaleNote->setObjectName("flowStale");
  this->StaleNote->setWordWrap(true);
  this->StaleNote->setStyleSheet("background: #d90; color: black; padding: 4px;");
  this->StaleNote->hide();
  compareLayout->addWidget(this->StaleNote);
  this->Views = new FlowViews(this->Comparison);
  compareLayout->addWidget(this->Views, 3);
  this->Table = new FlowComparisonTable(this->Comparison);
  compareLayout->addWidget(this->Table, 2);
  this->Cases = new QLabel(this->Comparison);
  this->Cases->setObjectName("flowCases");
  this->Cases->setWordWrap(true);
  this->Cases->setTextInteractionFlags(Qt::TextSelectableByMouse);
  compareLayout->addWidget(this->Cases);

  connect(this->Actions->RunFlow, &QAction::triggered, this, [this]() { this->runFlow(); });
  connect(this->CancelButton, &QPushButton::clicked, this, &FlowPanel::cancel);
  connect(this->ShowComparison, &QPushButton::clicked, this, &FlowPanel::showComparison);
  connect(this->SaveReport,
    &QPushButton::clicked,
    this,
    [this]()
    {
      if (this->Compared)
      {
        this->Reports->saveAsked(
          { this->Results[0]->caseDirectory, this->Results[1]->caseDirectory, this->RunPlan });
      }
    });
  // A job of the run that failed or was cancelled (the worker said why in the status bar).
  connect(this->Worker,
    &WorkRunner::finished,
    this,
    [this](bool ok)
    {
      if (!ok && this->Running)
      {
        this->stop("Flow stopped: the run was cancelled or failed (see the status bar).");
      }
    });
  this->sessionChanged();
}

FlowPanel::~FlowPanel() = default;

void FlowPanel::setViewRenderer(vtkRenderer* renderer)
{
  this->ViewRenderer = renderer;
  this->Sweep->setViewRenderer(renderer);
}

void FlowPanel::setCacheFolder(const QString& folder)
{
  this->CacheFolder = folder;
}

bender::CfdCaseOptions FlowPanel::caseOptions() const
{
  bender::CfdCaseOptions options;
  options.iterations = this->Iterations->value();
  options.cellSize = this->CellSize->value() * 1e-3; // mm -> m; 0: auto
  return options;
}

const bender::FlowShapeResult* FlowPanel::result(int which) const
{
  return which == 0 || which == 1 ? this->Results[which].get() : nullptr;
}

const bender::CfdComparison* FlowPanel::comparison() const
{
  return this->Compared.get();
}

void FlowPanel::sessionChanged()
{
  this->Actions->RunFlow->setEnabled(!this->Running && this->Session.HasSurface() &&
    this->Session.GetState() != bender::GrabState::Grabbed);
  this->CancelButton->setEnabled(this->Running);
  this->SaveReport->setEnabled(this->Compared && !this->Running);
  // A bend under way is not a shape yet: its release (or its cancel) says.
  if (this->Compared && this->Session.GetState() != bender::GrabState::Grabbed)
  {
    this->showStale(!this->RunCurrent || !this->RunFirst ||
      this->RunCurrent.GetPointer() != this->Session.GetSurface() ||
      this->RunFirst.GetPointer() != this->Session.GetFirstSurface());
  }
}

bool FlowPanel::saveReport(const QString& folder)
{
  if (!this->Compared || this->Running)
  {
    this->setStatus("Flow: run the flow of both shapes before saving a report.");
    return false;
  }
  return this->Reports->save(
    folder, { this->Results[0]->caseDirectory, this->Results[1]->caseDirectory, this->RunPlan });
}

void FlowPanel::showStale(bool stale)
{
  if (stale == this->Stale)
  {
    return;
  }
  this->Stale = stale;
  const QString note = "The shape changed after this run (a bend, an undo or another surface): "
                       "the results shown are of the earlier shape. Run the flow again for the "
                       "current one.";
  this->StaleNote->setText(note);
  this->StaleNote->setVisible(stale);
  this->Comparison->setWindowTitle(QString("Bender - flow: original and current shape%1")
                                     .arg(stale ? " (stale: the shape changed)" : ""));
  this->setStatus(stale ? "Stale: " + note : this->DoneText);
}

std::string FlowPanel::trimCache()
{
  const bender::FlowCacheTrimResult trimmed =
    bender::TrimFlowCache(QDir(this->CacheFolder).absolutePath().toStdString(),
      this->CacheLimits,
      { this->Results[0]->caseDirectory, this->Results[1]->caseDirectory });
  if (trimmed.removed.empty())
  {
    return std::string();
  }
  return "; the flow cache's " + std::to_string(trimmed.removed.size()) +
    " least recently used case(s) removed, " + std::to_string(trimmed.casesLeft) + " kept (" +
    std::to_string(trimmed.bytesLeft >> 20) + " MB)";
}

void FlowPanel::setStatus(const QString& text)
{
  this->Status->setText(text);
  this->Status->setToolTip(text);
}

bool FlowPanel::runFlow()
{
  if (this->Running)
  {
    this->setStatus("Flow: a run is under way (Cancel stops it).");
    return false;
  }
  if (!this->Session.HasSurface())
  {
    this->setStatus("Flow: open or segment a surface first.");
    return false;
  }
  if (this->Session.GetState() == bender::GrabState::Grabbed)
  {
    this->setStatus("Flow: release the bend first.");
    return false;
  }
  if (this->Worker->refuseWhenBusy(this->Session))
  {
    this->setStatus("Flow: wait for the current task or cancel it.");
    return false;
  }
  // What the jobs work on: copies, the session goes on.
  auto input = std::make_shared<bender::FlowStudyInput>();
  input->first = bender::DeepCopyOf(this->Session.GetFirstSurface());
  input->plan = this->Session.GetPlan();
  input->current = bender::DeepCopyOf(this->Session.GetSurface());
  if (!this->Session.GetSurfaceName().empty())
  {
    input->name = this->Session.GetSurfaceName();
  }
  this->Input = input;
  this->RunFirst = this->Session.GetFirstSurface();
  this->RunCurrent = this->Session.GetSurface();
  this->RunPlan = input->plan;
  this->Results[0].reset();
  this->Results[1].reset();
  this->Compared.reset();
  this->showStale(false);
  this->Plot->clear();
  this->Summary->clear();
  this->ShowComparison->setEnabled(false);
  this->Running = true;
  this->sessionChanged();
  this->startStudy();
  return this->Running;
}

void FlowPanel::cancel()
{
  if (this->Running)
  {
    this->Worker->cancel();
    this->setStatus("Flow: cancelling...");
  }
}

void FlowPanel::startStudy()
{
  bender::FlowStudyOptions options;
  options.cacheDirectory = QDir(this->CacheFolder).absolutePath().toStdString();
  options.caseOptions = this->caseOptions();
  QPointer<FlowPanel> self(this);
  const auto onIteration = [self](bender::FlowShape shape, const bender::CfdIteration& iteration)
  {
    const int which = shape == bender::FlowShape::Original ? 0 : 1;
    QMetaObject::invokeMethod(
      qApp,
      [self, which, iteration]()
      {
        if (self)
        {
          self->Plot->addIteration(which, iteration);
        }
      },
      Qt::QueuedConnection);
  };
  // Two serial cases on two cores: both at once take about the longer one's time.
  const unsigned cores = std::thread::hardware_concurrency();
  const bool concurrent = cores >= 2u * static_cast<unsigned>(options.caseOptions.processors);
  this->setStatus(QString("Flow: the original and the current shape%1 (mesh, solve, results)...")
                    .arg(concurrent ? " at once" : ", one after the other"));
  const auto input = this->Input;
  const bool started = this->Worker->run("Flow",
    [self, input, options, onIteration, concurrent](
      const bender::ProgressReporter& progress) -> WorkRunner::Finisher
    {
      bender::FlowStudyOptions run = options;
      run.progress = progress;
      auto study = std::make_shared<bender::FlowStudyResult>();
      try
      {
        *study = bender::RunFlowStudy(*input, run, onIteration, concurrent);
      }
      catch (const bender::Cancelled&)
      {
        throw; // the worker says so
      }
      catch (const std::exception& e)
      {
        const QString what = QString("Flow failed: %1").arg(e.what());
        return [self, what]()
        {
          if (self)
          {
            self->Session.AddMessage(bender::MessageSeverity::Error, what.toStdString());
            self->Worker->markFailed();
            self->stop(what);
          }
        };
      }
      return [self, study]()
      {
        if (self)
        {
          self->studyDone(*study);
        }
      };
    });
  if (!started)
  {
    this->stop("Flow: the worker is busy; nothing was run.");
  }
}

void FlowPanel::studyDone(const bender::FlowStudyResult& study)
{
  if (!this->Running)
  {
    return;
  }
  for (int which = 0; which < 2; ++which)
  {
    this->Results[which] = std::make_shared<bender::FlowShapeResult>(study.shapes[which]);
  }
  this->Running = false;
  this->Input.reset();
  this->sessionChanged();
  this->Compared = std::make_unique<bender::CfdComparison>(
    bender::CompareCfdResults(this->Results[0]->results, this->Results[1]->results));
  this->Compared->labelA = "Original";
  this->Compared->labelB = "Current";
  this->Table->setComparison(*this->Compared);
  this->Views->setSurfaces(this->Results[0]->surface,
    this->Results[1]->surface,
    this->ViewRenderer ? this->ViewRenderer->GetActiveCamera() : nullptr);
  this->Views->setStreamlines(this->Results[0]->streamlines, this->Results[1]->streamlines);
  QString cases = QString("Cases: %1 (original), %2 (current shape); bender-cli compare gives "
                          "the same table for them.")
                    .arg(QString::fromStdString(this->Results[0]->caseDirectory),
                      QString::fromStdString(this->Results[1]->caseDirectory));
  for (const auto& result : this->Results)
  {
    if (!result->streamlineProblem.empty())
    {
      cases += "\nNo streamlines: " + QString::fromStdString(result->streamlineProblem);
    }
  }
  this->Cases->setText(cases);
  this->DoneText =
    "Flow done. " + RunLine(0, *this->Results[0]) + "; " + RunLine(1, *this->Results[1]) + ".";
  this->setStatus(this->DoneText);
  const int notable = bender::CountHighlighted(*this->Compared);
  this->Summary->setText(QString("%1 of %2 quantities differ notably (highlighted in the table).")
                           .arg(notable)
                           .arg(this->Compared->rows.size()));
  this->ShowComparison->setEnabled(true);
  this->sessionChanged(); // Save report; stale already when the shape changed between the jobs
  this->Session.AddMessage(bender::MessageSeverity::Info,
    "Flow: original and current shape solved; " + std::to_string(notable) +
      " quantities differ notably" + this->trimCache());
  this->showComparison();
  emit this->flowFinished(true);
}

void FlowPanel::stop(const QString& why)
{
  if (!this->Running)
  {
    return;
  }
  this->Running = false;
  this->Input.reset();
  this->setStatus(why);
  this->sessionChanged();
  emit this->flowFinished(false);
}

void FlowPanel::showComparison()
{
  if (!this->Compared)
  {
    return;
  }
  this->Comparison->show();
  this->Comparison->raise();
  this->Views->render();
}
