// The Flow panel on the real window (issue 23, "original vs candidate, side by side"; labels gui
// and cfd: OpenFOAM runs). A small tube prepared for CFD and bent is in the session; the panel
// is driven by QTest events on its widgets:
//  - Run: one job on the window's worker (the original and the current shape, at once on a
//    machine with two cores), both solvers' residuals plotted while they run, the status bar's
//    progress naming the step, the event loop turning throughout; then the comparison window;
//  - the table holds the numbers of the two cases' results/flow.json (as bender-cli compare);
//  - the two views share one colour scale with its unit, and a drag in one moves the other;
//  - Save report: the PDF, its pictures and the plan in a folder picked in the dialog; saved
//    again there only when the user says to replace them;
//  - a later bend marks the results stale (said in the panel and the comparison window), an
//    undo back to the shape run makes them current again;
//  - Run again: both shapes found in the flow cache, nothing solved again;
//  - a changed case option is a new case, and Cancel stops it, leaving no results;
//  - the flow cache trimmed to its limits after a run, the cases shown kept.
#include "AppTestUtilities.h"
#include "FlowAppTestUtilities.h"
#include "FlowComparisonTable.h"
#include "FlowPanel.h"
#include "FlowReportSaver.h"
#include "FlowResidualPlot.h"
#include "FlowViews.h"
#include "MainActions.h"
#include "MainWindow.h"

#include "ApplyPlan.h"
#include "CfdComparison.h"
#include "CfdFlowResults.h"
#include "FlowCaseCache.h"
#include "LogicTestUtilities.h"
#include "ProcessRunner.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDateTime>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMessageBox>
#include <QMouseEvent>
#include <QProcess>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTimer>
#include <QToolButton>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkCamera.h>
#include <vtkLookupTable.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace
{
bool SameCamera(vtkCamera* a, vtkCamera* b)
{
  for (int k = 0; k < 3; ++k)
  {
    if (std::abs(a->GetPosition()[k] - b->GetPosition()[k]) > 1e-9 ||
      std::abs(a->GetFocalPoint()[k] - b->GetFocalPoint()[k]) > 1e-9 ||
      std::abs(a->GetViewUp()[k] - b->GetViewUp()[k]) > 1e-9)
    {
      return false;
    }
  }
  return std::abs(a->GetViewAngle() - b->GetViewAngle()) < 1e-9;
}

/// Whether the camera's position moved away from `before` (mm).
bool Moved(vtkCamera* camera, const double before[3])
{
  const double* p = camera->GetPosition();
  return std::hypot(p[0] - before[0], p[1] - before[1], p[2] - before[2]) > 1e-3;
}

QString Artifact(const QString& name)
{
  QDir().mkpath(BENDER_ARTIFACT_DIR);
  return QString(BENDER_ARTIFACT_DIR) + "/" + name;
}

/// The simpleFoam log's time stamp (an unchanged one: the case was not solved again).
QDateTime Solved(const std::string& caseDirectory)
{
  return QFileInfo(QString::fromStdString(caseDirectory) + "/log.simpleFoam").lastModified();
}

/// Answers the dialogs of one Save report while it lives: picks `folder` in the folder dialog
/// (Qt's own, typed in its name box), and presses `replace` (Replace or Keep them) in the
/// question asked when a report is there already, counting the questions.
class ReportDialogsAnswer
{
public:
  ReportDialogsAnswer(const QString& folder, QMessageBox::StandardButton replace)
  {
    QCoreApplication::setAttribute(Qt::AA_DontUseNativeDialogs, true);
    this->Timer.setInterval(30);
    QObject::connect(&this->Timer,
      &QTimer::timeout,
      [this, folder, replace]()
      {
        if (auto* box = bendertest::VisibleTopLevel<QMessageBox>("replaceFlowReport"))
        {
          ++this->Questions;
          this->Text = box->text();
          QTest::mouseClick(box->button(replace), Qt::LeftButton);
          return;
        }
        auto* dialog = bendertest::VisibleTopLevel<QFileDialog>();
        if (dialog && bendertest::TypeFileName(*dialog, folder))
        {
          QMetaObject::invokeMethod(dialog, "accept"); // as the Choose button does
        }
      });
    this->Timer.start();
  }
  int questions() const { return this->Questions; }
  const QString& text() const { return this->Text; }

private:
  QTimer Timer;
  int Questions = 0;
  QString Text;
};

/// The modification times of the report's files in `folder` (invalid for a missing one).
QList<QDateTime> ReportTimes(const QString& folder)
{
  QList<QDateTime> times;
  for (const QString& file : FlowReportSaver::filesIn(folder))
  {
    times << QFileInfo(file).lastModified();
  }
  return times;
}
} // namespace

class FlowAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  QString CaseA, CaseB;
  QDateTime SolvedA, SolvedB;

  FlowPanel* panel() { return this->Window->flowPanel(); }

private slots:
  void initTestCase()
  {
    BENDER_REQUIRE_OPENFOAM();
    // A bent tube, a small case; the cache in the test's folder.
    this->Window = bendertest::BentTubeWindow(this->Folder);
    QVERIFY(this->Window);
    this->panel()->setCacheFolder(this->Folder.filePath("flow-cache"));
  }

  void cleanupTestCase()
  {
    if (this->Window)
    {
      this->Window->close();
      this->Window.reset();
    }
  }

  void runSolvesBothShapesAsJobsWithTheResidualsLive()
  {
    QVERIFY(this->panel()->runButton()->isEnabled());
    // The event loop turns throughout; the plot fills while a job runs; the status bar's
    // progress names the step.
    int ticks = 0;
    QTimer ticker;
    connect(&ticker, &QTimer::timeout, [&ticks]() { ++ticks; });
    ticker.start(50);
    bool plottedWhileRunning = false;
    QStringList steps;
    QElapsedTimer clock;
    clock.start();
    const bool ok = bendertest::RunFlowAndWait(this->panel(),
      400000,
      [&]()
      {
        auto* progress = this->Window->findChild<QProgressBar*>();
        while (this->panel()->isRunning() && clock.elapsed() < 400000)
        {
          QTest::qWait(100);
          plottedWhileRunning = plottedWhileRunning ||
            (this->panel()->isRunning() && this->panel()->plot()->iterations(0) > 0);
          if (progress && progress->isVisible() && !steps.contains(progress->format()))
          {
            steps << progress->format();
          }
        }
      });
    QVERIFY2(ok, qPrintable(this->panel()->statusLabel()->text()));
    const double seconds = clock.elapsed() / 1000.0;
    QVERIFY(plottedWhileRunning);
    QVERIFY2(ticks > seconds * 5, qPrintable(QString("%1 ticks in %2 s").arg(ticks).arg(seconds)));
    // Both shapes' stages, named after their shape (run at once, the bar shows whichever
    // reported last: a short stage of one may not be seen).
    const QString seen = steps.join("|");
    QVERIFY2(seen.contains("Flow: original: "), qPrintable(seen));
    QVERIFY2(seen.contains("Flow: current shape: "), qPrintable(seen));
    QVERIFY2(seen.contains(": solve"), qPrintable(seen));
    for (int which = 0; which < 2; ++which)
    {
      const bender::FlowShapeResult* result = this->panel()->result(which);
      QVERIFY(result && result->surface);
      QVERIFY(!result->cached);
      // Every iteration of each run was plotted.
      QCOMPARE(this->panel()->plot()->iterations(which), result->results.run.iterations);
    }
    QVERIFY(this->panel()->comparisonWindow()->isVisible());
    this->CaseA = QString::fromStdString(this->panel()->result(0)->caseDirectory);
    this->CaseB = QString::fromStdString(this->panel()->result(1)->caseDirectory);
    QVERIFY(this->CaseA != this->CaseB);
    this->SolvedA = Solved(this->CaseA.toStdString());
    this->SolvedB = Solved(this->CaseB.toStdString());
    qInfo("both shapes solved in %.1f s", seconds);
  }

  void theTableHoldsTheNumbersOfTheResultsFiles()
  {
    QVERIFY(!this->CaseA.isEmpty());
    // What bender-cli compare computes from the two case folders.
    bendertest::ExpectTableOfTheResultsFiles(this->panel(), this->CaseA, this->CaseB);
    if (QTest::currentTestFailed())
    {
      return;
    }
    // bender-cli compare of the two case folders: the same rows, the same numbers, the same
    // highlights as the panel's table.
    bendertest::ExpectCompareGivesThePanelsNumbers(this->panel(),
      BENDER_CLI_PATH,
      this->CaseA,
      this->CaseB,
      this->Folder.filePath("report.pdf"));
  }

  void theViewsShareTheScaleAndMoveTogether()
  {
    FlowViews* views = this->panel()->views();
    QVERIFY(views->isVisible());
    // One colour scale, its unit in the title; WSS selectable.
    QCOMPARE(views->mapper(0)->GetLookupTable(), views->mapper(1)->GetLookupTable());
    QCOMPARE(views->scaleTitle(), QString("Pressure (Pa)"));
    auto* field = views->findChild<QComboBox*>("flowField");
    QVERIFY(field);
    field->setFocus();
    QTest::keyClick(field, Qt::Key_Down);
    QCOMPARE(views->field(), FlowViews::Field::WallShearStress);
    QCOMPARE(views->scaleTitle(), QString("WSS (Pa)"));
    double range[2];
    views->range(range);
    QCOMPARE(range[0], 0.0);
    QVERIFY(range[1] > 0.0);
    QTest::keyClick(field, Qt::Key_Up);
    QCOMPARE(views->field(), FlowViews::Field::Pressure);
    // The streamlines through both shapes, on and off.
    auto* streamlines = views->findChild<QCheckBox*>("flowStreamlines");
    QVERIFY(streamlines && streamlines->isEnabled());
    QTest::mouseClick(streamlines, Qt::LeftButton);
    QVERIFY(views->streamlinesShown());
    for (int which = 0; which < 2; ++which)
    {
      QVERIFY(this->panel()->result(which)->streamlines);
      QVERIFY(this->panel()->result(which)->streamlines->GetNumberOfLines() > 0);
    }

    // The pictures (streamlines on): the window with the Flow panel, the comparison window
    // (those of the docs are the demo's: FlowDemoAppTests).
    QVERIFY(this->Window->saveScreenshot(Artifact("flow-tube-panel.png")));
    QCoreApplication::processEvents();
    views->render();
    QWidget* comparison = this->panel()->comparisonWindow();
    QVERIFY(comparison->grab().toImage().save(Artifact("flow-tube-comparison.png"), "PNG"));
    QTest::mouseClick(streamlines, Qt::LeftButton);
    QVERIFY(!views->streamlinesShown());

    // A drag in one view turns both; a drag in the other turns both back.
    vtkCamera* a = views->renderer(0)->GetActiveCamera();
    vtkCamera* b = views->renderer(1)->GetActiveCamera();
    QVERIFY(SameCamera(a, b));
    double before[3];
    a->GetPosition(before);
    QWidget* left = views->view(0);
    const QPoint centre(left->width() / 2, left->height() / 2);
    bendertest::Drag(left, centre, centre + QPoint(60, 20));
    QVERIFY(Moved(a, before));
    QVERIFY(SameCamera(a, b));
    double moved[3];
    b->GetPosition(moved);
    QWidget* right = views->view(1);
    bendertest::Drag(right,
      QPoint(right->width() / 2, right->height() / 2),
      QPoint(right->width() / 2 - 40, right->height() / 2));
    QVERIFY(Moved(b, moved));
    QVERIFY(SameCamera(a, b));
  }

  void saveReportWritesThePdfAndAsksBeforeReplacingIt()
  {
    QVERIFY(this->panel()->saveReportButton()->isEnabled());
    const QString folder = this->Folder.filePath("report");
    QVERIFY(QDir().mkpath(folder)); // the folder dialog picks a folder that is there
    {
      // Save report..., the folder picked in the dialog: the PDF, the pictures, the plan.
      ReportDialogsAnswer answer(folder, QMessageBox::No);
      QSignalSpy saved(this->panel()->reportSaver(), &FlowReportSaver::saved);
      QTest::mouseClick(this->panel()->saveReportButton(), Qt::LeftButton);
      QVERIFY(saved.wait(300000));
      QVERIFY2(saved.first().first().toBool(), qPrintable(this->Window->statusLabel()->text()));
      QCOMPARE(saved.first().at(1).toString(), FlowReportSaver::pdfIn(folder));
      QCOMPARE(answer.questions(), 0); // nothing there to replace
    }
    for (const QString& file : FlowReportSaver::filesIn(folder))
    {
      QVERIFY2(QFileInfo(file).size() > 0, qPrintable(file));
    }
    QFile pdf(FlowReportSaver::pdfIn(folder));
    QVERIFY(pdf.open(QIODevice::ReadOnly));
    QCOMPARE(pdf.read(5), QByteArray("%PDF-"));
    pdf.close();
    if (!bender::FindExecutable("pdftoppm").empty())
    {
      // Every page renders.
      QProcess render;
      render.start("pdftoppm",
        { "-r", "20", "-png", FlowReportSaver::pdfIn(folder), this->Folder.filePath("page") });
      QVERIFY(render.waitForFinished(120000));
      QCOMPARE(render.exitCode(), 0);
      QVERIFY(QFileInfo::exists(this->Folder.filePath("page-1.png")));
    }
    // The plan beside it is the session's (the prepared then bent tube).
    QVERIFY(QFileInfo(folder + "/flow-plan.bender.json").size() > 0);
    QVERIFY(this->Window->statusLabel()->text().startsWith("Flow report saved"));

    // Saved again there: asked; "Keep them" leaves every file as it was.
    const QList<QDateTime> before = ReportTimes(folder);
    QTest::qWait(1100); // a rewrite shows in the time stamps
    {
      ReportDialogsAnswer answer(folder, QMessageBox::No);
      QVERIFY(!this->panel()->saveReport(folder));
      QCOMPARE(answer.questions(), 1);
      QVERIFY2(answer.text().contains("flow-report.pdf"), qPrintable(answer.text()));
    }
    QCOMPARE(ReportTimes(folder), before);
    // "Replace": written again.
    {
      ReportDialogsAnswer answer(folder, QMessageBox::Yes);
      QSignalSpy saved(this->panel()->reportSaver(), &FlowReportSaver::saved);
      QVERIFY(this->panel()->saveReport(folder));
      QCOMPARE(answer.questions(), 1);
      QVERIFY(saved.wait(300000));
      QVERIFY(saved.first().first().toBool());
    }
    QVERIFY(QFileInfo(FlowReportSaver::pdfIn(folder)).lastModified() > before.first());
  }

  void aLaterBendMakesTheResultsStaleUntilUndone()
  {
    QVERIFY(!this->panel()->isStale());
    auto* note = this->panel()->comparisonWindow()->findChild<QLabel*>("flowStale");
    QVERIFY(note && !note->isVisible());
    const QString done = this->panel()->statusLabel()->text();
    QVERIFY(done.startsWith("Flow done"));
    // Another bend after the run: the results are of the earlier shape, and say so.
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.ApplyWarp(bender::test::Swing(0, 10, 20, 8)));
    QVERIFY(this->panel()->isStale());
    QVERIFY(note->isVisible());
    QVERIFY(this->panel()->statusLabel()->text().startsWith("Stale"));
    QVERIFY(this->panel()->comparisonWindow()->windowTitle().contains("stale"));
    // The table still shows the run's numbers.
    QCOMPARE(this->panel()->table()->rowCount(),
      static_cast<int>(this->panel()->comparison()->rows.size()));
    // Undone (Ctrl+Z on the window): the shape of the run again, the results current.
    this->Window->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(this->Window.get()));
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier);
    QTRY_VERIFY_WITH_TIMEOUT(!this->panel()->isStale(), 10000);
    QVERIFY(!note->isVisible());
    QCOMPARE(this->panel()->statusLabel()->text(), done);
    QVERIFY(!this->panel()->comparisonWindow()->windowTitle().contains("stale"));
    // Redone: stale again; undone again for the next tests.
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QTRY_VERIFY_WITH_TIMEOUT(this->panel()->isStale(), 10000);
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier);
    QTRY_VERIFY_WITH_TIMEOUT(!this->panel()->isStale(), 10000);
  }

  void theSameShapesAreNotSolvedAgain()
  {
    QVERIFY(!this->CaseA.isEmpty());
    QElapsedTimer clock;
    clock.start();
    QVERIFY2(bendertest::RunFlowAndWait(this->panel(), 120000),
      qPrintable(this->panel()->statusLabel()->text()));
    for (int which = 0; which < 2; ++which)
    {
      QVERIFY(this->panel()->result(which)->cached);
    }
    QCOMPARE(QString::fromStdString(this->panel()->result(0)->caseDirectory), this->CaseA);
    QCOMPARE(QString::fromStdString(this->panel()->result(1)->caseDirectory), this->CaseB);
    QCOMPARE(Solved(this->CaseA.toStdString()), this->SolvedA);
    QCOMPARE(Solved(this->CaseB.toStdString()), this->SolvedB);
    QVERIFY(this->panel()->statusLabel()->text().contains("from the cache"));
    // The plot shows the cached runs' residuals.
    QCOMPARE(
      this->panel()->plot()->iterations(1), this->panel()->result(1)->results.run.iterations);
    qInfo("found in the cache in %.1f s", clock.elapsed() / 1000.0);
  }

  void aChangedCaseIsANewOneAndCancelStopsIt()
  {
    bendertest::TypeInto(this->panel()->iterationsBox(), "26");
    QSignalSpy finished(this->panel(), &FlowPanel::flowFinished);
    QTest::mouseClick(this->panel()->runButton(), Qt::LeftButton);
    QVERIFY(this->panel()->isRunning());
    QVERIFY(this->panel()->cancelButton()->isEnabled());
    QVERIFY(!this->panel()->runButton()->isEnabled());
    // Cancelled as soon as the cases are written and meshing (both shapes of the small tube
    // run at once solve in a few seconds: a fixed wait could come after them).
    auto* progress = this->Window->findChild<QProgressBar*>();
    QVERIFY(progress);
    QTRY_VERIFY_WITH_TIMEOUT(
      progress->format().contains(": mesh: ") || !this->panel()->isRunning(), 60000);
    QVERIFY2(this->panel()->isRunning(), "the run ended before it was meshing");
    QTest::mouseClick(this->panel()->cancelButton(), Qt::LeftButton);
    QVERIFY(!finished.isEmpty() || finished.wait(60000));
    QCOMPARE(finished.first().first().toBool(), false);
    QVERIFY(!this->panel()->isRunning());
    QVERIFY(this->panel()->runButton()->isEnabled());
    // Both changed cases are written before either is run; those being solved when Cancel
    // came have no results (both, where they run at once), the cases solved before do: the two
    // of the earlier tests and, run one after the other on a fast machine, the changed original
    // solved before the cancel reached the candidate.
    int withResults = 0, cases = 0;
    for (const QFileInfo& entry :
      QDir(this->Folder.filePath("flow-cache")).entryInfoList(QDir::Dirs | QDir::NoDotAndDotDot))
    {
      ++cases;
      withResults += bender::HasFlowResults(entry.absoluteFilePath().toStdString()) ? 1 : 0;
    }
    QCOMPARE(cases, 4);
    QVERIFY2(withResults == 2 || withResults == 3, qPrintable(QString::number(withResults)));
  }

  void theCacheIsTrimmedAfterARunKeepingTheCasesShown()
  {
    const QDir cache(this->Folder.filePath("flow-cache"));
    const auto caseFolders = [&cache]()
    { return cache.entryList(QDir::Dirs | QDir::NoDotAndDotDot).size(); };
    QVERIFY(caseFolders() >= 3);
    // Two cases at most: the run of the first settings (found in the cache) keeps its two and
    // removes the rest, the least recently used first.
    bender::FlowCacheLimits limits;
    limits.maxCases = 2;
    this->panel()->setCacheLimits(limits);
    bendertest::TypeInto(this->panel()->iterationsBox(), "25");
    QVERIFY2(bendertest::RunFlowAndWait(this->panel(), 120000),
      qPrintable(this->panel()->statusLabel()->text()));
    QVERIFY(this->panel()->result(0)->cached && this->panel()->result(1)->cached);
    QCOMPARE(caseFolders(), 2);
    QVERIFY(QFileInfo::exists(this->CaseA) && QFileInfo::exists(this->CaseB));
    QVERIFY2(this->Window->statusLabel()->text().contains("least recently used"),
      qPrintable(this->Window->statusLabel()->text()));
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("FlowAppTest");
  FlowAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "FlowAppTest.moc"
