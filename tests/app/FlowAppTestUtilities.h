#ifndef bender_FlowAppTestUtilities_h
#define bender_FlowAppTestUtilities_h

// Pieces shared by the Flow panel's window suites (FlowAppTests on a bent tube,
// FlowDemoAppTests on the demo vessel, SweepAppTests on a bent tube).

#include "AppTestUtilities.h"
#include "FlowComparisonTable.h"
#include "FlowPanel.h"
#include "MainActions.h"
#include "MainWindow.h"

#include "ApplyPlan.h"

#include "CfdComparison.h"
#include "CfdFlowResults.h"
#include "LogicTestUtilities.h"
#include "ProcessRunner.h"

#include <QAbstractSpinBox>
#include <QAction>
#include <QDoubleSpinBox>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QProcess>
#include <QSignalSpy>
#include <QSpinBox>
#include <QStringList>
#include <QTemporaryDir>
#include <QToolButton>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>

/// In a test function: skips it when OpenFOAM is not installed, or fails it when
/// BENDER_REQUIRE_CFD is set (CI, where scripts/setup installed it).
#define BENDER_REQUIRE_OPENFOAM()                                                                  \
  do                                                                                               \
  {                                                                                                \
    if (bender::FindExecutable("simpleFoam").empty())                                              \
    {                                                                                              \
      if (qEnvironmentVariableIsSet("BENDER_REQUIRE_CFD"))                                         \
      {                                                                                            \
        QFAIL("simpleFoam is not installed but BENDER_REQUIRE_CFD is set (scripts/setup)");        \
      }                                                                                            \
      QSKIP("OpenFOAM is not installed (scripts/setup installs it)");                              \
    }                                                                                              \
  } while (false)

