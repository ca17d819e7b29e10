// Safe commits, no lost work, trackers that start where the ribbon is (issue 12, items 4, 5, 6,
// 8) on the real window (QTest under Xvfb): the simulator connected to the demo moves nothing
// until its stylus press and then bends the branch from where the ribbon is, without flipped or
// crossing triangles; a crushing bend is held by the commit guard with its triangles drawn and
// the dialog's buttons cancel or keep it; "Save changes?" before the demo replaces warps; a
// plan already applied is not replayed again; after a crash, the next window recovers the
// volume, the segmentation parameters, the surface with its name, the warps and the ribbon
// (and, the volume file gone, the rest with one message); a DICOM series opened by its folder.
#include "AppTestUtilities.h"
#include "SwungRibbon.h"

#include "BendPanel.h"
#include "BenderMeshCheck.h"
#include "BenderSession.h"
#include "DemoPipeline.h"
#include "FileOpener.h"
#include "GestureController.h"
#include "MainActions.h"
#include "MainWindow.h"
#include "ProblemOverlay.h"
#include "SegmentPanel.h"
#include "SessionAutosave.h"
#include "SliceViews.h"
#include "TrackerSession.h"
#include "TrackersPanel.h"
#include "VolumeIO.h"
#include "WarpPlanIO.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QDialog>
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <QTemporaryDir>
#include <QTimer>
#include <QtTest>

#include <vtkPolyData.h>

#include <cmath>
#include <memory>

namespace
{

double EndDistance(const bender::RibbonEnd& a, const bender::RibbonEnd& b)
{
  using bender::Distance;
  using bender::Normalized;
  return std::max({ Distance(a.position, b.position),
    Distance(Normalized(a.tangent), Normalized(b.tangent)),
    Distance(Normalized(a.normal), Normalized(b.normal)) });
}

double RibbonDistance(const bender::RibbonSpec& a, const bender::RibbonSpec& b)
{
  return std::max(EndDistance(a.start, b.start), EndDistance(a.end, b.end));
}

vtkSmartPointer<vtkPolyData> Copy(vtkPolyData* surface)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(surface);
  return copy;
}

double MaxDifference(vtkPolyData* a, vtkPolyData* b)
{
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints())
    return HUGE_VAL;
  double worst = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(p[k] - q[k]));
  }
  return worst;
}

} // namespace

class SafetyAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  bender::RibbonSpec Placed;

  QString artefact(const QString& name)
  {
    QDir().mkpath(BENDER_ARTIFACT_DIR);
    return QString(BENDER_ARTIFACT_DIR) + "/" + name;
  }
  bender::RibbonSpec widgetRibbon()
  {
    return this->Window->ribbonWidget()->GetRibbonRepresentation()->GetRibbon();
  }
  bool hasMessage(const std::string& part) { return HasMessage(*this->Window, part); }
  static bool HasMessage(MainWindow& window, const std::string& part)
  {
    for (const auto& m : window.session().GetMessages())
      if (m.text.find(part) != std::string::npos)
        return true;
    return false;
  }
  static const bender::LogicMessage* FindMessage(MainWindow& window, const std::string& part)
  {
    for (const auto& m : window.session().GetMessages())
      if (m.text.find(part) != std::string::npos)
        return &m;
    return nullptr;
  }
  static int CountMessages(MainWindow& window, const std::string& part)
  {
    int count = 0;
    for (const auto& m : window.session().GetMessages())
      if (m.text.find(part) != std::string::npos)
        ++count;
    return count;
  }
  // A window that offers recovery at start, as Bender does; the recovery dialog is answered
  // `which` (its text and a picture of it kept).
  std::unique_ptr<MainWindow> startWindowAnsweringRecovery(const QString& folder,
    QMessageBox::StandardButton which,
    QString* text,
    const QString& picture)
  {
    auto* timer = new QTimer(this);
    timer->setInterval(50);
    auto deadline = std::make_shared<QElapsedTimer>();
    deadline->start();
    connect(timer,
      &QTimer::timeout,
      this,
      [timer, which, text, picture, deadline]()
      {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (deadline->elapsed() > 30000)
        {
          timer->stop();
          timer->deleteLater();
          return;
        }
        if (!box || box->objectName() != "recoverSession")
          return;
        timer->stop();
        timer->deleteLater();
        *text = box->text() + "\n" + box->informativeText();
        if (!picture.isEmpty())
          box->grab().save(picture);
        QTest::mouseClick(box->button(which), Qt::LeftButton);
      });
    timer->start();
    MainWindowOptions options = bendertest::TestWindowOptions(folder);
    options.offerRecovery = true;
    auto window = std::make_unique<MainWindow>(options);
    bendertest::ShowTestWindow(*window, false);
    return window;
  }
  // Answers the next modal message box with the button `which`; the text it showed lands in
  // `text`.
  void answerNextMessageBox(QMessageBox::StandardButton which, QString* text)
  {
    // Gives up after 30 s: a box that never came is the test's failure, not the next test's.
    auto* timer = new QTimer(this);
    timer->setInterval(50);
    auto deadline = std::make_shared<QElapsedTimer>();
    deadline->start();
    connect(timer,
      &QTimer::timeout,
      this,
      [timer, which, text, deadline]()
      {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box && deadline->elapsed() > 30000)
        {
          timer->stop();
          timer->deleteLater();
          return;
        }
        if (!box)
          return;
        timer->stop();
        timer->deleteLater();
        if (text)
          *text = box->text();
        QTest::mouseClick(box->button(which), Qt::LeftButton);
      });
    timer->start();
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    QCoreApplication::setOrganizationName("BenderSafetyTest");
    QSettings().clear();
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*this->Window, false));
    this->Window->startDemo();
    QVERIFY(this->Window->waitUntilIdle(180000));
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.HasSurface());
    // The demo placed its ribbon: the session knows it (r_min, the trackers' anchor).
    QVERIFY(this->Window->ribbonWidget()->GetEnabled());
    QVERIFY(session.GetRibbon().has_value());
    this->Placed = *session.GetRibbon();
    QVERIFY(RibbonDistance(this->Placed, this->widgetRibbon()) < 1e-12);
    QVERIFY(!session.HasUnsavedChanges());
  }

  void theBendPanelShowsTheSessionsOneMinimumRadius()
  {
    // The panel and the status bar's warning quote one r_min, the session's: while grabbed the
    // smaller of the initial and the final wire's (here the straight placed wire swung into an
    // arc), and the placed ribbon's once the bend is cancelled.
    bender::BenderSession& session = this->Window->session();
    auto* label = this->Window->findChild<QLabel*>("minimumRadius");
    QVERIFY(label);
    const auto expected = [&]
    {
      const double rmin = session.GetMinimumRadius();
      return std::isfinite(rmin) && rmin < 1e6 ? QString("r_min = %1 mm").arg(rmin, 0, 'f', 2)
                                               : QString("r_min: none (straight wire)");
    };
    QVERIFY(this->Window->grab());
    this->Window->setRibbon(bendertest::Swung(this->Placed, 30));
    QTRY_VERIFY(std::isfinite(session.GetMinimumRadius()) && session.GetMinimumRadius() < 1e6);
    QTRY_VERIFY2(label->text().contains(expected()), qPrintable(label->text()));
    if (session.GetSpaceInversionRisk())
    {
      QVERIFY(label->text().contains(QString::fromStdString(session.GetSpaceInversionWarning())));
    }
    // Swung further while grabbed, the wire's r_min changes: the status bar's warning, given
    // once in the grab, follows it (it kept the first value before).
    this->Window->setRibbon(bendertest::Swung(this->Placed, 60));
    QTRY_VERIFY(session.GetSpaceInversionRisk());
    const double firstMinimum = session.GetMinimumRadius();
    this->Window->setRibbon(bendertest::Swung(this->Placed, 80));
    QTRY_VERIFY(session.GetSpaceInversionRisk());
    QVERIFY(std::abs(session.GetMinimumRadius() - firstMinimum) > 0.01);
    const QString warning = QString::fromStdString(session.GetSpaceInversionWarning());
    QVERIFY2(
      warning.contains(QString::number(session.GetMinimumRadius(), 'g', 3)), qPrintable(warning));
    QTRY_COMPARE(this->Window->statusLabel()->text(), warning);
    QVERIFY(label->text().contains(warning));
    this->Window->gesture()->cancelHeld();
    QVERIFY(this->Window->waitUntilIdle(60000));
    QTRY_VERIFY2(label->text().contains(expected()), qPrintable(label->text()));
  }

  void cleanup()
  {
    // Each function starts with nothing grabbed or held, whatever the previous one left.
    this->Window->disconnectTrackers();
    this->Window->waitUntilIdle(60000);
    if (this->Window->session().GetState() == bender::GrabState::Grabbed)
      this->Window->gesture()->cancelHeld();
  }

  void cleanupTestCase()
  {
    this->Window->disconnectTrackers();
    this->Window->close();
    this->Window.reset();
    QSettings().clear();
  }

  void simulatorStartsWhereTheRibbonIsAndBendsGracefully()
  {
    bender::BenderSession& session = this->Window->session();
    auto before = Copy(session.GetSurface());
    TrackersPanel* panel = this->Window->trackersPanel();
    panel->setDeviceSpec("sim");
    QCOMPARE(panel->motionScale(), 0.0); // automatic by default
    QVERIFY(this->Window->connectTrackers());
    QVERIFY(this->Window->trackers().IsRelative());
    // Until the stylus press at 1 s of the script: nothing moves, the ribbon stays put.
    QElapsedTimer timer;
    timer.start();
    int checked = 0;
    while (timer.elapsed() < 700)
    {
      QTest::qWait(20);
      if (session.GetState() == bender::GrabState::Grabbed)
        break;
      QVERIFY(RibbonDistance(this->widgetRibbon(), this->Placed) < 1e-6);
      QCOMPARE(MaxDifference(session.GetDisplaySurface(), before), 0.0);
      ++checked;
    }
    // (How many checks fit before the press depends on the machine's speed; the warp's initial
    // ribbon below says the same whatever the timing.)
    Q_UNUSED(checked);
    QVERIFY(this->Window->saveScreenshot(this->artefact("safety-trackers-connected.png")));
    // Mid-bend, for the documentation's screenshot (taken only when the grab is seen: the
    // checks below do not depend on it).
    // The Trackers panel in front: the picture shows the devices driving the ribbon.
    QVERIFY(bendertest::ShowPanel(*this->Window, panel));
    if (QTest::qWaitFor([&]() { return session.GetState() == bender::GrabState::Grabbed; }, 5000))
    {
      QTest::qWait(2500);
      QVERIFY(this->Window->saveScreenshot(this->artefact("safety-trackers-bending.png")));
    }
    // One press (1 s), the bend (1-4 s), the release (5 s): one commit, started where the
    // ribbon was.
    QTRY_VERIFY_WITH_TIMEOUT(session.GetHistoryPosition() == 1 || session.IsCommitHeld(), 20000);
    this->Window->disconnectTrackers();
    QVERIFY(this->Window->waitUntilIdle(60000));
    if (session.IsCommitHeld())
    {
      // Never a flipped or crossing triangle. The user reduces R and retries: the R proposed
      // passes the same checks and is not below the vessel's radius.
      const bender::CommitCheck& check = session.GetHeldCheck();
      QVERIFY2(
        check.flippedTriangles == 0 && check.newSelfIntersections == 0, check.Summary().c_str());
      QDialog* dialog = this->Window->gesture()->commitGuardDialog();
      QTRY_VERIFY(dialog->isVisible());
      QVERIFY(this->Window->grabWindowImage().save(this->artefact("safety-trackers-held.png")));
      const double held = session.GetParameters().radius;
      QTest::mouseClick(dialog->findChild<QPushButton*>("guardReduce"), Qt::LeftButton);
      QVERIFY(this->Window->waitUntilIdle(120000));
      QTest::qWait(50); // the release that follows the search
      QVERIFY(this->Window->waitUntilIdle(120000));
      QVERIFY2(!session.IsCommitHeld(), session.GetHeldCheck().Summary().c_str());
      QVERIFY(session.GetParameters().radius < held);
      QVERIFY(session.GetParameters().radius >= this->Window->gesture()->vesselRadius());
    }
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    const bender::WarpSpec warp = session.GetPlan().warps.front();
    QVERIFY(RibbonDistance(warp.initial, this->Placed) < 1e-6);
    QVERIFY(MaxDifference(session.GetSurface(), before) > 0.5);
    // Gracefully: no flipped triangle, no new crossing (the export check's numbers).
    const bender::MeshCheckReport report = bender::CheckMesh(session.GetSurface(), before);
    QCOMPARE(report.flippedTriangles, vtkIdType(0));
    QCOMPARE(report.selfIntersections, bender::CheckMesh(before).selfIntersections);
    // The ribbon lies on the bent branch: the committed final ribbon.
    QVERIFY(RibbonDistance(this->widgetRibbon(), warp.final) < 1e-9);
    QVERIFY(this->Window->saveScreenshot(this->artefact("safety-trackers-bent.png")));
    QVERIFY(session.HasUnsavedChanges());
    // Undo: the ribbon goes back onto the surface, where it was grabbed.
    this->Window->actions()->Undo->trigger(); // Edit > Undo (Ctrl+Z)
    QTRY_VERIFY(session.GetHistoryPosition() == 0);
    QTRY_VERIFY(RibbonDistance(this->widgetRibbon(), this->Placed) < 1e-9);
    // The Bend panel in front again for the functions (and pictures) that follow.
    QVERIFY(bendertest::ShowPanel(*this->Window, this->Window->bendPanel()));
  }

  void commitGuardHoldsACrushingBend()
  {
    bender::BenderSession& session = this->Window->session();
    auto before = Copy(session.GetSurface());
    GestureController* gesture = this->Window->gesture();
    QVERIFY(this->Window->grab());
    // The branch's end swung by 170 degrees: it folds onto itself.
    this->Window->setRibbon(bendertest::Swung(this->Placed, 170));
    QVERIFY(this->Window->release());
    QVERIFY(this->Window->waitUntilIdle(60000));
    QVERIFY(session.IsCommitHeld());
    QCOMPARE(session.GetHistoryPosition(), std::size_t(0));
    QCOMPARE(MaxDifference(session.GetSurface(), before), 0.0);
    const bender::CommitCheck& check = session.GetHeldCheck();
    QVERIFY(!check.Passed());
    // The dialog says what failed; the triangles are drawn.
    QDialog* dialog = gesture->commitGuardDialog();
    QTRY_VERIFY(dialog->isVisible());
    const QString text = dialog->findChild<QLabel*>("commitGuardText")->text();
    QVERIFY2(text.contains(QString::fromStdString(check.problems.front()).toHtmlEscaped()),
      qPrintable(text));
    if (!check.problemCells.empty())
    {
      QVERIFY(gesture->problemOverlay()->IsShown());
      QCOMPARE(
        gesture->problemOverlay()->GetNumberOfTriangles(), vtkIdType(check.problemCells.size()));
    }
    // The status bar says the same as the dialog, with the same r_min.
    QVERIFY(this->Window->statusLabel()->toolTip().contains("Commit held"));
    QVERIFY(this->Window->grabWindowImage().save(this->artefact("safety-commit-guard.png")));
    // The dialog alone too (grabWindowImage() grabs the main window only).
    QVERIFY(dialog->grab().save(this->artefact("safety-commit-guard-dialog.png")));
    // Cancel: nothing committed, the ribbon back where it was grabbed.
    QTest::mouseClick(dialog->findChild<QPushButton*>("guardCancel"), Qt::LeftButton);
    QVERIFY(!dialog->isVisible());
    QVERIFY(!gesture->problemOverlay()->IsShown());
    QCOMPARE(session.GetState(), bender::GrabState::Idle);
    QCOMPARE(session.GetHistoryPosition(), std::size_t(0));
    QCOMPARE(MaxDifference(session.GetDisplaySurface(), before), 0.0);
    QVERIFY(RibbonDistance(this->widgetRibbon(), this->Placed) < 1e-9);

    // Again, and keep it this time: committed as computed, with a warning.
    QVERIFY(this->Window->grab());
    this->Window->setRibbon(bendertest::Swung(this->Placed, 170));
    QVERIFY(this->Window->release());
    QVERIFY(this->Window->waitUntilIdle(60000));
    QTRY_VERIFY(dialog->isVisible());
    QTest::mouseClick(dialog->findChild<QPushButton*>("guardKeep"), Qt::LeftButton);
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QVERIFY(!session.IsCommitHeld());
    QVERIFY(this->hasMessage("committed although the check found"));
  }

  void planAppliedTwiceIsNotReplayedAgain()
  {
    bender::BenderSession& session = this->Window->session();
    const QString plan = this->Folder.filePath("kept.bender.json");
    QVERIFY(session.SavePlan(plan.toStdString()));
    QVERIFY(!session.HasUnsavedChanges());
    auto bent = Copy(session.GetSurface());
    QVERIFY(!this->Window->openFile(plan)); // refused at once: not interactive
    QVERIFY(this->hasMessage("not applied again"));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QCOMPARE(MaxDifference(session.GetSurface(), bent), 0.0);
  }

  void theDemoAsksBeforeReplacingUnsavedWarps()
  {
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.Undo()); // unsaved again
    QVERIFY(session.HasUnsavedChanges());
    FileOpener* files = this->Window->files();
    files->setInteractive(true);
    // Cancel: the demo does not start, the work stays.
    QString asked;
    this->answerNextMessageBox(QMessageBox::Cancel, &asked);
    this->Window->actions()->Demo->trigger();
    QVERIFY2(asked.contains("not saved"), qPrintable(asked));
    QVERIFY(!this->Window->isBusy());
    QVERIFY(session.HasUnsavedChanges());
    QCOMPARE(session.GetHistoryPosition(), std::size_t(0));
    QVERIFY(session.CanRedo());
    // Discard: the demo runs; the work counts as discarded.
    asked.clear();
    this->answerNextMessageBox(QMessageBox::Discard, &asked);
    this->Window->actions()->Demo->trigger();
    QVERIFY(!asked.isEmpty());
    QVERIFY(this->Window->waitUntilIdle(180000));
    QVERIFY(!session.CanRedo());
    QVERIFY(!session.HasUnsavedChanges());
    // Nothing unsaved: no question at all.
    // (A box would block confirmDiscard in its event loop, where this watcher answers it; the
    // watcher lives no longer than this function, so it never answers a later test's box.)
    bool askedAgain = false;
    QTimer watcher;
    watcher.setInterval(50);
    connect(&watcher,
      &QTimer::timeout,
      this,
      [&askedAgain]()
      {
        if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget()))
        {
          askedAgain = true;
          QTest::mouseClick(box->button(QMessageBox::Cancel), Qt::LeftButton);
        }
      });
    watcher.start();
    QVERIFY(files->confirmDiscard("Quit"));
    watcher.stop();
    QVERIFY(!askedAgain);
    files->setInteractive(false);
  }

  void quitAsksAndKeepsTheAutosaveOfUnsavedWork()
  {
    QTemporaryDir folder;
    const QString autosave = folder.filePath("autosave.bender-session.json");
    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(folder.path()));
    window->show();
    QVERIFY(QTest::qWaitForWindowExposed(window.get()));
    bender::BenderSession& session = window->session();
    QVERIFY(session.SetSurface(bendertest::Tube(0, 60, 3), "tube"));
    // The lumen guard on: the ribbon runs to the tube's open end, so the bend turns the tube's
    // end whole (a ribbon ending mid-tube would shear the tube beyond it: a waist it holds).
    QVERIFY(session.GetLumenGuard().enabled);
    bender::RibbonSpec ribbon;
    ribbon.start.position = { 20, 0, 0 };
    ribbon.end.position = { 60, 0, 0 };
    bender::WarpParameters parameters = session.GetParameters();
    parameters.radius = 6;
    QVERIFY(session.SetParameters(parameters));
    QVERIFY(session.Grab(ribbon));
    QVERIFY(session.MoveFinal(bendertest::Swung(ribbon, 30)));
    QVERIFY(session.Release());
    QVERIFY(QFileInfo::exists(autosave));
    // Interactive: Quit asks; Cancel keeps the window open.
    window->files()->setInteractive(true);
    QString asked;
    this->answerNextMessageBox(QMessageBox::Cancel, &asked);
    window->close();
    QVERIFY(!asked.isEmpty());
    QVERIFY(window->isVisible());
    // Not asked (a test window): the window closes, the unsaved warps stay recoverable.
    window->files()->setInteractive(false);
    QVERIFY(window->close());
    QVERIFY(QFileInfo::exists(autosave));
    bender::BenderSession recovered;
    QVERIFY(recovered.Recover(autosave.toStdString()));
    QCOMPARE(recovered.GetHistoryPosition(), std::size_t(1));
    QCOMPARE(recovered.GetSurfaceName(), std::string("tube"));
    window.reset();
  }

  void recoveryAfterACrashRestoresEverything()
  {
    QTemporaryDir folder;
    const QString autosave = folder.filePath("autosave.bender-session.json");
    // The demo's MRA-like volume as a file the user opens.
    const auto demoVolume = this->Window->segmentation().GetVolume();
    QVERIFY(demoVolume);
    const QString nrrd = folder.filePath("mra.nrrd");
    bender::WriteVolume(*demoVolume, nrrd.toStdString());

    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*window, false));
    QVERIFY(window->openFile(nrrd));
    QVERIFY(window->waitUntilIdle(60000));
    QVERIFY(window->segmentation().HasVolume());
    // The user's parameters, through the Segment panel, then Segment.
    auto* threshold = window->segmentPanel()->findChild<QDoubleSpinBox*>("lumenThreshold");
    auto* smoothing = window->segmentPanel()->findChild<QDoubleSpinBox*>("smoothing");
    QVERIFY(threshold && smoothing);
    threshold->setValue(240.5);
    smoothing->setValue(0.35);
    QVERIFY(window->segmentVolume());
    QVERIFY(window->waitUntilIdle(180000));
    bender::BenderSession& session = window->session();
    QVERIFY(session.HasSurface());
    QCOMPARE(session.GetSurfaceName(), std::string("segmented vessel"));
    // Bent by the demo plan, then a ribbon placed for the next bend with R = 7.25.
    const bender::WarpPlan plan = bender::ReadWarpPlan(bender::DemoPlanPath());
    QVERIFY(window->openFile(QString::fromStdString(bender::DemoPlanPath())));
    QVERIFY(window->waitUntilIdle(120000));
    QCOMPARE(session.GetHistoryPosition(), plan.warps.size());
    bender::WarpParameters parameters = window->bendPanel()->parameters();
    parameters.radius = 7.25;
    window->bendPanel()->setParameters(parameters);
    window->gesture()->applyParameters();
    const bender::RibbonSpec placed = plan.warps.front().initial;
    window->gesture()->showRibbon(placed, 3.0);
    QVERIFY(session.GetRibbon().has_value());
    QVERIFY(RibbonDistance(*session.GetRibbon(), placed) < 1e-12);
    QVERIFY(session.HasUnsavedChanges());
    // The placed ribbon changes no warp: the window autosaves it once it rests.
    const auto autosavedRibbon = [&]()
    {
      const bender::SessionSnapshot s = bender::ReadSessionFile(autosave.toStdString());
      return s.ribbon && RibbonDistance(s.ribbon->ribbon, placed) < 1e-12 &&
        s.ribbon->radius == 7.25;
    };
    QTRY_VERIFY_WITH_TIMEOUT(autosavedRibbon(), 10000);

    const bender::ImageGeometry geometry = window->segmentation().GetVolume()->geometry;
    QVERIFY(window->segmentation().GetMask());
    const std::vector<std::uint8_t> maskVoxels = window->segmentation().GetMask()->voxels;
    const bender::SegmentationSettings settings = window->segmentation().GetSettings();
    QCOMPARE(settings.segmentation.lower, 240.5);
    QCOMPARE(settings.surface.smoothing, 0.35);
    const auto bent = Copy(session.GetSurface());
    const std::string planText = bender::SerializeWarpPlan(session.GetPlan());

    // The crash: the window goes without its close (no question, no clean exit).
    window.reset();
    QVERIFY(QFileInfo::exists(autosave));

    // The next start offers the recovery, listing what it holds; the user recovers.
    QString asked;
    auto recovered = this->startWindowAnsweringRecovery(
      folder.path(), QMessageBox::Yes, &asked, this->artefact("safety-recovery-dialog.png"));
    QTRY_VERIFY_WITH_TIMEOUT(!asked.isEmpty(), 20000);
    QVERIFY2(asked.contains("segmented vessel") && asked.contains("mra.nrrd") &&
        asked.contains(
          QString("%1 warp%2").arg(plan.warps.size()).arg(plan.warps.size() == 1 ? "" : "s")) &&
        asked.contains("threshold 240.5") && asked.contains("ribbon"),
      qPrintable(asked));
    bender::BenderSession& again = recovered->session();
    QTRY_VERIFY_WITH_TIMEOUT(again.HasSurface(), 60000);
    QVERIFY(recovered->waitUntilIdle(120000));

    // The volume: read again, the same grid, in the slice views.
    QVERIFY(recovered->segmentation().HasVolume());
    const bender::ImageGeometry& back = recovered->segmentation().GetVolume()->geometry;
    QCOMPARE(back.size, geometry.size);
    QCOMPARE(back.spacing, geometry.spacing);
    QVERIFY(bender::SameVolumeGeometry(back, geometry));
    QCOMPARE(QString::fromStdString(recovered->segmentation().GetVolumeSource().path),
      QFileInfo(nrrd).absoluteFilePath());
    QVERIFY(recovered->sliceViews()->hasVolume());
    // With the segmentation's mask (the slices' overlay), voxel for voxel.
    QVERIFY(recovered->segmentation().GetMask());
    QVERIFY(recovered->segmentation().GetMask()->voxels == maskVoxels);
    QVERIFY(recovered->sliceViews()->isVisible());
    // The segmentation parameters, in the session and in the Segment panel.
    const bender::SegmentationSettings& restored = recovered->segmentation().GetSettings();
    QCOMPARE(restored.segmentation.lower, settings.segmentation.lower);
    QCOMPARE(restored.surface.smoothing, settings.surface.smoothing);
    QCOMPARE(int(restored.segmentation.method), int(settings.segmentation.method));
    QCOMPARE(restored.segmentation.upper, settings.segmentation.upper);
    QCOMPARE(restored.segmentation.fillHoles, settings.segmentation.fillHoles);
    SegmentPanel* panel = recovered->segmentPanel();
    QCOMPARE(panel->findChild<QDoubleSpinBox*>("lumenThreshold")->value(), 240.5);
    QCOMPARE(panel->findChild<QDoubleSpinBox*>("smoothing")->value(), 0.35);
    QCOMPARE(panel->settings().segmentation.lower, 240.5);
    // The surface: its name, the bent points, the plan.
    QCOMPARE(again.GetSurfaceName(), std::string("segmented vessel"));
    QCOMPARE(again.GetHistoryPosition(), plan.warps.size());
    QCOMPARE(bender::SerializeWarpPlan(again.GetPlan()), planText);
    QCOMPARE(again.GetSurface()->GetNumberOfPoints(), bent->GetNumberOfPoints());
    QVERIFY2(MaxDifference(again.GetSurface(), bent) < 1e-9,
      qPrintable(QString::number(MaxDifference(again.GetSurface(), bent))));
    // The ribbon where it was placed, with its R; recovered work is unsaved work.
    QVERIFY(again.GetRibbon().has_value());
    QVERIFY(RibbonDistance(*again.GetRibbon(), placed) < 1e-12);
    QVERIFY(recovered->ribbonWidget()->GetEnabled());
    QVERIFY(RibbonDistance(
              recovered->ribbonWidget()->GetRibbonRepresentation()->GetRibbon(), placed) < 1e-12);
    QCOMPARE(again.GetParameters().radius, 7.25);
    QVERIFY(again.HasUnsavedChanges());
    QVERIFY(HasMessage(*recovered, "Recovered the surface \"segmented vessel\""));
    QVERIFY(recovered->saveScreenshot(this->artefact("safety-recovered.png")));

    // Another crash, and the volume file now holds another volume (another grid): not loaded,
    // one message saying both grids, the rest recovered.
    recovered.reset();
    const QString kept = folder.filePath("kept.bender-session.json");
    QVERIFY(QFile::copy(autosave, kept));
    bender::WriteVolume(bender::ResampleVolume(*demoVolume, { 40, 40, 40 }), nrrd.toStdString());
    asked.clear();
    auto changed = this->startWindowAnsweringRecovery(folder.path(), QMessageBox::Yes, &asked, {});
    QTRY_VERIFY_WITH_TIMEOUT(!asked.isEmpty(), 20000);
    QTRY_VERIFY_WITH_TIMEOUT(changed->session().HasSurface(), 60000);
    QVERIFY(changed->waitUntilIdle(120000));
    QVERIFY(!changed->segmentation().HasVolume());
    QCOMPARE(changed->session().GetHistoryPosition(), plan.warps.size());
    const bender::LogicMessage* refused = FindMessage(*changed, "was not loaded");
    QVERIFY(refused);
    QVERIFY2(refused->text.find("now holds 40x40x40 voxels") != std::string::npos &&
        refused->text.find(bender::DescribeVolumeGeometry(geometry)) != std::string::npos &&
        refused->text.find("Recovered the surface") != std::string::npos,
      refused->text.c_str());

    // Another crash (the autosave as it was before), and the volume file is gone: one message,
    // the rest recovered.
    changed.reset();
    QVERIFY(QFile::remove(autosave));
    QVERIFY(QFile::copy(kept, autosave));
    QVERIFY(QFile::remove(nrrd));
    asked.clear();
    auto partial = this->startWindowAnsweringRecovery(folder.path(), QMessageBox::Yes, &asked, {});
    QTRY_VERIFY_WITH_TIMEOUT(!asked.isEmpty(), 20000);
    QTRY_VERIFY_WITH_TIMEOUT(partial->session().HasSurface(), 60000);
    QVERIFY(partial->waitUntilIdle(120000));
    QVERIFY(!partial->segmentation().HasVolume());
    QCOMPARE(partial->session().GetHistoryPosition(), plan.warps.size());
    QVERIFY(MaxDifference(partial->session().GetSurface(), bent) < 1e-9);
    QCOMPARE(partial->segmentation().GetSettings().segmentation.lower, 240.5);
    QCOMPARE(CountMessages(*partial, "mra.nrrd"), 1);
    const bender::LogicMessage* said = FindMessage(*partial, "could not be read");
    QVERIFY(said);
    QCOMPARE(int(said->severity), int(bender::MessageSeverity::Warning));
    QVERIFY2(said->text.find("mra.nrrd") != std::string::npos &&
        said->text.find("Recovered the surface \"segmented vessel\"") != std::string::npos,
      said->text.c_str());
    QVERIFY(partial->saveScreenshot(this->artefact("safety-recovered-without-volume.png")));

    // Discard at the next start: the autosave and what lies beside it go.
    partial.reset();
    asked.clear();
    auto discarded = this->startWindowAnsweringRecovery(folder.path(), QMessageBox::No, &asked, {});
    QTRY_VERIFY_WITH_TIMEOUT(!asked.isEmpty(), 20000);
    QTRY_VERIFY(!QFileInfo::exists(autosave));
    QVERIFY(!discarded->session().HasSurface());
    discarded.reset();
  }

  void aDicomSeriesOpensByItsFolder()
  {
    // File > Open DICOM folder is in the menu with its own folder memory.
    QAction* action = this->Window->actions()->OpenDicomFolder;
    QVERIFY(action);
    bool inFileMenu = false;
    for (QMenu* menu : this->Window->menuBar()->findChildren<QMenu*>())
      if (menu->title() == "&File" && menu->actions().contains(action))
        inFileMenu = true;
    QVERIFY(inFileMenu);
    // Two series in one folder (the project's two real DICOM slices): one is read, and the
    // status bar says which and what else is there.
    const QString external =
      QFileInfo(QString::fromStdString(bender::DemoVesselPath())).absolutePath();
    QTemporaryDir folder;
    const QString study = folder.filePath("study");
    QVERIFY(QDir().mkpath(study));
    QVERIFY(QFile::copy(external + "/CT_small.dcm", study + "/ct.dcm"));
    QVERIFY(QFile::copy(external + "/MR_small.dcm", study + "/mr.dcm"));
    QVERIFY(this->Window->files()->openDicomFolder(study));
    QVERIFY(this->Window->waitUntilIdle(60000));
    QVERIFY(this->Window->segmentation().HasVolume());
    QCOMPARE(this->Window->segmentation().GetVolumeName(), std::string("study"));
    QVERIFY(!this->Window->segmentation().GetVolumeSource().dicomSeriesUid.empty());
    const bender::LogicMessage* said = FindMessage(*this->Window, "study: 2 DICOM series");
    QVERIFY(said);
    QVERIFY2(said->text.find("read the largest") != std::string::npos, said->text.c_str());
    QVERIFY(this->Window->sliceViews()->hasVolume());
    // A folder without DICOM: one line naming it; the volume loaded stays.
    const QString empty = folder.filePath("notes");
    QVERIFY(QDir().mkpath(empty));
    QFile(empty + "/readme.txt").open(QIODevice::WriteOnly);
    QVERIFY(this->Window->files()->openDicomFolder(empty));
    QVERIFY(this->Window->waitUntilIdle(60000));
    const bender::LogicMessage* refused = FindMessage(*this->Window, "no DICOM series");
    QVERIFY(refused);
    QCOMPARE(int(refused->severity), int(bender::MessageSeverity::Error));
    QVERIFY2(refused->text.find("notes") != std::string::npos, refused->text.c_str());
    QCOMPARE(this->Window->segmentation().GetVolumeName(), std::string("study"));
    // Not a folder at all.
    QVERIFY(!this->Window->files()->openDicomFolder(folder.filePath("missing")));
    QVERIFY(this->hasMessage("missing: not a folder"));
  }

  void dialogsRememberTheLastFolder()
  {
    QDir(this->Folder.path()).mkpath("plans");
    FileOpener::rememberFolder("plan", this->Folder.filePath("plans/a.bender.json"));
    QCOMPARE(
      FileOpener::lastFolder("plan"), QFileInfo(this->Folder.filePath("plans")).absoluteFilePath());
    QCOMPARE(FileOpener::lastFolder("never-used"), QDir::homePath());
  }
};

QTEST_MAIN(SafetyAppTest)
#include "SafetyAppTest.moc"
