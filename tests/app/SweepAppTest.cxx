// The sweep in the Flow panel on the real window (issue 24, "In the application"; labels gui
// and cfd: OpenFOAM runs). A small tube prepared for CFD and bent is in the session; the panel's
// sweep is driven by QTest events on its widgets:
//  - Sweep the bend: fractions 0, 0.5 and 1 solved as one job on the window's worker, then the
//    sweep window: the plot draws summary.json's series, the table holds its numbers;
//  - a row chosen in the table shows that candidate (its case's results surface) beside the
//    original in the linked views, and marks it on the plot;
//  - Open reads a sweep folder back (and refuses a folder that is not one, with the reason);
//  - Sweep again on the same folder keeps every finished candidate (nothing is solved again);
//  - Cancel stops a sweep: the folder stays consistent (its summary says what is missing) and
//    the window shows what it left.
#include "AppTestUtilities.h"
#include "FlowAppTestUtilities.h"
#include "FlowPanel.h"
#include "FlowViews.h"
#include "MainWindow.h"
#include "SweepCandidateTable.h"
#include "SweepControls.h"
#include "SweepPlotView.h"
#include "SweepWindow.h"

#include "CfdFlowResults.h"
#include "FlowCaseCache.h"
#include "FlowStudy.h"

#include <QApplication>
#include <QDateTime>
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkChartXY.h>
#include <vtkDataArray.h>
#include <vtkPlot.h>
#include <vtkPolyDataMapper.h>
#include <vtkTable.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

namespace
{
QString Artifact(const QString& name)
{
  QDir().mkpath(BENDER_ARTIFACT_DIR);
  return QString(BENDER_ARTIFACT_DIR) + "/" + name;
}

QJsonObject ReadJson(const QString& path)
{
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly))
  {
    return {};
  }
  return QJsonDocument::fromJson(file.readAll()).object();
}

/// The number a table cell keeps (Qt::UserRole); NaN when the cell has none.
double CellValue(const QTableWidget* table, int row, int column)
{
  const QTableWidgetItem* item = column >= 0 ? table->item(row, column) : nullptr;
  const QVariant value = item ? item->data(Qt::UserRole) : QVariant();
  return value.isValid() ? value.toDouble() : std::nan("");
}

/// A JSON number, NaN for null.
double JsonNumber(const QJsonValue& value)
{
  return value.isDouble() ? value.toDouble() : std::nan("");
}

bool SameNumber(double a, double b)
{
  return (std::isnan(a) && std::isnan(b)) || a == b;
}
} // namespace

class SweepAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  QString Sweep; // the folder of the sweep of the first test

  FlowPanel* panel() { return this->Window->flowPanel(); }
  SweepControls* controls() { return this->panel()->sweepControls(); }
  SweepWindow* sweepWindow() { return this->controls()->window(); }

  /// Types `folder` into the sweep's folder box.
  void typeFolder(const QString& folder)
  {
    QLineEdit* box = this->controls()->folderBox();
    box->setFocus();
    box->selectAll();
    QTest::keyClicks(box, folder);
  }

  /// Clicks a table row's first cell.
  void clickRow(int row)
  {
    QTableWidget* table = this->sweepWindow()->table();
    table->scrollToItem(table->item(row, 0));
    const QRect cell = table->visualItemRect(table->item(row, 0));
    QTest::mouseClick(table->viewport(), Qt::LeftButton, Qt::NoModifier, cell.center());
  }

  /// The results surface of candidate `id` of the first sweep.
  vtkSmartPointer<vtkPolyData> resultsOf(const QString& id)
  {
    return bender::ReadFlowShape(
      QDir(this->Sweep).filePath(id + "/case").toStdString(), bender::FlowShape::Current)
      .surface;
  }