namespace bendertest
{

/// Types `value` into a spin box as a user does (all of it replaced, Enter).
inline void TypeInto(QAbstractSpinBox* box, const QString& value)
{
  box->setFocus();
  box->selectAll();
  QTest::keyClick(box, Qt::Key_Delete);
  QTest::keyClicks(box, value);
  QTest::keyClick(box, Qt::Key_Enter);
}

/// Clicks the panel's Run and waits for flowFinished; its argument (false when none came in
/// time). `whileRunning` runs once the jobs are under way.
inline bool RunFlowAndWait(FlowPanel* panel,
  int milliseconds,
  const std::function<void()>& whileRunning = {})
{
  QSignalSpy finished(panel, &FlowPanel::flowFinished);
  QTest::mouseClick(panel->runButton(), Qt::LeftButton);
  if (!panel->isRunning())
  {
    return false;
  }
  if (whileRunning)
  {
    whileRunning();
  }
  // flowFinished may have come while whileRunning waited.
  return (!finished.isEmpty() || finished.wait(milliseconds)) && finished.first().first().toBool();
}

/// The panel's table holds the numbers of the two case folders' results/flow.json, highlighted
/// as the comparison says, with pressure drop, split and WSS rows.
inline void ExpectTableOfTheResultsFiles(FlowPanel* panel,
  const QString& caseA,
  const QString& caseB)
{
  const bender::CfdComparison files =
    bender::CompareCfdResults(bender::ReadCfdFlowResults(caseA.toStdString()),
      bender::ReadCfdFlowResults(caseB.toStdString()));
  FlowComparisonTable* table = panel->table();
  QCOMPARE(table->rowCount(), static_cast<int>(files.rows.size()));
  bool pressureDrop = false, split = false, wss = false;
  for (const bender::CfdComparisonRow& row : files.rows)
  {
    const int r = table->rowOf(QString::fromStdString(row.key));
    QVERIFY2(r >= 0, row.key.c_str());
    const int decimals = bender::CfdRowDecimals(row);
    if (row.textA.empty() && row.a)
    {
      QVERIFY2(table->item(r, 1)->text().startsWith(
                 QString::fromStdString(bender::FormatCfdValue(row.a, decimals))),
        qPrintable(table->item(r, 1)->text()));
    }
    if (row.textB.empty() && row.b)
    {
      QVERIFY2(table->item(r, 2)->text().startsWith(
                 QString::fromStdString(bender::FormatCfdValue(row.b, decimals))),
        qPrintable(table->item(r, 2)->text()));
    }
    // Highlighted rows are drawn so.
    QCOMPARE(table->item(r, 0)->font().bold(), row.highlighted);
    pressureDrop = pressureDrop || row.kind == bender::CfdRowKind::Pressure;
    split = split || row.kind == bender::CfdRowKind::Split;
    wss = wss || row.kind == bender::CfdRowKind::Stress;
  }
  QVERIFY(pressureDrop && split && wss);
}

/// `bender-cli compare CASE_A CASE_B -o REPORT --json` (plus `extra`) gives the rows, numbers
/// and highlights of the panel's comparison.
inline void ExpectCompareGivesThePanelsNumbers(FlowPanel* panel,
  const QString& cli,
  const QString& caseA,
  const QString& caseB,
  const QString& report,
  const QStringList& extra = {})
{
  QProcess compare;
  compare.start(cli, QStringList{ "compare", caseA, caseB, "-o", report, "--json" } + extra);
  QVERIFY(compare.waitForFinished(300000));
  QVERIFY2(compare.exitCode() == 0, compare.readAllStandardError().constData());
  const QJsonArray rows =
    QJsonDocument::fromJson(compare.readAllStandardOutput()).object().value("rows").toArray();
  const bender::CfdComparison* shown = panel->comparison();
  QVERIFY(shown);
  QCOMPARE(rows.size(), static_cast<int>(shown->rows.size()));
  for (int i = 0; i < rows.size(); ++i)
  {
    const QJsonObject row = rows[i].toObject();
    const bender::CfdComparisonRow& mine = shown->rows[static_cast<std::size_t>(i)];
    QCOMPARE(row.value("key").toString(), QString::fromStdString(mine.key));
    QCOMPARE(row.value("highlighted").toBool(), mine.highlighted);
    const auto same = [](const QJsonValue& value, const std::optional<double>& number)
    {
      return value.isNull()
        ? !number
        : number && std::abs(value.toDouble() - *number) <= 1e-9 * std::max(1.0, std::abs(*number));
    };
    QVERIFY2(same(row.value("a"), mine.a), qPrintable(row.value("key").toString()));
    QVERIFY2(same(row.value("b"), mine.b), qPrintable(row.value("key").toString()));
  }
}

/// A test window (autosave in `folder`) shown and active, with a tube prepared for CFD (its open
/// ends capped and named, short extensions) then bent (the plan's Prepare step comes before its
/// warp), seen from above (the bend is about +z); the Flow panel in front with a small case (25
/// iterations, 1.6 mm cells). Null when the folder is not valid, the window could not be shown
/// or the session refused a step.
inline std::unique_ptr<MainWindow> BentTubeWindow(const QTemporaryDir& folder)
{
  if (!folder.isValid())
  {
    return nullptr;
  }
  auto window = std::make_unique<MainWindow>(TestWindowOptions(folder.path()));
  if (!ShowTestWindow(*window, true))
  {
    return nullptr;
  }
  bender::BenderSession& session = window->session();
  const auto tube = Tube(-20, 20, 5, 41, 32);
  bender::CfdStep step;
  step.clip = false;
  step.inletExtension = 2.0;
  step.outletExtension = 1.0;
  if (!session.SetSurface(tube, "tube") ||
    !session.CommitCfdStep(step, bender::ApplyCfdStep(tube, step).surface, false) ||
    !session.ApplyWarp(bender::test::Swing(0, 15, 20, 8)))
  {
    return nullptr;
  }
  window->actions()->StandardViews[4]->trigger();
  FlowPanel* panel = window->flowPanel();
  if (!ShowPanel(*window, panel))
  {
    return nullptr;
  }
  TypeInto(panel->iterationsBox(), "25");
  TypeInto(panel->cellSizeBox(), "1.60");
  const bool small = panel->caseOptions().iterations == 25 &&
    std::abs(panel->caseOptions().cellSize - 1.6e-3) < 1e-9;
  return small ? std::move(window) : nullptr;
}

} // namespace bendertest

#endif
