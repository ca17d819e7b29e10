// The slice views' cursor linked to the 3D view, and the trackers' Align, on the real window
// with the demo (QTest under Xvfb, real mouse events): a click in the axial view puts the
// cursor on the point under the mouse (checked against the view's camera), the coronal and
// sagittal slices go through it and the 3D crosshair sits on it; a drag follows the mouse, a
// Shift+drag sets the window/level and leaves the cursor; a Shift+click on the surface in the
// 3D view puts the cursor on the surface point under the mouse (and a Shift+drag still pans);
// held trackers' markers drift off the ribbon's ends when a hand moves, and Align puts them
// back on the ends to 1e-6 mm without bending anything; a tracker's bend is measured live in
// the Measure panel.

#include "AppTestUtilities.h"
#include "BenderSession.h"
#include "BenderView.h"
#include "CursorOverlay.h"
#include "MainWindow.h"
#include "SimulatedDevice.h"
#include "SliceViews.h"
#include "TrackerSession.h"
#include "TrackersPanel.h"
#include "VesselController.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QApplication>
#include <QComboBox>
#include <QLabel>
#include <QMouseEvent>
#include <QPushButton>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellLocator.h>
#include <vtkCellPicker.h>
#include <vtkGenericCell.h>
#include <vtkImageData.h>
#include <vtkImageProperty.h>
#include <vtkImageSlice.h>
#include <vtkInteractorObserver.h>
#include <vtkMatrix3x3.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <atomic>
#include <cmath>
#include <memory>

namespace
{

// The Qt position of VTK display pixel (x, y) (origin bottom left) of a VTK widget.
QPoint ToWidget(QVTKOpenGLNativeWidget* widget, double x, double y)
{
  const double ratio = widget->devicePixelRatioF();
  return QPoint(static_cast<int>(std::lround(x / ratio)),
    widget->height() - 1 - static_cast<int>(std::lround(y / ratio)));
}

void Move(QWidget* widget, const QPoint& at, Qt::KeyboardModifiers modifiers)
{
  QMouseEvent move(
    QEvent::MouseMove, at, widget->mapToGlobal(at), Qt::NoButton, Qt::LeftButton, modifiers);
  QApplication::sendEvent(widget, &move);
}

// A drag with real press, move and release events.
void Drag(QWidget* widget, const QPoint& from, const QPoint& to, Qt::KeyboardModifiers modifiers)
{
  QTest::mousePress(widget, Qt::LeftButton, modifiers, from);
  for (int i = 1; i <= 4; ++i)
  {
    Move(widget, from + (to - from) * i / 4, modifiers);
    QCoreApplication::processEvents();
  }
  QTest::mouseRelease(widget, Qt::LeftButton, modifiers, to);
  QCoreApplication::processEvents();
}

double Distance(const double a[3], const double b[3])
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

double Distance(const double a[3], const bender::Vec3& b)
{
  const double c[3] = { b.x, b.y, b.z };
  return Distance(a, c);
}

// The voxel index of `p` along each axis of `image`, computed from its origin, spacing and
// direction (index = D^T (p - origin) / spacing).
void VoxelOf(vtkImageData* image, const double p[3], long ijk[3])
{
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  vtkMatrix3x3* d = image->GetDirectionMatrix();
  for (int c = 0; c < 3; ++c)
  {
    double along = 0.0;
    for (int r = 0; r < 3; ++r)
    {
      along += d->GetElement(r, c) * (p[r] - origin[r]);
    }
    ijk[c] = std::lround(along / spacing[c]);
  }
}

// Two hands held still 200 mm apart (tracker x), facing each other, the stylus up; the right
// hand displaced along x by `offset`, settable while streaming.
std::unique_ptr<bender::TrackerDevice> HeldHands(std::shared_ptr<std::atomic<double>> offset)
{
  bender::SimulatedDevice::Options options;
  options.rateHz = 100;
  options.realtime = true;
  return std::make_unique<bender::SimulatedDevice>(options,
    bender::SimulationScript(
      [offset](int station, double)
      {
        bender::TrackerPose pose;
        if (station == 2)
        {
          pose.position = { 100.0 + offset->load(), 0.0, 0.0 };
          pose.orientation = { 0.0, 0.0, 0.0, 1.0 }; // half a turn about z
        }
        else
        {
          pose.position = { -100.0, 0.0, 0.0 };
        }
        return pose;
      }));
}

}