private slots:
  void initTestCase()
  {
    BENDER_REQUIRE_OPENFOAM();
    // A bent tube seen as it is bent (the sweep's views take that viewpoint), and the Flow
    // panel's small case for every candidate.
    this->Window = bendertest::BentTubeWindow(this->Folder);
    QVERIFY(this->Window);
    this->Sweep = this->Folder.filePath("sweep");
  }

  void cleanupTestCase()
  {
    if (this->Window)
    {
      this->Window->close();
      this->Window.reset();
    }
  }

  void sweepTheBendAsAJob()
  {
    SweepControls* controls = this->controls();
    this->typeFolder(this->Sweep);
    bendertest::TypeInto(controls->fromBox(), "0");
    bendertest::TypeInto(controls->toBox(), "1");
    bendertest::TypeInto(controls->countBox(), "3");
    QSignalSpy finished(controls, &SweepControls::sweepFinished);
    QTest::mouseClick(controls->sweepButton(), Qt::LeftButton);
    QVERIFY(controls->isRunning());
    QVERIFY(controls->cancelButton()->isEnabled());
    QVERIFY(!controls->sweepButton()->isEnabled());
    QElapsedTimer clock;
    clock.start();
    QVERIFY(!finished.isEmpty() || finished.wait(500000));
    QVERIFY2(finished.first().first().toBool(), qPrintable(controls->statusLabel()->text()));
    qInfo("3 candidates swept in %.1f s", clock.elapsed() / 1000.0);
    QVERIFY(!controls->isRunning());
    QVERIFY(controls->sweepButton()->isEnabled());
    // The sweep window shows it: three rows, each solved.
    SweepWindow* window = this->sweepWindow();
    QVERIFY(window->isVisible());
    QCOMPARE(window->table()->rowCount(), 3);
    for (int r = 0; r < 3; ++r)
    {
      QCOMPARE(window->table()->item(r, 2)->text(), QString("solved"));
    }
    QVERIFY(QFileInfo::exists(QDir(this->Sweep).filePath("summary.json")));
    // summary.png drawn by the window, on its own thread.
    QVERIFY(QFileInfo(QDir(this->Sweep).filePath("summary.png")).size() > 0);
  }

  void theTableHoldsTheSummarysNumbers()
  {
    const QJsonObject summary = ReadJson(QDir(this->Sweep).filePath("summary.json"));
    const QJsonArray rows = summary["rows"].toArray();
    SweepCandidateTable* table = this->sweepWindow()->table();
    QCOMPARE(table->rowCount(), rows.size());
    const std::vector<std::pair<QString, QString>> columns = { { "Fraction", "value" },
      { "Bend (deg)", "bendAngleDeg" },
      { "Length change (%)", "lengthChangePercent" },
      { "Min radius (mm)", "minRadiusMm" },
      { "Pressure drop (Pa)", "pressureDropPa" },
      { "Cells", "meshCells" },
      { "Iterations", "iterations" } };
    int outlets = 0;
    for (int r = 0; r < rows.size(); ++r)
    {
      const QJsonObject row = rows[r].toObject();
      QVERIFY(table->item(r, 0)->text().startsWith(row["id"].toString()));
      QCOMPARE(table->item(r, 2)->text(), row["state"].toString());
      for (const auto& [title, key] : columns)
      {
        const int c = table->columnOf(title);
        QVERIFY2(c >= 0, qPrintable(title));
        QVERIFY2(SameNumber(CellValue(table, r, c), JsonNumber(row[key])),
          qPrintable(QString("%1 of %2: %3 in the table, %4 in summary.json")
                       .arg(title, row["id"].toString())
                       .arg(CellValue(table, r, c))
                       .arg(JsonNumber(row[key]))));
        // The text shows the value rounded.
        if (!std::isnan(JsonNumber(row[key])))
        {
          const double shown = table->item(r, c)->text().toDouble();
          QVERIFY(std::abs(shown - JsonNumber(row[key])) <=
            0.051 + 1e-6 * std::abs(JsonNumber(row[key])));
        }
      }
      for (const QJsonValue& o : row["outlets"].toArray())
      {
        const QJsonObject outlet = o.toObject();
        const int c = table->columnOf("Split " + outlet["name"].toString() + " (%)");
        QVERIFY(c >= 0);
        QVERIFY(SameNumber(CellValue(table, r, c), JsonNumber(outlet["splitPercent"])));
        ++outlets;
      }
      const QJsonObject wss = row["wallShearStress"].toObject();
      QVERIFY(SameNumber(CellValue(table, r, table->columnOf("Mean WSS (Pa)")),
        wss.isEmpty() ? std::nan("") : JsonNumber(wss["meanPa"])));
      QVERIFY(SameNumber(CellValue(table, r, table->columnOf("Low-WSS area (mm2)")),
        wss.isEmpty() ? std::nan("") : JsonNumber(wss["lowAreaMm2"])));
    }
    QVERIFY(outlets >= rows.size());
  }

  void thePlotDrawsTheSummarysSeries()
  {
    const QJsonArray rows = ReadJson(QDir(this->Sweep).filePath("summary.json"))["rows"].toArray();
    std::vector<std::pair<double, double>> drops;
    for (const QJsonValue& r : rows)
    {
      drops.emplace_back(r["value"].toDouble(), r["pressureDropPa"].toDouble());
    }
    std::sort(drops.begin(), drops.end());
    vtkChartXY* chart = this->sweepWindow()->plot()->chart(0);
    QVERIFY(chart && chart->GetNumberOfPlots() >= 2);
    // The first series: the drops against the fraction; then the original dashed across.
    vtkTable* series = chart->GetPlot(0)->GetInput();
    QCOMPARE(static_cast<std::size_t>(series->GetNumberOfRows()), drops.size());
    for (std::size_t i = 0; i < drops.size(); ++i)
    {
      QCOMPARE(series->GetValue(i, 0).ToDouble(), drops[i].first);
      QCOMPARE(series->GetValue(i, 1).ToDouble(), drops[i].second);
    }
    QVERIFY(QString::fromStdString(chart->GetPlot(1)->GetLabel()).contains("original"));
    QCOMPARE(this->sweepWindow()->plot()->chart(1)->GetNumberOfPlots() > 0, true);
  }

  void choosingARowShowsThatCandidateBesideTheOriginal()
  {
    SweepWindow* window = this->sweepWindow();
    // Opened on its first candidate that is not the original.
    QCOMPARE(window->shownCandidate(), std::string("c01"));
    const auto original = this->resultsOf("c00");
    const auto half = this->resultsOf("c01");
    const auto whole = this->resultsOf("c02");
    QVERIFY(bender::test::MaxDifference(half, whole) > 0.1);
    // A click on the last row: the bend as it is, beside the original.
    this->clickRow(2);
    QCOMPARE(window->shownCandidate(), std::string("c02"));
    FlowViews* views = window->views();
    QCOMPARE(bender::test::MaxDifference(
               vtkPolyData::SafeDownCast(views->mapper(0)->GetInput()), original),
      0.0);
    QCOMPARE(
      bender::test::MaxDifference(vtkPolyData::SafeDownCast(views->mapper(1)->GetInput()), whole),
      0.0);
    QVERIFY(window->caption()->text().startsWith("c02"));
    // Marked on the plot.
    vtkChartXY* chart = window->plot()->chart(0);
    const QString marked =
      QString::fromStdString(chart->GetPlot(chart->GetNumberOfPlots() - 1)->GetLabel());
    QVERIFY2(marked.contains("c02"), qPrintable(marked));
    QCoreApplication::processEvents();
    views->render();
    QVERIFY(window->grab().toImage().save(Artifact("sweep-window.png"), "PNG"));
    // The arrow key up: the half bend.
    QTest::keyClick(window->table(), Qt::Key_Up);
    QCOMPARE(window->shownCandidate(), std::string("c01"));
    QCOMPARE(
      bender::test::MaxDifference(vtkPolyData::SafeDownCast(views->mapper(1)->GetInput()), half),
      0.0);
  }

  void openReadsASweepFolderBack()
  {
    SweepControls* controls = this->controls();
    // A folder that is not a sweep: refused with the reason, the window unchanged.
    const QString empty = this->Folder.filePath("not-a-sweep");
    QVERIFY(QDir().mkpath(empty));
    this->typeFolder(empty);
    QTest::mouseClick(controls->openButton(), Qt::LeftButton);
    QVERIFY2(controls->statusLabel()->text().contains("not a sweep folder"),
      qPrintable(controls->statusLabel()->text()));
    QCOMPARE(this->sweepWindow()->table()->rowCount(), 3);
    // The sweep itself.
    this->typeFolder(this->Sweep);
    QTest::mouseClick(controls->openButton(), Qt::LeftButton);
    QVERIFY2(controls->statusLabel()->text().contains("3 of 3"),
      qPrintable(controls->statusLabel()->text()));
    QCOMPARE(this->sweepWindow()->sweep().rows.size(), std::size_t(3));
    QCOMPARE(this->sweepWindow()->shownCandidate(), std::string("c01"));
  }

  void sweepingAgainKeepsWhatIsFinished()
  {
    SweepControls* controls = this->controls();
    const QDateTime solved =
      QFileInfo(QDir(this->Sweep).filePath("c02/case/log.simpleFoam")).lastModified();
    QSignalSpy finished(controls, &SweepControls::sweepFinished);
    QTest::mouseClick(controls->sweepButton(), Qt::LeftButton);
    // Nothing to solve: it may have ended before the wait begins.
    QVERIFY2(
      !finished.isEmpty() || finished.wait(120000), qPrintable(controls->statusLabel()->text()));
    QVERIFY2(finished.first().first().toBool(), qPrintable(controls->statusLabel()->text()));
    QVERIFY2(controls->statusLabel()->text().contains("0 this time, 3 kept"),
      qPrintable(controls->statusLabel()->text()));
    QCOMPARE(
      QFileInfo(QDir(this->Sweep).filePath("c02/case/log.simpleFoam")).lastModified(), solved);
  }

  void cancelStopsASweep()
  {
    SweepControls* controls = this->controls();
    const QString folder = this->Folder.filePath("cancelled");
    this->typeFolder(folder);
    bendertest::TypeInto(controls->fromBox(), "0.25");
    bendertest::TypeInto(controls->toBox(), "0.75");
    bendertest::TypeInto(controls->countBox(), "2");
    QSignalSpy finished(controls, &SweepControls::sweepFinished);
    QTest::mouseClick(controls->sweepButton(), Qt::LeftButton);
    QVERIFY(controls->isRunning());
    // Cancelled once the first candidate is prepared (its case written).
    QTRY_VERIFY_WITH_TIMEOUT(
      QFileInfo::exists(QDir(folder).filePath("c00/state.json")) || !controls->isRunning(), 120000);
    QTest::mouseClick(controls->cancelButton(), Qt::LeftButton);
    QVERIFY(!finished.isEmpty() || finished.wait(120000));
    QCOMPARE(finished.first().first().toBool(), false);
    QVERIFY(!controls->isRunning());
    QVERIFY(controls->sweepButton()->isEnabled());
    // The folder is consistent: its summary lists what is missing and why; a candidate not
    // solved has no results.
    const QJsonObject summary = ReadJson(QDir(folder).filePath("summary.json"));
    const QJsonArray rows = summary["rows"].toArray();
    QCOMPARE(rows.size(), 2);
    QVERIFY(!summary["missing"].toArray().isEmpty());
    for (const QJsonValue& m : summary["missing"].toArray())
    {
      QVERIFY2(m["reason"].toString().contains("cancelled"), qPrintable(m["reason"].toString()));
      QVERIFY(
        !bender::HasFlowResults(QDir(folder).filePath(m["id"].toString() + "/case").toStdString()));
    }
    // The window shows what the sweep left, row for row.
    SweepWindow* window = this->sweepWindow();
    QCOMPARE(QString::fromStdString(window->sweep().folder), QDir(folder).absolutePath());
    QCOMPARE(window->table()->rowCount(), 2);
    for (int r = 0; r < 2; ++r)
    {
      const QString state = rows[r]["state"].toString();
      QCOMPARE(window->table()->item(r, 2)->text(), state);
    }
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("SweepAppTest");
  SweepAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "SweepAppTest.moc"
