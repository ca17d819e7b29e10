// The Flow panel on the demo vessel (issue 23, "done when": on the demo vessel and its bent
// candidate, bender-cli compare and the Flow panel show the same numbers; labels gui and cfd:
// OpenFOAM runs). On the real window: Demo (the segmented vessel), its bend by the demo plan,
// the Export panel's Prepare for CFD (the three ends clipped, named and capped), then the Flow
// panel's Run: the original and the bent candidate solved as two jobs on a coarse mesh (cells
// of 1.6 mm, 20 iterations: the numbers are not converged, the comparison's agreement is what
// is tested). The panel's table holds the two cases' results, and bender-cli compare of the
// two case folders gives the same rows, numbers and highlights. The pictures of docs/app.md's
// Flow section are taken here.
#include "AppTestUtilities.h"
#include "ExportPanel.h"
#include "FlowAppTestUtilities.h"
#include "FlowPanel.h"
#include "FlowViews.h"
#include "MainActions.h"
#include "MainWindow.h"

#include "ApplyPlan.h"
#include "PatchLabels.h"
#include "WarpPlanIO.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QDir>
#include <QElapsedTimer>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <memory>

namespace
{
QString Artifact(const QString& name)
{
  QDir().mkpath(BENDER_ARTIFACT_DIR);
  return QString(BENDER_ARTIFACT_DIR) + "/" + name;
}
} // namespace

class FlowDemoAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  QString CaseA, CaseB;

  FlowPanel* panel() { return this->Window->flowPanel(); }

private slots:
  void initTestCase()
  {
    BENDER_REQUIRE_OPENFOAM();
    QVERIFY(this->Folder.isValid());
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*this->Window, true));
    QElapsedTimer clock;
    clock.start();
    // The demo vessel, bent as the demo plan bends it (bender-cli warp vessel.vtp
    // demo.bender.json).
    this->Window->actions()->Demo->trigger();
    QVERIFY(this->Window->waitUntilIdle(300000));
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.HasSurface());
    const bender::WarpPlan demo = bender::ReadWarpPlan(BENDER_DEMO_PLAN);
    QVERIFY(!demo.warps.empty());
    QVERIFY2(
      session.ApplyWarp(demo.warps.front()), qPrintable(this->Window->statusLabel()->text()));
    this->Window->setRibbon(demo.warps.front().final); // where a drag would have left it
    // Prepare for CFD of the bent vessel, as a user does after a bend: the Export panel's
    // button. Its step writes out every end's cut on the bent shape; the flow's original is the
    // unbent vessel cut at the same ends (the positions carried back through the bend).
    auto* exportPanel = this->Window->findChild<ExportPanel*>();
    QVERIFY(exportPanel);
    QVERIFY(bendertest::ShowPanel(*this->Window, exportPanel));
    QSignalSpy prepared(this->Window.get(), &MainWindow::workFinished);
    QTest::mouseClick(exportPanel->Prepare, Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(300000));
    QCOMPARE(prepared.count(), 1);
    QVERIFY2(prepared.first().first().toBool(), qPrintable(this->Window->statusLabel()->text()));
    QVERIFY(session.GetCurrentCfdStep() && session.GetCurrentCfdStep()->afterWarps == 1);
    QCOMPARE(bender::ReadPatchLabels(session.GetSurface()).size(), std::size_t(4)); // wall + 3 ends
    qInfo("demo loaded, bent and prepared in %.1f s", clock.elapsed() / 1000.0);
    // Seen from the patient's left, framed: the trunk's swing from anterior to superior lies in
    // the picture's plane.
    this->Window->actions()->StandardViews[2]->trigger();
    QVERIFY(bendertest::ShowPanel(*this->Window, this->panel()));
    // A coarse case in the test's folder.
    this->panel()->setCacheFolder(this->Folder.filePath("flow-cache"));
    bendertest::TypeInto(this->panel()->iterationsBox(), "20");
    bendertest::TypeInto(this->panel()->cellSizeBox(), "1.60");
  }

  void cleanupTestCase()
  {
    if (this->Window)
    {
      this->Window->close();
      this->Window.reset();
    }
  }

  void runSolvesTheDemoAndItsBentCandidate()
  {
    QVERIFY(this->panel()->runButton()->isEnabled());
    QElapsedTimer clock;
    clock.start();
    QVERIFY2(bendertest::RunFlowAndWait(this->panel(), 480000),
      qPrintable(
        this->panel()->statusLabel()->text() + " / " + this->Window->statusLabel()->text()));
    for (int which = 0; which < 2; ++which)
    {
      const bender::FlowShapeResult* result = this->panel()->result(which);
      QVERIFY(result && result->surface);
      QVERIFY(!result->cached);
      // The demo's three ends in the results: the inlet and two outlets.
      QCOMPARE(result->results.ends.size(), std::size_t(3));
    }
    QVERIFY(this->panel()->comparisonWindow()->isVisible());
    QVERIFY(!this->panel()->isStale());
    this->CaseA = QString::fromStdString(this->panel()->result(0)->caseDirectory);
    this->CaseB = QString::fromStdString(this->panel()->result(1)->caseDirectory);
    QVERIFY(this->CaseA != this->CaseB);
    qInfo("the demo's original and candidate solved in %.1f s", clock.elapsed() / 1000.0);
  }

  void thePanelShowsTheNumbersOfBenderCliCompare()
  {
    QVERIFY(!this->CaseA.isEmpty());
    bendertest::ExpectTableOfTheResultsFiles(this->panel(), this->CaseA, this->CaseB);
    if (QTest::currentTestFailed())
    {
      return;
    }
    QElapsedTimer clock;
    clock.start();
    bendertest::ExpectCompareGivesThePanelsNumbers(this->panel(),
      BENDER_CLI_PATH,
      this->CaseA,
      this->CaseB,
      this->Folder.filePath("report.pdf"),
      { "--no-bend-measures" });
    qInfo("bender-cli compare in %.1f s", clock.elapsed() / 1000.0);
  }

  void thePicturesOfTheDocs()
  {
    // The window with the Flow panel (no field being edited); the comparison window with the
    // streamlines.
    if (QWidget* focused = QApplication::focusWidget())
    {
      focused->clearFocus();
    }
    QVERIFY(this->Window->saveScreenshot(Artifact("flow-panel.png")));
    FlowViews* views = this->panel()->views();
    auto* streamlines = views->findChild<QCheckBox*>("flowStreamlines");
    QVERIFY(streamlines && streamlines->isEnabled());
    QTest::mouseClick(streamlines, Qt::LeftButton);
    QVERIFY(views->streamlinesShown());
    QCoreApplication::processEvents();
    views->render();
    QWidget* comparison = this->panel()->comparisonWindow();
    QVERIFY(comparison->grab().toImage().save(Artifact("flow-comparison.png"), "PNG"));
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("FlowDemoAppTest");
  FlowDemoAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "FlowDemoAppTest.moc"
