// The application as a user drives it: the real main window loads the demo, places the
// ribbon, grabs, drags a handle with a recorded event log, releases; undo/redo, plan
// save/load/replay, export checked by bender-cli, a screenshot, a replayed tracker recording,
// and a corrupt file dropped on the window. Run under Xvfb (QT_QPA_PLATFORM=xcb).
#include "AppTestUtilities.h"
#include "BendPanel.h"
#include "DemoPipeline.h"
#include "MainWindow.h"
#include "MeshIO.h"
#include "Ribbon.h"
#include "SessionAutosave.h"
#include "SliceViews.h"
#include "TrackersPanel.h"
#include "VesselController.h"
#include "VolumeIO.h"
#include "WarpPlanIO.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAbstractButton>
#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QMimeData>
#include <QProcess>
#include <QPushButton>
#include <QSignalSpy>
#include <QSurfaceFormat>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkInteractorObserver.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include "LogicTestUtilities.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <thread>

namespace
{

using bender::test::MaxDifference;

vtkSmartPointer<vtkPolyData> Copy(vtkPolyData* surface)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(surface);
  return copy;
}

double DistanceToWire(const bender::RibbonSpec& ribbon, const double p[3])
{
  const bender::Ribbon wire(ribbon);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 2000; ++i)
  {
    best = std::min(best, bender::Distance({ p[0], p[1], p[2] }, wire.Wire().PointAt(i / 2000.0)));
  }
  return best;
}

}

class BenderAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  vtkSmartPointer<vtkPolyData> Segmented;
  vtkSmartPointer<vtkPolyData> AfterFirstBend;
  // The slow fake job: while SlowJobs, every background job first waits on the worker until
  // the GUI thread's timer has ticked 5 more times (so it ends only if the event loop turns).
  std::atomic<bool> SlowJobs{ false };
  std::atomic<int> Ticks{ 0 };
  std::atomic<int> Stalls{ 0 };
  std::atomic<int> SlowJobsRun{ 0 };
  // The copies beside the autosave, held the same way while HoldCopies: a copy written on the
  // GUI thread would never see the ticks and count a stall.
  std::atomic<bool> HoldCopies{ false };
  std::atomic<int> HeldCopies{ 0 };
  std::atomic<int> CopyStalls{ 0 };

  void showPanel(QWidget* panel)
  {
    auto* panels = this->Window->findChild<QTabWidget*>("panels");
    QVERIFY(panels);
    panels->setCurrentWidget(panel);
  }

  QString artefact(const QString& name)
  {
    QDir().mkpath(BENDER_ARTIFACT_DIR);
    return QString(BENDER_ARTIFACT_DIR) + "/" + name;
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    MainWindowOptions options;
    options.autosavePath = this->Folder.filePath("autosave.bender-session.json");
    options.offerRecovery = false;
    options.interactive = false;
    options.workHook = [this](const bender::ProgressReporter& progress)
    {
      if (!this->SlowJobs)
        return;
      ++this->SlowJobsRun;
      const int start = this->Ticks;
      for (int wait = 0; this->Ticks < start + 5 && !progress.Cancelled(); ++wait)
      {
        if (wait > 60000)
        {
          ++this->Stalls; // a minute without 5 ticks: the GUI thread is blocked
          return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    };
    options.autosaveCopyHook = [this]()
    {
      if (!this->HoldCopies)
        return;
      ++this->HeldCopies;
      const int start = this->Ticks;
      for (int wait = 0; this->Ticks < start + 5; ++wait)
      {
        if (wait > 60000)
        {
          ++this->CopyStalls; // a minute without 5 ticks: the GUI thread is blocked
          return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    };
    this->Window = std::make_unique<MainWindow>(options);
    QVERIFY(bendertest::ShowTestWindow(*this->Window, true));
  }

  void cleanupTestCase()
  {
    this->Window->close();
    this->Window.reset();
  }

  void cancelStopsTheWorkAndChangesNothing()
  {
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    this->Window->startDemo();
    QVERIFY(this->Window->isBusy());
    auto* cancel = this->Window->findChild<QPushButton*>("cancelWork");
    QVERIFY(cancel && cancel->isVisible());
    QTest::mouseClick(cancel, Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(finished.count(), 1);
    QCOMPARE(finished.first().first().toBool(), false);
    QVERIFY(!this->Window->session().HasSurface());
    QVERIFY(!cancel->isVisible());
  }

  void demoSegmentsAndPlacesTheRibbon()
  {
    QTimer timer;
    connect(&timer, &QTimer::timeout, [this]() { ++this->Ticks; });
    timer.start(5);
    this->HoldCopies = true;
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    this->Window->startDemo();
    QVERIFY(this->Window->isBusy());
    QVERIFY(this->Window->waitUntilIdle(180000));
    QCOMPARE(finished.count(), 1);
    QCOMPARE(finished.first().first().toBool(), true);
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.HasSurface());
    QVERIFY(session.GetSurface()->GetNumberOfPolys() > 10000);
    QVERIFY(this->Window->ribbonWidget()->GetEnabled());
    const bender::WarpPlan plan = bender::ReadWarpPlan(bender::DemoPlanPath());
    const auto& ribbon = this->Window->ribbonWidget()->GetRibbonRepresentation()->GetRibbon();
    QCOMPARE(ribbon.start.position.x, plan.warps[0].initial.start.position.x);
    QCOMPARE(session.GetParameters().radius, plan.warps[0].radius);
    QVERIFY(this->Window->findChild<SliceViews*>()->isVisible());
    QVERIFY2(this->Window->statusLabel()->text().contains("press G"),
      qPrintable(this->Window->statusLabel()->text()));
    this->Segmented = Copy(session.GetSurface());

    // The demo's volume has no file: the autosave keeps a copy beside itself, written off the
    // GUI thread (the copy waits for the GUI thread's ticks), and names it only once the copy
    // is complete: whenever the autosave names a volume, the file is the whole volume.
    const QString autosave = this->Folder.filePath("autosave.bender-session.json");
    const auto volume = this->Window->segmentation().GetVolume();
    QVERIFY(volume);
    const bool hasMask = static_cast<bool>(this->Window->segmentation().GetMask());
    const std::string copy = bender::SessionVolumeCopyPath(autosave.toStdString());
    int incomplete = 0;
    const auto keptWhole = [&]()
    {
      if (!QFileInfo::exists(autosave))
        return false;
      const bender::SessionSnapshot kept = bender::ReadSessionFile(autosave.toStdString());
      if (!kept.volume)
        return false;
      if (bender::ReadVolume(kept.volume->path).voxels != volume->voxels)
        ++incomplete;
      return kept.volume->path == copy && (!hasMask || !kept.volume->maskPath.empty());
    };
    QTRY_VERIFY_WITH_TIMEOUT(keptWhole(), 120000);
    QCOMPARE(incomplete, 0);
    QVERIFY(this->HeldCopies >= 1);
    QCOMPARE(this->CopyStalls.load(), 0);
    this->HoldCopies = false;
  }

  void grabDragReleaseMovesOnlyInsideR()
  {
    bender::BenderSession& session = this->Window->session();
    auto* rep = this->Window->ribbonWidget()->GetRibbonRepresentation();
    const bender::RibbonSpec initial = rep->GetRibbon();
    QVERIFY(this->Window->grab());
    QCOMPARE(session.GetState(), bender::GrabState::Grabbed);

    // Drag the end handle 80 pixels across the view with a recorded event log.
    this->Window->render();
    double world[3], display[3];
    rep->GetHandlePosition(vtkBenderRibbonRepresentation::EndPosition, world);
    vtkInteractorObserver::ComputeWorldToDisplay(
      this->Window->renderer(), world[0], world[1], world[2], display);
    const int x = static_cast<int>(std::lround(display[0]));
    const int y = static_cast<int>(std::lround(display[1]));
    std::ostringstream log;
    log << "# StreamVersion 1.2\n";
    log << "MouseMoveEvent " << x << " " << y << " 0 0 0 0 0\n";
    log << "LeftButtonPressEvent " << x << " " << y << " 0 0 0 0 0\n";
    for (int step = 1; step <= 8; ++step)
      log << "MouseMoveEvent " << x + 10 * step << " " << y << " 0 0 0 0 0\n";
    log << "LeftButtonReleaseEvent " << x + 80 << " " << y << " 0 0 0 0 0\n";
    vtkNew<vtkInteractorEventRecorder> recorder;
    recorder->SetInteractor(this->Window->renderer()->GetRenderWindow()->GetInteractor());
    recorder->ReadFromInputStringOn();
    recorder->SetInputString(log.str().c_str());
    recorder->Play();
    recorder->Off();
    // docs/screenshots: grabbing, handles visible (scripts/screenshots picks it up).
    this->Window->saveScreenshot(this->artefact("bender-grabbing.png"));

    const bender::RibbonSpec moved = rep->GetRibbon();
    QVERIFY(bender::Distance(moved.end.position, initial.end.position) > 1.0);
    QVERIFY(session.GetLiveProblem().empty());
    // The live display follows; the committed surface has not changed yet.
    QVERIFY(MaxDifference(session.GetDisplaySurface(), this->Segmented) > 0.5);
    QCOMPARE(MaxDifference(session.GetSurface(), this->Segmented), 0.0);

    QVERIFY(this->Window->release());
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    vtkPolyData* after = session.GetSurface();
    QCOMPARE(after->GetNumberOfPoints(), this->Segmented->GetNumberOfPoints());
    const double radius = session.GetParameters().radius;
    int movedInside = 0;
    for (vtkIdType i = 0; i < after->GetNumberOfPoints(); i += 1)
    {
      double p[3], q[3];
      this->Segmented->GetPoint(i, p);
      after->GetPoint(i, q);
      const double change = std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
      if (change == 0.0)
        continue;
      // Every moved point lies inside the region of influence of the initial wire.
      QVERIFY2(
        DistanceToWire(initial, p) < radius * (1 + 1e-9), qPrintable(QString("point %1").arg(i)));
      ++movedInside;
    }
    QVERIFY(movedInside > 100);
    this->AfterFirstBend = Copy(after);
    this->Window->saveScreenshot(this->artefact("bender-after-bend.png"));
  }

  void undoRedoRestoreExactCoordinates()
  {
    bender::BenderSession& session = this->Window->session();
    // The shortcuts, as typed on the 3D view.
    this->Window->view()->setFocus();
    QTest::keyClick(this->Window->view(), Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(session.GetHistoryPosition(), std::size_t(0));
    QCOMPARE(MaxDifference(session.GetSurface(), this->Segmented), 0.0);
    QCOMPARE(MaxDifference(session.GetDisplaySurface(), this->Segmented), 0.0);
    QTest::keyClick(this->Window->view(), Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QCOMPARE(MaxDifference(session.GetSurface(), this->AfterFirstBend), 0.0);
  }

  void planSaveLoadReplayGivesTheSameSurface()
  {
    bender::BenderSession& session = this->Window->session();
    const QString plan = this->Folder.filePath("gui.bender.json");
    QVERIFY(session.SavePlan(plan.toStdString()));
    QVERIFY(session.Undo());
    QCOMPARE(MaxDifference(session.GetSurface(), this->Segmented), 0.0);
    QVERIFY(this->Window->openFile(plan));
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QVERIFY(MaxDifference(session.GetSurface(), this->AfterFirstBend) <= 1e-9);
  }

  void exportIsAcceptedByTheCheckCommand()
  {
    const QString stl = this->Folder.filePath("bent.stl");
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QVERIFY(this->Window->exportSurface(stl, false));
    QVERIFY(this->Window->waitUntilIdle(120000));
    QCOMPARE(finished.count(), 1);
    QCOMPARE(finished.first().first().toBool(), true);
    QVERIFY(QFileInfo(stl).size() > 84);
    QProcess check;
    check.start(BENDER_CLI_PATH, { "check", stl });
    QVERIFY(check.waitForFinished(120000));
    const QString output = QString::fromLocal8Bit(check.readAllStandardOutput());
    QVERIFY2(check.exitCode() == 0, qPrintable(output + check.readAllStandardError()));
    QVERIFY(output.contains("clean"));
    // The frame and unit are written into the file header.
    QFile file(stl);
    QVERIFY(file.open(QIODevice::ReadOnly));
    QVERIFY(file.read(80).contains("LPS"));
  }

  // Release, replay and export run on the worker: the window's event loop keeps turning (a
  // timer keeps firing) while they run, and their results arrive afterwards.
  void longWorkKeepsTheEventLoopTurning()
  {
    bender::BenderSession& session = this->Window->session();
    QTimer timer;
    connect(&timer, &QTimer::timeout, [this]() { ++this->Ticks; });
    timer.start(5);
    this->SlowJobs = true;
    const std::size_t position = session.GetHistoryPosition();

    // Release: grab, move the end, release.
    auto* rep = this->Window->ribbonWidget()->GetRibbonRepresentation();
    QVERIFY(this->Window->grab());
    bender::RibbonSpec moved = rep->GetRibbon();
    moved.end.position.y += 2.0;
    this->Window->setRibbon(moved);
    QVERIFY(session.GetLiveProblem().empty());
    int before = this->Ticks;
    QVERIFY(this->Window->release());
    QVERIFY(this->Window->isBusy()); // returned at once; the commit runs on the worker
    QVERIFY(this->Window->waitUntilIdle(120000));
    QVERIFY(this->Ticks - before >= 5);
    QCOMPARE(session.GetHistoryPosition(), position + 1);

    // Replay: the plan of those warps onto the surface before them.
    const QString plan = this->Folder.filePath("slow.bender.json");
    QVERIFY(session.SavePlan(plan.toStdString()));
    vtkSmartPointer<vtkPolyData> bent = Copy(session.GetSurface());
    for (std::size_t i = 0; i <= position; ++i)
      QVERIFY(session.Undo());
    before = this->Ticks;
    QVERIFY(this->Window->openFile(plan));
    QVERIFY(this->Window->isBusy());
    QVERIFY(this->Window->waitUntilIdle(120000));
    QVERIFY(this->Ticks - before >= 5);
    QCOMPARE(session.GetHistoryPosition(), position + 1);
    QVERIFY(MaxDifference(session.GetSurface(), bent) <= 1e-9);

    // Export.
    const QString vtp = this->Folder.filePath("slow.vtp");
    before = this->Ticks;
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QVERIFY(this->Window->exportSurface(vtp, true));
    QVERIFY(this->Window->isBusy());
    QVERIFY(this->Window->waitUntilIdle(120000));
    QVERIFY(this->Ticks - before >= 5);
    QCOMPARE(finished.count(), 1);
    QVERIFY(QFileInfo(vtp).size() > 0);

    this->SlowJobs = false;
    QCOMPARE(this->SlowJobsRun.load(), 3);
    QCOMPARE(this->Stalls.load(), 0);
    // Back to the state the next tests expect: one warp.
    while (session.GetHistoryPosition() > position)
      QVERIFY(session.Undo());
  }

  void screenshotIsNotBlank()
  {
    this->Window->render();
    const QString path = this->artefact("bender-window.png");
    QVERIFY(this->Window->saveScreenshot(path));
    QImage image(path);
    QVERIFY(!image.isNull());
    QVERIFY(image.width() >= 800);
    std::set<QRgb> colours;
    for (int y = 0; y < image.height(); y += 4)
      for (int x = 0; x < image.width(); x += 4)
        colours.insert(image.pixel(x, y));
    QVERIFY2(colours.size() > 200, qPrintable(QString("%1 colours").arg(colours.size())));
    // The 3D view itself shows the vessel: its reddish pixels.
    const QString viewPath = this->artefact("bender-view.png");
    QVERIFY(this->Window->saveViewScreenshot(viewPath));
    QImage view(viewPath);
    int red = 0;
    for (int y = 0; y < view.height(); y += 2)
      for (int x = 0; x < view.width(); x += 2)
      {
        const QColor c = view.pixelColor(x, y);
        red += (c.red() > 120 && c.red() > c.green() + 40) ? 1 : 0;
      }
    QVERIFY2(red > 500, qPrintable(QString("%1 vessel pixels").arg(red)));
  }

  void corruptFileDroppedGivesAMessage()
  {
    bender::BenderSession& session = this->Window->session();
    const std::size_t position = session.GetHistoryPosition();
    const QString broken = this->Folder.filePath("broken.stl");
    {
      QFile file(broken);
      QVERIFY(file.open(QIODevice::WriteOnly));
      file.write("solid x\nfacet normal 0 0 1\n outer loop\n vertex 1 2\n");
    }
    QMimeData mime;
    mime.setUrls({ QUrl::fromLocalFile(broken) });
    // As the window system delivers a drop: enter, then drop, on the window's central area.
    QWidget* target = this->Window->centralWidget();
    QDragEnterEvent enter(QPoint(100, 100), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(target, &enter);
    QVERIFY(enter.isAccepted());
    QDropEvent drop(QPointF(100, 100), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(target, &drop);
    QVERIFY(this->Window->waitUntilIdle(30000));
    QString log;
    for (const auto& message : session.GetMessages())
      log += QString::fromStdString(message.text) + "\n";
    QVERIFY2(this->Window->statusLabel()->text().contains("broken.stl"), qPrintable(log));
    QVERIFY(session.HasSurface());
    QCOMPARE(session.GetHistoryPosition(), position);

    const QString unknown = this->Folder.filePath("notes.xyz");
    QFile(unknown).open(QIODevice::WriteOnly);
    QVERIFY(!this->Window->openFile(unknown));
    QVERIFY(this->Window->statusLabel()->text().contains("unknown file type"));
    const QString badPlan = this->Folder.filePath("bad.bender.json");
    {
      QFile file(badPlan);
      QVERIFY(file.open(QIODevice::WriteOnly));
      file.write("{ not json");
    }
    QVERIFY(!this->Window->openFile(badPlan));
    QVERIFY(this->Window->statusLabel()->text().contains("bad.bender.json"));
  }

  void volumeOpensAndSegmentsFromTheSegmentPanel()
  {
    // The demo's MRA-like volume written as NRRD, opened and segmented through the panel.
    bender::DemoVessel demo = bender::SegmentDemoVessel(bender::DemoVesselPath());
    const QString nrrd = this->Folder.filePath("mra.nrrd");
    bender::WriteVolume(demo.volume, nrrd.toStdString());
    QVERIFY(this->Window->openFile(nrrd));
    QVERIFY(this->Window->waitUntilIdle(60000));
    QVERIFY(this->Window->findChild<SliceViews*>()->hasVolume());
    QVERIFY(this->Window->statusLabel()->text().contains("mra.nrrd"));
    auto* lumen = this->Window->findChild<QDoubleSpinBox*>("lumenThreshold");
    QVERIFY(lumen);
    lumen->setValue(250.0);
    auto* segment = this->Window->findChild<QAbstractButton*>("segmentButton");
    QVERIFY(segment);
    segment->click();
    QVERIFY(this->Window->waitUntilIdle(120000));
    bender::BenderSession& session = this->Window->session();
    QCOMPARE(session.GetSurfaceName(), std::string("segmented vessel"));
    // The same lumen as the demo's segmentation, within a few percent of its triangles.
    const double ratio =
      double(session.GetSurface()->GetNumberOfPolys()) / demo.surface->GetNumberOfPolys();
    QVERIFY2(ratio > 0.9 && ratio < 1.1, qPrintable(QString::number(ratio)));
  }

  void replayedTrackerRecordingGrabsBendsAndReleases()
  {
    // A tube held by the recorded hands: (-100,0,0) to (100,0,0) at rest, the right hand at
    // its open end (x = 100), so the bend turns the tube's end whole and passes the lumen
    // guard (a ribbon ending mid-tube would shear the tube beyond it: a waist the guard holds).
    const QString tube = this->Folder.filePath("tube.vtp");
    bender::WriteMesh(bendertest::Tube(-150, 100, 10, 101), tube.toStdString());
    QVERIFY(this->Window->openFile(tube));
    QVERIFY(this->Window->waitUntilIdle(30000));
    bender::BenderSession& session = this->Window->session();
    QCOMPARE(session.GetSurfaceName(), std::string("tube.vtp"));
    auto original = Copy(session.GetSurface());
    bender::WarpParameters parameters = session.GetParameters();
    // R and decay for the tube, whatever the demo before left: the end the right hand turns
    // is mid-tube, and the bell decay blends the turn into the tube beyond it.
    parameters.radius = 30;
    parameters.decay = bender::DecaySpec{};
    this->Window->bendPanel()->setParameters(parameters);
    QVERIFY(session.SetParameters(parameters));
    QVERIFY(session.GetLumenGuard().enabled);

    this->Window->trackersPanel()->setDeviceSpec(
      QString("replay:%1/tracking/two-hands.fastrak").arg(BENDER_TEST_DATA_DIR));
    this->Window->trackersPanel()->setMotionScale(1.0);
    QSignalSpy jobs(this->Window.get(), &MainWindow::workFinished);
    QVERIFY(this->Window->connectTrackers());
    bool sawGrab = false;
    QElapsedTimer timer;
    timer.start();
    while (session.GetMessages().size() > 0 && timer.elapsed() < 20000)
    {
      QTest::qWait(20);
      sawGrab |= session.GetState() == bender::GrabState::Grabbed;
      if (!this->Window->trackers().IsConnected())
        break;
    }
    QVERIFY(!this->Window->trackers().IsConnected());
    QVERIFY(sawGrab);
    // The stylus release committed through the release job on the worker (as G does), not
    // on the GUI thread inside the poll: the job ended with workFinished(true).
    QVERIFY(this->Window->waitUntilIdle(60000));
    QVERIFY(jobs.count() >= 1);
    QCOMPARE(jobs.last().first().toBool(), true);
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QVERIFY(MaxDifference(session.GetSurface(), original) > 5.0);
    // Seen from the side: the recorded hands bent the tube upwards at the right hand.
    this->Window->renderer()->GetActiveCamera()->Elevation(-75);
    this->Window->renderer()->GetActiveCamera()->OrthogonalizeViewUp();
    this->Window->renderer()->ResetCamera();
    this->Window->saveScreenshot(this->artefact("bender-tracker-bend.png"));
  }

  void placeRibbonByClickingOnTheVessel()
  {
    // Back to the straight tube; its centerline is computed in the background. P, then two
    // clicks on its wall at x = 50 and x = 90: the ribbon goes on the centerline between
    // them (along the tube's axis), R from the inscribed radius (10 mm).
    QVERIFY(this->Window->session().Undo());
    QVERIFY(this->Window->waitForCenterlines(60000));
    QVERIFY(this->Window->vessels()->vessels().HasCenterlines());
    this->Window->renderer()->GetActiveCamera()->SetPosition(70, 0, 200);
    this->Window->renderer()->GetActiveCamera()->SetFocalPoint(70, 0, 0);
    this->Window->renderer()->GetActiveCamera()->SetViewUp(0, 1, 0);
    this->Window->renderer()->ResetCameraClippingRange();
    this->Window->render();
    this->Window->view()->setFocus();
    QTest::keyClick(this->Window->view(), Qt::Key_P);
    QVERIFY(this->Window->isPlacingRibbon());
    std::ostringstream log;
    log << "# StreamVersion 1.2\n";
    for (const double at : { 50.0, 90.0 })
    {
      double display[3];
      vtkInteractorObserver::ComputeWorldToDisplay(this->Window->renderer(), at, 0, 10, display);
      const int x = static_cast<int>(std::lround(display[0]));
      const int y = static_cast<int>(std::lround(display[1]));
      log << "LeftButtonPressEvent " << x << " " << y << " 0 0 0 0 0\n";
      log << "LeftButtonReleaseEvent " << x << " " << y << " 0 0 0 0 0\n";
    }
    vtkNew<vtkInteractorEventRecorder> recorder;
    recorder->SetInteractor(this->Window->renderer()->GetRenderWindow()->GetInteractor());
    recorder->ReadFromInputStringOn();
    recorder->SetInputString(log.str().c_str());
    recorder->Play();
    recorder->Off();
    QVERIFY(!this->Window->isPlacingRibbon());
    const auto ribbon = this->Window->ribbonWidget()->GetRibbonRepresentation()->GetRibbon();
    const bender::Vec3 middle = 0.5 * (ribbon.start.position + ribbon.end.position);
    QVERIFY2(std::abs(middle.y) < 1.5 && std::abs(middle.z) < 1.5,
      qPrintable(QString("%1 %2 %3").arg(middle.x).arg(middle.y).arg(middle.z)));
    QVERIFY2(std::abs(middle.x - 70) < 3, qPrintable(QString::number(middle.x)));
    const bender::Vec3 axis = bender::Normalized(ribbon.end.position - ribbon.start.position);
    QVERIFY(std::abs(axis.x) > 0.98);
    QVERIFY(std::abs(this->Window->session().GetParameters().radius - 22.0) < 3.0);
    QVERIFY(this->Window->grab());
    this->Window->session().CancelGrab("test");
  }

  // Holding Space: the window system sends auto-repeat release/press pairs while the key is
  // down. One press grabs, the pairs change nothing, the real release commits one warp; the
  // same with a button of the panel holding the focus (Space would click it).
  void holdingSpaceWithAutoRepeatRecordsOneWarp()
  {
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.GetState() != bender::GrabState::Grabbed);
    auto* rep = this->Window->ribbonWidget()->GetRibbonRepresentation();
    const bender::RibbonSpec placed = rep->GetRibbon();
    QWidget* button = this->Window->findChild<QWidget*>("grab");
    QVERIFY(button);
    for (QWidget* focus : { static_cast<QWidget*>(this->Window->view()), button })
    {
      this->showPanel(this->Window->bendPanel());
      focus->setFocus();
      QCOMPARE(QApplication::focusWidget(), focus);
      const std::size_t position = session.GetHistoryPosition();
      const std::size_t messages = session.GetMessages().size();
      QTest::simulateEvent(focus, true, Qt::Key_Space, Qt::NoModifier, " ", false);
      QCOMPARE(session.GetState(), bender::GrabState::Grabbed);
      bender::RibbonSpec moved = placed;
      for (int repeat = 1; repeat <= 12; ++repeat)
      {
        moved.end.position.y = placed.end.position.y + 0.5 * repeat;
        this->Window->setRibbon(moved);
        QTest::simulateEvent(focus, false, Qt::Key_Space, Qt::NoModifier, " ", true);
        QTest::simulateEvent(focus, true, Qt::Key_Space, Qt::NoModifier, " ", true);
        QCOMPARE(session.GetState(), bender::GrabState::Grabbed);
        QVERIFY(!this->Window->isBusy());
      }
      QVERIFY(session.GetLiveProblem().empty());
      QTest::simulateEvent(focus, false, Qt::Key_Space, Qt::NoModifier, " ", false);
      QVERIFY(this->Window->waitUntilIdle(60000));
      QCOMPARE(session.GetHistoryPosition(), position + 1);
      QCOMPARE(session.GetState(), bender::GrabState::Released);
      QCOMPARE(session.GetPlan().warps.size(), position + 1);
      // The committed warp is the whole drag (to the last move), not a piece of it.
      QVERIFY(bender::Distance(
                session.GetPlan().warps.back().final.end.position, moved.end.position) < 1e-9);
      for (std::size_t i = messages; i < session.GetMessages().size(); ++i)
        QVERIFY2(session.GetMessages()[i].severity != bender::MessageSeverity::Error,
          session.GetMessages()[i].text.c_str());
      QVERIFY(session.Undo());
      this->Window->setRibbon(placed);
    }
  }

  // G and P are application-wide: they work from a checkbox, a button, the 3D view and a
  // floating panel, but a text field being typed in keeps its letters.
  void grabAndPlaceKeysWorkWhateverHasFocusButTextFields()
  {
    bender::BenderSession& session = this->Window->session();
    this->showPanel(this->Window->bendPanel());
    auto* subdivide = this->Window->bendPanel()->findChild<QWidget*>("subdivide");
    auto* place = this->Window->findChild<QWidget*>("placeRibbon");
    QVERIFY(subdivide && place);
    for (QWidget* focus : { subdivide, place, static_cast<QWidget*>(this->Window->view()) })
    {
      focus->setFocus();
      QCOMPARE(QApplication::focusWidget(), focus);
      QTest::keyClick(focus, Qt::Key_P);
      QVERIFY2(this->Window->isPlacingRibbon(), focus->metaObject()->className());
      QTest::keyClick(focus, Qt::Key_Escape);
      QVERIFY(!this->Window->isPlacingRibbon());
      QTest::keyClick(focus, Qt::Key_G);
      QCOMPARE(session.GetState(), bender::GrabState::Grabbed);
      QTest::keyClick(focus, Qt::Key_G); // released without moving: no warp, no longer grabbed
      QVERIFY(this->Window->waitUntilIdle(60000));
      QVERIFY(session.GetState() != bender::GrabState::Grabbed);
    }

    // Typing into the Radius field: P and G are text, not commands.
    auto* radius = this->Window->bendPanel()->findChild<QDoubleSpinBox*>("radius");
    QVERIFY(radius);
    const double r = radius->value();
    radius->setFocus();
    QCOMPARE(QApplication::focusWidget(), radius);
    QTest::keyClick(radius, Qt::Key_P);
    QTest::keyClick(radius, Qt::Key_G);
    QVERIFY(!this->Window->isPlacingRibbon());
    QVERIFY(session.GetState() != bender::GrabState::Grabbed);
    QCOMPARE(radius->value(), r);
    // And the tracker device's line edit takes the letters.
    this->showPanel(this->Window->trackersPanel());
    auto* device = this->Window->trackersPanel()->findChild<QLineEdit*>("trackerDevice");
    QVERIFY(device);
    const QString spec = device->text();
    device->setFocus();
    device->end(false);
    QTest::keyClick(device, Qt::Key_G);
    QTest::keyClick(device, Qt::Key_Space);
    QTest::keyClick(device, Qt::Key_P);
    QCOMPARE(device->text(), spec + "g p"); // Space too is the text field's
    QVERIFY(!this->Window->isPlacingRibbon());
    QVERIFY(session.GetState() != bender::GrabState::Grabbed);
    device->setText(spec);

    // A floating panel dock is a window of its own: G still grabs from there.
    auto* dock = this->Window->findChild<QDockWidget*>("panelsDock");
    QVERIFY(dock);
    this->showPanel(this->Window->bendPanel());
    dock->setFloating(true);
    QVERIFY(QTest::qWaitForWindowExposed(dock));
    dock->activateWindow();
    subdivide->setFocus();
    QTest::keyClick(subdivide, Qt::Key_G);
    QCOMPARE(session.GetState(), bender::GrabState::Grabbed);
    QTest::keyClick(subdivide, Qt::Key_Escape);
    QCOMPARE(session.GetState(), bender::GrabState::Idle);
    dock->setFloating(false);
    this->Window->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(this->Window.get()));
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("BenderAppTest");
  BenderAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "BenderAppTest.moc"
