// Interactive on big meshes (issue 12): in the real window, a surface above the level-of-detail
// threshold is dragged as its decimated copy (the view draws the warped copy, the whole surface
// is neither drawn nor warped meanwhile), and the release draws the whole, exactly committed
// surface; a surface below the threshold is always drawn whole. The threshold is lowered so
// that a 51k-triangle tube counts as big. Real mouse events drag the end handle.
// Under Xvfb (QT_QPA_PLATFORM=xcb).
#include "AppTestUtilities.h"
#include "ApplyPlan.h"
#include "BendPanel.h"
#include "BenderSession.h"
#include "BenderView.h"
#include "MainActions.h"
#include "MainWindow.h"
#include "MeshIO.h"
#include "Ribbon.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAction>
#include <QApplication>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkActor.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkInteractorObserver.h>
#include <vtkMapper.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <cmath>
#include <memory>
#include <sstream>

namespace
{
// The largest coordinate difference between two surfaces of the same points (inf otherwise).
double MaxDifference(vtkPolyData* a, vtkPolyData* b)
{
  if (!a || !b || a->GetNumberOfPoints() != b->GetNumberOfPoints())
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

vtkSmartPointer<vtkPolyData> Copy(vtkPolyData* surface)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(surface);
  return copy;
}
} // namespace

class LodAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  vtkSmartPointer<vtkPolyData> Tube;

  BenderView* view() { return this->Window->benderView(); }
  vtkRenderWindowInteractor* interactor()
  {
    return this->Window->renderer()->GetRenderWindow()->GetInteractor();
  }

  /// A straight ribbon along the tube's axis to its open end, its handles sized for the tube.
  void placeRibbon()
  {
    bender::RibbonSpec ribbon;
    ribbon.start.position = { -12, 0, 0 };
    ribbon.start.tangent = { 1, 0, 0 };
    ribbon.start.normal = { 0, 0, 1 };
    ribbon.end.position = { 40, 0, 0 };
    ribbon.end.tangent = { 1, 0, 0 };
    ribbon.end.normal = { 0, 0, 1 };
    auto* rep = this->Window->ribbonWidget()->GetRibbonRepresentation();
    rep->SetHandleLength(6.0);
    rep->SetHandleRadius(1.1);
    rep->SetStripWidth(1.5);
    this->Window->setRibbon(ribbon);
    this->Window->ribbonWidget()->On();
    this->Window->render();
  }

  /// Plays real mouse events on the interactor: a press on the end handle and `steps` moves
  /// of 8 pixels upwards; the button is let go only with `release`.
  void dragEndHandle(int steps, bool release)
  {
    auto* rep = this->Window->ribbonWidget()->GetRibbonRepresentation();
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
    for (int step = 1; step <= steps; ++step)
      log << "MouseMoveEvent " << x << " " << y + 8 * step << " 0 0 0 0 0\n";
    if (release)
      log << "LeftButtonReleaseEvent " << x << " " << y + 8 * steps << " 0 0 0 0 0\n";
    vtkNew<vtkInteractorEventRecorder> recorder;
    recorder->SetInteractor(this->interactor());
    recorder->ReadFromInputStringOn();
    recorder->SetInputString(log.str().c_str());
    recorder->Play();
    recorder->Off();
  }

  void letGo()
  {
    int x = 0, y = 0;
    this->interactor()->GetEventPosition(x, y);
    this->interactor()->SetEventInformation(x, y);
    this->interactor()->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*this->Window, true));
    // The lumen guard on: the ribbon runs to the tube's open end (placeRibbon), so the drags
    // below move the tube's end whole (a ribbon ending mid-tube would shear the tube beyond
    // it: a waist the guard holds).
    QVERIFY(this->Window->session().GetLumenGuard().enabled);
    // 401 rings of 64 points: 51k triangles, radius 5, along x from -40 to 40.
    this->Tube = bendertest::Tube(-40, 40, 5, 401, 64);
    const QString path = this->Folder.filePath("tube.vtp");
    bender::WriteMesh(this->Tube, path.toStdString());
    QVERIFY(this->Window->openFile(path));
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(
      this->Window->session().GetSurface()->GetNumberOfPoints(), this->Tube->GetNumberOfPoints());
  }

  void cleanupTestCase()
  {
    this->Window->close();
    this->Window.reset();
  }

  void bigSurfaceIsDraggedAsItsCopyAndReleasedWhole()
  {
    bender::BenderSession& session = this->Window->session();
    session.SetLevelOfDetailThreshold(20000);
    this->view()->setLevelOfDetailThreshold(20000);
    this->placeRibbon();
    const vtkSmartPointer<vtkPolyData> before = Copy(session.GetSurface());
    const long long bindingsBefore = session.GetLiveFilter()->GetBindingCount();

    QVERIFY(this->Window->grab());
    QVERIFY(session.IsDraggingProxy());
    this->dragEndHandle(6, false);
    this->Window->render();
    // Mid-drag: the view draws the warped copy, not the surface.
    QVERIFY(this->view()->isShowingProxy());
    QVERIFY(!this->view()->surfaceActor()->GetVisibility());
    vtkPolyData* drawn = this->view()->levelOfDetailProxy();
    QVERIFY(drawn);
    QVERIFY(drawn->GetNumberOfPolys() > 500);
    QVERIFY(drawn->GetNumberOfPoints() < this->Tube->GetNumberOfPoints() / 2);
    // The copy moved with the handle: some of its points left the tube's wall (radius 5).
    double farthest = 0.0;
    for (vtkIdType i = 0; i < drawn->GetNumberOfPoints(); ++i)
    {
      double p[3];
      drawn->GetPoint(i, p);
      farthest = std::max(farthest, std::abs(std::hypot(p[1], p[2]) - 5.0));
    }
    QVERIFY2(farthest > 2.0, qPrintable(QString("farthest %1").arg(farthest)));
    this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/lod-during-drag.png");
    // The whole surface was neither drawn nor warped during the drag.
    QCOMPARE(session.GetLiveFilter()->GetBindingCount(), bindingsBefore);
    QCOMPARE(MaxDifference(session.GetSurface(), before), 0.0);
    this->letGo();
    QVERIFY(this->view()->isShowingProxy()); // still grabbed (G releases)

    QVERIFY(this->Window->release());
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    this->Window->render();
    // After the release: the whole committed surface is drawn.
    QVERIFY(!session.IsDraggingProxy());
    QVERIFY(!this->view()->isShowingProxy());
    QVERIFY(this->view()->surfaceActor()->GetVisibility());
    auto* shown = vtkPolyData::SafeDownCast(this->view()->surfaceActor()->GetMapper()->GetInput());
    QVERIFY(shown);
    QCOMPARE(shown->GetNumberOfPoints(), this->Tube->GetNumberOfPoints());
    QCOMPARE(MaxDifference(shown, session.GetSurface()), 0.0);
    // The commit is the exact warp of the whole surface (the plan's warp replayed on the tube).
    vtkSmartPointer<vtkPolyData> replayed =
      bender::ApplyWarp(this->Tube, session.GetPlan().warps[0]);
    QVERIFY(MaxDifference(session.GetSurface(), replayed) <= 1e-9);
    QVERIFY(MaxDifference(session.GetSurface(), before) > 2.0);
    this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/lod-after-release.png");
  }

  void smallSurfaceIsAlwaysDrawnWhole()
  {
    bender::BenderSession& session = this->Window->session();
    session.SetLevelOfDetailThreshold(500000);
    this->view()->setLevelOfDetailThreshold(500000);
    // The straight tube again.
    this->Window->actions()->Undo->trigger();
    QCOMPARE(session.GetHistoryPosition(), std::size_t(0));
    this->placeRibbon();
    QVERIFY(this->Window->grab());
    QVERIFY(!session.IsDraggingProxy());
    this->dragEndHandle(4, true);
    this->Window->render();
    QVERIFY(!this->view()->isShowingProxy());
    QVERIFY(this->view()->surfaceActor()->GetVisibility());
    QVERIFY(MaxDifference(session.GetDisplaySurface(), session.GetSurface()) > 1.0);
    QVERIFY(this->Window->release());
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QVERIFY(!this->view()->isShowingProxy());
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("LodAppTest");
  LodAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "LodAppTest.moc"