class SliceAppTest : public QObject
{
  Q_OBJECT

  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;

  SliceViews* slices() { return this->Window->sliceViews(); }

  /// Clicks in a slice view at the projection of `target` (on its slice); returns the pixel
  /// size in mm.
  double clickAt(int view, const double target[3], Qt::KeyboardModifiers modifiers = {})
  {
    vtkRenderer* renderer = this->slices()->renderer(view);
    double display[3];
    vtkInteractorObserver::ComputeWorldToDisplay(
      renderer, target[0], target[1], target[2], display);
    QTest::mouseClick(this->slices()->viewWidget(view),
      Qt::LeftButton,
      modifiers,
      ToWidget(this->slices()->viewWidget(view), display[0], display[1]));
    QCoreApplication::processEvents();
    return 2.0 * renderer->GetActiveCamera()->GetParallelScale() / renderer->GetSize()[1];
  }

  QPoint widgetPoint(int view, const double target[3])
  {
    double display[3];
    vtkInteractorObserver::ComputeWorldToDisplay(
      this->slices()->renderer(view), target[0], target[1], target[2], display);
    return ToWidget(this->slices()->viewWidget(view), display[0], display[1]);
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*this->Window, true));
    this->Window->startDemo();
    QVERIFY(this->Window->waitUntilIdle(180000));
    QVERIFY(this->Window->session().HasSurface());
    QVERIFY(this->slices()->hasVolume());
    QTRY_VERIFY(this->slices()->isVisible());
    QVERIFY(this->slices()->cursorOverlay());
    this->Window->render();
    this->slices()->render();
    QCoreApplication::processEvents();
  }

  void cleanupTestCase()
  {
    this->Window->disconnectTrackers();
    this->Window->close();
    this->Window.reset();
  }

  void aClickInTheAxialViewMovesTheCursorAndTheOtherSlices()
  {
    SliceViews* slices = this->slices();
    double bounds[6];
    slices->volumeBounds(bounds);
    double before[3];
    slices->cursor(before);
    // The cursor starts at the volume's centre, on all three slices.
    for (int axis = 0; axis < 3; ++axis)
    {
      QVERIFY(std::abs(before[axis] - 0.5 * (bounds[2 * axis] + bounds[2 * axis + 1])) < 1e-9);
    }
    const int sagittalBefore = slices->sliceIndex(SliceViews::Sagittal);
    const int coronalBefore = slices->sliceIndex(SliceViews::Coronal);

    // A point of the axial slice, 30% across (L) and 70% down (P) the box.
    const double target[3] = { bounds[0] + 0.3 * (bounds[1] - bounds[0]),
      bounds[2] + 0.7 * (bounds[3] - bounds[2]),
      before[2] };
    const double pixel = this->clickAt(SliceViews::Axial, target);
    QVERIFY(pixel > 0 && pixel < 0.05 * (bounds[1] - bounds[0]));
    double cursor[3];
    slices->cursor(cursor);
    // The point under the mouse, to a pixel; the axial slice did not move.
    QVERIFY2(std::abs(cursor[0] - target[0]) <= pixel && std::abs(cursor[1] - target[1]) <= pixel,
      qPrintable(QString("cursor (%1, %2), expected (%3, %4) within %5 mm")
                   .arg(cursor[0])
                   .arg(cursor[1])
                   .arg(target[0])
                   .arg(target[1])
                   .arg(pixel)));
    QCOMPARE(cursor[2], before[2]);
    // The sagittal and coronal slices go through the cursor, their voxel layers followed.
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Sagittal) - cursor[0]) < 1e-9);
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Coronal) - cursor[1]) < 1e-9);
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Axial) - cursor[2]) < 1e-9);
    long ijk[3];
    VoxelOf(slices->volume(), cursor, ijk);
    vtkMatrix3x3* direction = slices->volume()->GetDirectionMatrix();
    QVERIFY(direction->IsIdentity()); // the demo volume: index axes along L, P, S
    QCOMPARE(long(slices->sliceIndex(SliceViews::Sagittal)), ijk[0]);
    QCOMPARE(long(slices->sliceIndex(SliceViews::Coronal)), ijk[1]);
    QCOMPARE(long(slices->sliceIndex(SliceViews::Axial)), ijk[2]);
    QVERIFY(slices->sliceIndex(SliceViews::Sagittal) != sagittalBefore);
    QVERIFY(slices->sliceIndex(SliceViews::Coronal) != coronalBefore);
    // Each view's crosshair: the two other slices' traces through the cursor.
    vtkPolyData* coronal = slices->crosshair(SliceViews::Coronal);
    QCOMPARE(coronal->GetNumberOfLines(), vtkIdType(2));
    double a[3], b[3];
    coronal->GetPoint(0, a); // the axial slice's trace: S fixed, along L
    coronal->GetPoint(1, b);
    QVERIFY(std::abs(a[2] - cursor[2]) < 1e-9 && std::abs(b[2] - cursor[2]) < 1e-9);
    QVERIFY(std::abs(a[0] - bounds[0]) < 1e-9 && std::abs(b[0] - bounds[1]) < 1e-9);
    coronal->GetPoint(2, a); // the sagittal slice's trace: L fixed, along S
    QVERIFY(std::abs(a[0] - cursor[0]) < 1e-9);
    // The 3D view's crosshair is on the cursor.
    CursorOverlay* overlay = slices->cursorOverlay();
    QVERIFY(overlay->isShown());
    QVERIFY(overlay->crosshairActor()->GetVisibility());
    double drawn[3];
    overlay->position(drawn);
    QCOMPARE(Distance(drawn, cursor), 0.0);
    double crossBounds[6];
    overlay->crosshairLines()->GetBounds(crossBounds);
    const double centre[3] = { 0.5 * (crossBounds[0] + crossBounds[1]),
      0.5 * (crossBounds[2] + crossBounds[3]),
      0.5 * (crossBounds[4] + crossBounds[5]) };
    QVERIFY(Distance(centre, cursor) < 1e-9);
    // The position in mm and the intensity under the cursor, in the line under the views.
    double value = 0.0;
    QVERIFY(slices->cursorValue(value));
    QCOMPARE(value,
      slices->volume()->GetScalarComponentAsDouble(int(ijk[0]), int(ijk[1]), int(ijk[2]), 0));
    const QString text = this->Window->findChild<QLabel*>("sliceCursor")->text();
    QVERIFY2(text == slices->cursorText() && text.contains(" mm: ") &&
        text.contains(
          QString("%1 %2").arg(cursor[2] >= 0 ? "S" : "I").arg(std::abs(cursor[2]), 0, 'f', 1)),
      qPrintable(text));

    // A drag follows the mouse; a Shift+drag sets the window/level and leaves the cursor.
    const double to[3] = { bounds[0] + 0.6 * (bounds[1] - bounds[0]),
      bounds[2] + 0.4 * (bounds[3] - bounds[2]),
      cursor[2] };
    QWidget* axial = slices->viewWidget(SliceViews::Axial);
    Drag(axial,
      this->widgetPoint(SliceViews::Axial, cursor),
      this->widgetPoint(SliceViews::Axial, to),
      Qt::NoModifier);
    double dragged[3];
    slices->cursor(dragged);
    QVERIFY(std::abs(dragged[0] - to[0]) <= pixel && std::abs(dragged[1] - to[1]) <= pixel);
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Sagittal) - dragged[0]) < 1e-9);
    const double window = slices->slice(SliceViews::Axial)->GetProperty()->GetColorWindow();
    const QPoint from = this->widgetPoint(SliceViews::Axial, dragged);
    Drag(axial, from, from + QPoint(60, 0), Qt::ShiftModifier);
    double after[3];
    slices->cursor(after);
    QCOMPARE(Distance(after, dragged), 0.0);
    QVERIFY(slices->slice(SliceViews::Axial)->GetProperty()->GetColorWindow() != window);

    // Panned and zoomed away, R frames the axial view again, its slice still at the cursor.
    vtkCamera* camera = slices->renderer(SliceViews::Axial)->GetActiveCamera();
    const double scale = camera->GetParallelScale();
    camera->SetParallelScale(0.3 * scale);
    double focal[3], eye[3];
    camera->GetFocalPoint(focal);
    camera->GetPosition(eye);
    camera->SetFocalPoint(focal[0] + 7, focal[1] - 5, focal[2]);
    camera->SetPosition(eye[0] + 7, eye[1] - 5, eye[2]);
    axial->setFocus();
    QTest::keyClick(axial, Qt::Key_R);
    QCoreApplication::processEvents();
    camera->GetFocalPoint(focal);
    QVERIFY(std::abs(focal[0] - 0.5 * (bounds[0] + bounds[1])) < 1e-9);
    QVERIFY(std::abs(focal[1] - 0.5 * (bounds[2] + bounds[3])) < 1e-9);
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Axial) - after[2]) < 1e-9);
    QVERIFY(std::abs(camera->GetParallelScale() - scale) < 1e-9 * scale);
  }

  void aShiftClickOnTheSurfaceMovesTheCursorThere()
  {
    auto* view = static_cast<BenderView*>(this->Window->view());
    vtkRenderer* renderer = this->Window->renderer();
    this->Window->render();
    QCoreApplication::processEvents();
    // A pixel on the surface, found by the test's own picker, scanning from the centre.
    const int* size = renderer->GetSize();
    vtkNew<vtkCellPicker> picker;
    picker->SetTolerance(0.002);
    picker->PickFromListOn();
    picker->AddPickList(view->surfaceActor());
    int hit[2] = { -1, -1 };
    for (int r = 0; r < size[0] / 2 && hit[0] < 0; r += 8)
    {
      for (const int dx : { 0, r, -r })
      {
        const int x = size[0] / 2 + dx, y = size[1] / 2 + r / 3;
        if (picker->Pick(x, y, 0, renderer))
        {
          hit[0] = x;
          hit[1] = y;
          break;
        }
      }
    }
    QVERIFY(hit[0] >= 0);
    double expected[3];
    picker->GetPickPosition(expected);
    double cameraBefore[3];
    renderer->GetActiveCamera()->GetPosition(cameraBefore);
    const std::size_t history = this->Window->session().GetHistoryPosition();

    QTest::mouseClick(view, Qt::LeftButton, Qt::ShiftModifier, ToWidget(view, hit[0], hit[1]));
    QCoreApplication::processEvents();
    SliceViews* slices = this->slices();
    double cursor[3];
    slices->cursor(cursor);
    QVERIFY2(Distance(cursor, expected) < 1e-9,
      qPrintable(QString("cursor (%1, %2, %3), picked (%4, %5, %6)")
                   .arg(cursor[0])
                   .arg(cursor[1])
                   .arg(cursor[2])
                   .arg(expected[0])
                   .arg(expected[1])
                   .arg(expected[2])));
    // Independently: the cursor lies on the surface and under the mouse.
    vtkNew<vtkCellLocator> locator;
    locator->SetDataSet(this->Window->session().GetDisplaySurface());
    locator->BuildLocator();
    double closest[3], distance2 = 0.0;
    vtkIdType cell = -1;
    int sub = 0;
    locator->FindClosestPoint(cursor, closest, cell, sub, distance2);
    QVERIFY2(std::sqrt(distance2) < 1e-2, qPrintable(QString::number(std::sqrt(distance2))));
    double display[3];
    vtkInteractorObserver::ComputeWorldToDisplay(
      renderer, cursor[0], cursor[1], cursor[2], display);
    QVERIFY(std::abs(display[0] - hit[0]) < 1.5 && std::abs(display[1] - hit[1]) < 1.5);
    // The slices followed, the 3D crosshair is there; the camera and the surface did not move.
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Axial) - cursor[2]) < 1e-9);
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Coronal) - cursor[1]) < 1e-9);
    QVERIFY(std::abs(slices->slicePosition(SliceViews::Sagittal) - cursor[0]) < 1e-9);
    double drawn[3];
    slices->cursorOverlay()->position(drawn);
    QCOMPARE(Distance(drawn, cursor), 0.0);
    double cameraAfter[3];
    renderer->GetActiveCamera()->GetPosition(cameraAfter);
    QCOMPARE(Distance(cameraAfter, cameraBefore), 0.0);
    QVERIFY(this->Window->session().GetState() != bender::GrabState::Grabbed);
    QCOMPARE(this->Window->session().GetHistoryPosition(), history);

    // A Shift+drag is still the camera's pan: the cursor stays.
    const QPoint at = ToWidget(view, hit[0], hit[1]);
    Drag(view, at, at + QPoint(50, 20), Qt::ShiftModifier);
    double after[3];
    slices->cursor(after);
    QCOMPARE(Distance(after, cursor), 0.0);
    renderer->GetActiveCamera()->GetPosition(cameraAfter);
    QVERIFY(Distance(cameraAfter, cameraBefore) > 1e-6);

    // The planes' outlines on demand, through the cursor.
    auto* style = this->Window->findChild<QComboBox*>("sliceCursorStyle");
    QVERIFY(style);
    style->setCurrentIndex(CursorOverlay::CrosshairAndPlanes);
    QVERIFY(slices->cursorOverlay()->planesActor()->GetVisibility());
    QCOMPARE(slices->cursorOverlay()->planeOutlines()->GetNumberOfLines(), vtkIdType(3));
    double p[3];
    slices->cursorOverlay()->planeOutlines()->GetPoint(0, p); // the axial plane's corner
    QVERIFY(std::abs(p[2] - cursor[2]) < 1e-9);
    view->resetCamera();
    this->Window->render();
    QVERIFY(this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/slices-crosshair.png"));
    style->setCurrentIndex(CursorOverlay::Hidden);
    QVERIFY(!slices->cursorOverlay()->crosshairActor()->GetVisibility());
    style->setCurrentIndex(CursorOverlay::Crosshair);
    QVERIFY(slices->cursorOverlay()->crosshairActor()->GetVisibility());
  }

  void alignPutsTheHandMarkersOnTheRibbonEnds()
  {
    bender::BenderSession& session = this->Window->session();
    TrackersPanel* panel = this->Window->trackersPanel();
    this->Window->findChild<QTabWidget*>("panels")->setCurrentWidget(panel);
    QPushButton* align = panel->alignButton();
    QVERIFY(!align->isEnabled());
    QVERIFY2(align->toolTip().startsWith("Connect a tracker first"), qPrintable(align->toolTip()));
    QVERIFY(session.GetRibbon().has_value());
    const bender::RibbonSpec placed = *session.GetRibbon();
    vtkNew<vtkPolyData> before;
    before->DeepCopy(session.GetDisplaySurface());
    const std::size_t history = session.GetHistoryPosition();

    // The screenshots look at the ribbon from closer.
    vtkCamera* camera = this->Window->renderer()->GetActiveCamera();
    const bender::Vec3 middle = (placed.start.position + placed.end.position) * 0.5;
    double focal[3], eye[3];
    camera->GetFocalPoint(focal);
    camera->GetPosition(eye);
    camera->SetFocalPoint(middle.x, middle.y, middle.z);
    camera->SetPosition(
      eye[0] - focal[0] + middle.x, eye[1] - focal[1] + middle.y, eye[2] - focal[2] + middle.z);
    camera->Zoom(2.5);
    this->Window->render();

    auto offset = std::make_shared<std::atomic<double>>(0.0);
    QVERIFY(panel->connectWith(HeldHands(offset)));
    QVERIFY(align->isEnabled());
    QVERIFY(!align->toolTip().startsWith("Connect a tracker first"));
    // Anchored on connect: the markers sit on the ribbon's ends.
    QTRY_VERIFY(panel->handMarkersShown());
    double left[3], right[3];
    QTRY_VERIFY(panel->handMarkerPosition(0, left) && panel->handMarkerPosition(1, right) &&
      Distance(left, placed.start.position) < 1e-6 && Distance(right, placed.end.position) < 1e-6);
    // The right hand moves 40 mm with the stylus up: its marker drifts off the end by the
    // scaled displacement, the ribbon stays.
    offset->store(40.0);
    QTRY_VERIFY(panel->handMarkerPosition(1, right) && Distance(right, placed.end.position) > 1.0);
    const double length = bender::Distance(placed.start.position, placed.end.position);
    QTRY_VERIFY(panel->handMarkerPosition(1, right) &&
      std::abs(Distance(right, placed.end.position) - 40.0 * length / 200.0) < 1e-6);
    QVERIFY(panel->handMarkerPosition(0, left) && Distance(left, placed.start.position) < 1e-6);
    const bender::RibbonSpec shown =
      this->Window->ribbonWidget()->GetRibbonRepresentation()->GetRibbon();
    QVERIFY(bender::Distance(shown.end.position, placed.end.position) < 1e-9);
    QVERIFY(this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/trackers-drifted.png"));

    // Align: the markers jump onto the ends; the status bar says so; nothing is bent.
    QTest::mouseClick(align, Qt::LeftButton);
    QVERIFY(panel->handMarkerPosition(0, left) && panel->handMarkerPosition(1, right));
    QVERIFY2(Distance(left, placed.start.position) < 1e-6,
      qPrintable(QString::number(Distance(left, placed.start.position))));
    QVERIFY2(Distance(right, placed.end.position) < 1e-6,
      qPrintable(QString::number(Distance(right, placed.end.position))));
    const QString status = this->Window->statusLabel()->toolTip();
    QVERIFY2(status.startsWith("Hands aligned") && status.contains("nothing was bent"),
      qPrintable(status));
    // Still there after more polls (the hands are still), and the surface is untouched.
    for (int i = 0; i < 10; ++i)
    {
      QTest::qWait(20);
    }
    QVERIFY(panel->handMarkerPosition(0, left) && panel->handMarkerPosition(1, right));
    QVERIFY(Distance(left, placed.start.position) < 1e-6);
    QVERIFY(Distance(right, placed.end.position) < 1e-6);
    QCOMPARE(session.GetHistoryPosition(), history);
    QVERIFY(session.GetState() != bender::GrabState::Grabbed);
    vtkPolyData* now = session.GetDisplaySurface();
    QCOMPARE(now->GetNumberOfPoints(), before->GetNumberOfPoints());
    double largest = 0.0;
    for (vtkIdType i = 0; i < now->GetNumberOfPoints(); ++i)
    {
      double p[3], q[3];
      now->GetPoint(i, p);
      before->GetPoint(i, q);
      largest = std::max(largest, Distance(p, q));
    }
    QCOMPARE(largest, 0.0);
    QVERIFY(this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/trackers-aligned.png"));

    // Disconnected: the markers go, Align is disabled and says why.
    this->Window->disconnectTrackers();
    QVERIFY(!panel->handMarkersShown());
    QVERIFY(!align->isEnabled());
    QVERIFY(align->toolTip().startsWith("Connect a tracker first"));
  }

  void aTrackerBendIsMeasuredLive()
  {
    // The simulator grabs at 1 s and arches the ribbon until 4 s; its stream ends at 4.5 s,
    // mid-grab (the bend is cancelled, nothing committed). Meanwhile the Measure panel's live
    // column follows the tracker as it follows the mouse.
    QVERIFY(this->Window->waitForCenterlines(120000));
    bender::BenderSession& session = this->Window->session();
    const std::size_t history = session.GetHistoryPosition();
    TrackersPanel* panel = this->Window->trackersPanel();
    QSignalSpy grabbed(panel, &TrackersPanel::trackerGrabbed);
    QSignalSpy moved(panel, &TrackersPanel::trackerMoved);
    bender::SimulatedDevice::Options options;
    options.rateHz = 60;
    options.realtime = true;
    options.duration = 4.5;
    QVERIFY(panel->connectWith(std::make_unique<bender::SimulatedDevice>(options)));
    QTRY_VERIFY_WITH_TIMEOUT(grabbed.count() == 1, 15000);
    VesselController* vessels = this->Window->vessels();
    QVERIFY(vessels->heldBefore().valid);
    const double angle = vessels->heldBefore().bendAngle;
    QTRY_VERIFY_WITH_TIMEOUT(moved.count() > 5 && vessels->heldNow().valid &&
        std::abs(vessels->heldNow().bendAngle - angle) > 5.0,
      15000);
    QTRY_VERIFY_WITH_TIMEOUT(!this->Window->trackers().IsConnected(), 15000);
    QCOMPARE(grabbed.count(), 1);
    QTRY_VERIFY(session.GetState() != bender::GrabState::Grabbed);
    QCOMPARE(session.GetHistoryPosition(), history);
  }
};

QTEST_MAIN(SliceAppTest)
#include "SliceAppTest.moc"
