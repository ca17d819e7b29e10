// The view explains itself (issue 12): handles that say what they are and stay visible through
// the vessel, the orientation marker, the scale bar, the standard views and Reset camera, the
// camera reframed for a mesh of another size (the bunny after the demo), slice views that fit
// a head MRI with their position and letters, the intensity histogram and the warning for a
// tiny segmentation, the ghost of the original shape, the level of detail while rotating, the
// status text cut with a tooltip, and Help's shortcut list. The real window under Xvfb
// (QT_QPA_PLATFORM=xcb).
#include "AppTestUtilities.h"
#include "BenderView.h"
#include "ElidedLabel.h"
#include "HistogramWidget.h"
#include "MainActions.h"
#include "MainWindow.h"
#include "SegmentPanel.h"
#include "SliceViews.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAction>
#include <QApplication>
#include <QDialog>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkActor.h>
#include <vtkAnnotatedCubeActor.h>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkImageSlice.h>
#include <vtkInteractorObserver.h>
#include <vtkMapper.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkPolyData.h>
#include <vtkPropCollection.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkTextActor.h>
#include <vtkWindowToImageFilter.h>

#include <array>
#include <cmath>

using Rep = vtkBenderRibbonRepresentation;

namespace
{
double Dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void Display(vtkRenderer* renderer, const double world[3], double display[3])
{
  vtkInteractorObserver::ComputeWorldToDisplay(renderer, world[0], world[1], world[2], display);
}
} // namespace

class ViewAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;

  BenderView* view() { return this->Window->benderView(); }

  /// The fraction of the 3D view's width and height that the surface's bounds cover, and
  /// whether all their corners project inside the view.
  bool surfaceInView(double& widthShare, double& heightShare)
  {
    this->Window->render();
    double bounds[6];
    this->Window->session().GetDisplaySurface()->GetBounds(bounds);
    vtkRenderer* renderer = this->Window->renderer();
    const int* size = renderer->GetSize();
    double low[2] = { 1e300, 1e300 }, high[2] = { -1e300, -1e300 };
    bool inside = true;
    for (int corner = 0; corner < 8; ++corner)
    {
      const double p[3] = {
        bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)], bounds[4 + ((corner >> 2) & 1)]
      };
      double d[3];
      Display(renderer, p, d);
      for (int c = 0; c < 2; ++c)
      {
        low[c] = std::min(low[c], d[c]);
        high[c] = std::max(high[c], d[c]);
        inside = inside && d[c] >= -1 && d[c] <= size[c] + 1;
      }
    }
    widthShare = (high[0] - low[0]) / size[0];
    heightShare = (high[1] - low[1]) / size[1];
    return inside;
  }

  void sendMouseMove(const QPoint& at)
  {
    QMouseEvent move(QEvent::MouseMove, at, Qt::NoButton, Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(this->Window->view(), &move);
    QCoreApplication::processEvents();
  }

  QPoint widgetPoint(const double display[3])
  {
    const double ratio = this->Window->view()->devicePixelRatioF();
    return QPoint(static_cast<int>(std::lround(display[0] / ratio)),
      this->Window->view()->height() - 1 - static_cast<int>(std::lround(display[1] / ratio)));
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*this->Window, true));
  }

  void cleanupTestCase()
  {
    this->Window->close();
    this->Window.reset();
  }

  void helpListsEveryShortcutAndActionsExplainThemselves()
  {
    MainActions* actions = this->Window->actions();
    const QList<QStringList> rows = actions->shortcutRows();
    // Every action of the window with a shortcut is listed, with its key.
    int withShortcut = 0;
    for (QAction* action : this->Window->findChildren<QAction*>())
    {
      if (action->shortcut().isEmpty())
        continue;
      ++withShortcut;
      const QString key = action->shortcut().toString(QKeySequence::NativeText);
      bool listed = false;
      for (const QStringList& row : rows)
        listed = listed || row.value(0) == key;
      QVERIFY2(listed, qPrintable(key));
    }
    QVERIFY(withShortcut >= 20);
    QVERIFY(rows.size() >= withShortcut);
    // Every command in the menus says more than its name.
    for (QMenu* menu : this->Window->menuBar()->findChildren<QMenu*>())
    {
      for (QAction* action : menu->actions())
      {
        if (action->isSeparator() || action->menu() || action->objectName().isEmpty())
          continue;
        QVERIFY2(action->toolTip().remove('&') != action->text().remove('&'),
          qPrintable(action->objectName()));
      }
    }
    // F1 opens the table.
    actions->Shortcuts->trigger();
    QCoreApplication::processEvents();
    auto* dialog = this->Window->findChild<QDialog*>("shortcutsDialog");
    QVERIFY(dialog && dialog->isVisible());
    auto* table = dialog->findChild<QTableWidget*>("shortcutsTable");
    QVERIFY(table);
    QCOMPARE(table->rowCount(), rows.size());
    bool reset = false;
    for (int r = 0; r < table->rowCount(); ++r)
      reset = reset ||
        (table->item(r, 0)->text() == "Ctrl+R" &&
          table->item(r, 1)->text().contains("Reset camera"));
    QVERIFY(reset);
    dialog->close();
    QCoreApplication::processEvents();
  }

  void longStatusTextIsCutWithATooltip()
  {
    const int width = this->Window->width();
    const QString text =
      QString("A long message about ") + QString("the vessel ").repeated(60) + "end";
    this->Window->session().AddMessage(bender::MessageSeverity::Warning, text.toStdString());
    QCoreApplication::processEvents();
    auto* label = qobject_cast<ElidedLabel*>(this->Window->statusLabel());
    QVERIFY(label);
    QCOMPARE(this->Window->width(), width);
    QCOMPARE(label->text(), text);
    QVERIFY(label->isElided());
    QVERIFY(label->shownText().endsWith(QChar(0x2026)));
    QVERIFY(label->fontMetrics().horizontalAdvance(label->shownText()) <= label->width());
    QCOMPARE(label->toolTip(), text);
  }

  void headMriSlicesFitAndTheHistogramWarnsOfATinySegmentation()
  {
    QVERIFY(this->Window->openFile(QString(BENDER_EXTERNAL_DATA_DIR) + "/ch2.nii.gz"));
    QVERIFY(this->Window->waitUntilIdle(120000));
    const auto& volume = this->Window->segmentation().GetVolume();
    QVERIFY(volume);
    SliceViews* slices = this->Window->sliceViews();
    QVERIFY(slices->isVisible());
    QCoreApplication::processEvents();
    slices->render();

    // Each view shows the whole section of the volume, centred, not a corner, not black.
    double bounds[6];
    slices->volumeBounds(bounds);
    const char* letters[3][4] = {
      { "A", "P", "R", "L" }, { "S", "I", "R", "L" }, { "S", "I", "A", "P" }
    };
    for (int v = 0; v < 3; ++v)
    {
      vtkRenderer* renderer = slices->renderer(v);
      const int* size = renderer->GetSize();
      double low[2] = { 1e300, 1e300 }, high[2] = { -1e300, -1e300 };
      for (int corner = 0; corner < 8; ++corner)
      {
        const double p[3] = {
          bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)], bounds[4 + ((corner >> 2) & 1)]
        };
        double d[3];
        Display(renderer, p, d);
        for (int c = 0; c < 2; ++c)
        {
          low[c] = std::min(low[c], d[c]);
          high[c] = std::max(high[c], d[c]);
        }
      }
      QVERIFY2(low[0] >= -1 && low[1] >= -1 && high[0] <= size[0] + 1 && high[1] <= size[1] + 1,
        qPrintable(QString("view %1 cut").arg(v)));
      QVERIFY(std::max((high[0] - low[0]) / size[0], (high[1] - low[1]) / size[1]) > 0.9);
      QVERIFY(std::abs(0.5 * (low[0] + high[0]) - 0.5 * size[0]) < 2.0);
      QVERIFY(std::abs(0.5 * (low[1] + high[1]) - 0.5 * size[1]) < 2.0);
      // The image is drawn where the volume is: the middle of the view is not background.
      vtkNew<vtkWindowToImageFilter> grab;
      grab->SetInput(renderer->GetRenderWindow());
      grab->ReadFrontBufferOff();
      grab->Update();
      int lit = 0, total = 0;
      vtkImageData* image = grab->GetOutput();
      for (int y = size[1] / 3; y < 2 * size[1] / 3; y += 2)
        for (int x = size[0] / 3; x < 2 * size[0] / 3; x += 2)
        {
          const auto* p = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
          lit += (p[0] + p[1] + p[2] > 60) ? 1 : 0;
          ++total;
        }
      QVERIFY2(
        lit > total / 3, qPrintable(QString("view %1: %2 of %3 lit").arg(v).arg(lit).arg(total)));
      const QStringList edges = slices->edgeLetters(v);
      for (int e = 0; e < 4; ++e)
        QCOMPARE(edges.value(e), QString(letters[v][e]));
      // The slice position in mm, with its letter, follows the wheel.
      const double before = slices->slicePosition(v);
      slices->moveSlice(v, 3);
      const double after = slices->slicePosition(v);
      QVERIFY(std::abs(std::abs(after - before) - 3.0) < 0.01);
      const QString text = slices->positionText(v);
      QVERIFY2(text.endsWith(QString(" %1 mm").arg(std::abs(after), 0, 'f', 1)), qPrintable(text));
    }
    QCOMPARE(slices->positionText(SliceViews::Axial).left(1),
      QString(slices->slicePosition(SliceViews::Axial) >= 0 ? "S" : "I"));

    // The histogram counts every voxel; the head MRI is 8-bit.
    SegmentPanel* panel = this->Window->segmentPanel();
    HistogramWidget* histogram = panel->histogram();
    std::size_t sum = 0;
    for (std::size_t c : histogram->counts())
      sum += c;
    QCOMPARE(sum, volume->voxels.size());
    QCOMPARE(histogram->total(), volume->voxels.size());
    QVERIFY(panel->isEightBit());
    QVERIFY(histogram->maximum() <= 255.0);

    // Threshold 250 keeps almost nothing: the segmentation is done, and a warning says so.
    auto* threshold = panel->findChild<QDoubleSpinBox*>("lumenThreshold");
    threshold->setValue(250.0);
    QVERIFY(this->Window->segmentVolume());
    QVERIFY(this->Window->waitUntilIdle(180000));
    QCoreApplication::processEvents();
    // The Segment panel comes back, with the warning under the histogram.
    QVERIFY2(panel->warningLabel()->isVisible(), qPrintable(this->Window->statusLabel()->text()));
    const QString warning = panel->warningLabel()->text();
    QVERIFY2(warning.contains("threshold 250 on an 8-bit volume kept"), qPrintable(warning));
    // The window's advice: its histogram (the command line's is its --lower).
    QVERIFY2(warning.contains("lower threshold on the histogram"), qPrintable(warning));
    QVERIFY2(this->Window->statusLabel()->text().contains("too little for a vessel"),
      qPrintable(this->Window->statusLabel()->text()));
    this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/view-head-mri.png");
  }

  void demoHandlesSayWhatTheyAreAndShowThroughTheVessel()
  {
    this->Window->startDemo();
    QVERIFY(this->Window->waitUntilIdle(180000));
    QVERIFY(this->Window->ribbonWidget()->GetEnabled());
    // The ribbon is drawn in the layer above the surface, with the same camera.
    vtkRenderer* ribbonLayer = this->view()->ribbonRenderer();
    QVERIFY(ribbonLayer->GetLayer() > this->Window->renderer()->GetLayer());
    QCOMPARE(ribbonLayer->GetActiveCamera(), this->Window->renderer()->GetActiveCamera());
    auto* rep = this->Window->ribbonWidget()->GetRibbonRepresentation();
    QVERIFY(ribbonLayer->GetViewProps()->IsItemPresent(rep));
    QVERIFY(!this->Window->renderer()->GetViewProps()->IsItemPresent(rep));
    double end[3], tangent[3], twist[3];
    rep->GetHandleActor(Rep::EndPosition)->GetProperty()->GetColor(end);
    rep->GetHandleActor(Rep::EndTangent)->GetProperty()->GetColor(tangent);
    rep->GetHandleActor(Rep::EndNormal)->GetProperty()->GetColor(twist);
    QVERIFY(end[2] > end[0] + 0.5);                                  // blue
    QVERIFY(tangent[1] > tangent[0] + 0.5);                          // green
    QVERIFY(twist[0] > twist[1] + 0.4 && twist[2] > twist[1] + 0.4); // magenta

    // The end handle lies on the vessel's axis, inside the wall: its pixel is still blue.
    this->view()->resetCamera();
    double world[3], display[3];
    rep->GetHandlePosition(Rep::EndPosition, world);
    Display(this->Window->renderer(), world, display);
    const QImage image = this->Window->view()->grabFramebuffer();
    const QColor pixel = image.pixelColor(static_cast<int>(std::lround(display[0])),
      image.height() - 1 - static_cast<int>(std::lround(display[1])));
    QVERIFY2(pixel.blue() > pixel.red() + 40,
      qPrintable(QString("%1 %2 %3").arg(pixel.red()).arg(pixel.green()).arg(pixel.blue())));

    // Hovering a handle names it.
    this->sendMouseMove(this->widgetPoint(display));
    QCOMPARE(QString(rep->GetHoverText()), QString("end: drag to move"));
    double tip[3];
    rep->GetHandlePosition(Rep::EndTangent, tip);
    Display(this->Window->renderer(), tip, display);
    this->sendMouseMove(this->widgetPoint(display));
    QCOMPARE(QString(rep->GetHoverText()), QString("tangent: drag to bend"));
    this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/view-handles.png");
    this->sendMouseMove(QPoint(3, 3));
    QCOMPARE(QString(rep->GetHoverText()), QString());
  }

  void orientationMarkerFollowsTheCamera()
  {
    vtkAnnotatedCubeActor* cube = this->view()->orientationCube();
    QCOMPARE(QString(cube->GetXPlusFaceText()), QString("L"));
    QCOMPARE(QString(cube->GetXMinusFaceText()), QString("R"));
    QCOMPARE(QString(cube->GetYPlusFaceText()), QString("P"));
    QCOMPARE(QString(cube->GetYMinusFaceText()), QString("A"));
    QCOMPARE(QString(cube->GetZPlusFaceText()), QString("S"));
    QCOMPARE(QString(cube->GetZMinusFaceText()), QString("I"));
    QVERIFY(this->view()->orientationMarker()->GetEnabled());
    vtkRenderer* markerRenderer = nullptr;
    vtkRendererCollection* renderers = this->Window->renderer()->GetRenderWindow()->GetRenderers();
    renderers->InitTraversal();
    while (vtkRenderer* r = renderers->GetNextItem())
      if (r->GetViewProps()->IsItemPresent(cube))
        markerRenderer = r;
    QVERIFY(markerRenderer);
    vtkCamera* camera = this->Window->renderer()->GetActiveCamera();
    for (double azimuth : { 35.0, 120.0 })
    {
      camera->Azimuth(azimuth);
      camera->Elevation(20.0);
      camera->OrthogonalizeViewUp();
      this->Window->render();
      double a[3], b[3];
      camera->GetDirectionOfProjection(a);
      markerRenderer->GetActiveCamera()->GetDirectionOfProjection(b);
      QVERIFY(Dot3(a, b) > 0.9999);
      QVERIFY(Dot3(camera->GetViewUp(), markerRenderer->GetActiveCamera()->GetViewUp()) > 0.9999);
    }
  }

  void standardViewsLookFromEachSideAndFrameTheSurface()
  {
    // Direction of projection (camera to focal point) and view-up, LPS.
    const double projection[6][3] = {
      { 0, 1, 0 }, { 0, -1, 0 }, { -1, 0, 0 }, { 1, 0, 0 }, { 0, 0, -1 }, { 0, 0, 1 }
    };
    const double up[6][3] = {
      { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 }, { 0, -1, 0 }, { 0, -1, 0 }
    };
    const char* keys[6] = { "Ctrl+1", "Ctrl+2", "Ctrl+3", "Ctrl+4", "Ctrl+5", "Ctrl+6" };
    vtkCamera* camera = this->Window->renderer()->GetActiveCamera();
    for (int v = 0; v < 6; ++v)
    {
      camera->Azimuth(40);
      camera->Elevation(25);
      camera->OrthogonalizeViewUp();
      QAction* action = this->Window->actions()->StandardViews[v];
      QCOMPARE(action->shortcut().toString(), QString(keys[v]));
      action->trigger();
      double d[3];
      camera->GetDirectionOfProjection(d);
      QVERIFY2(Dot3(d, projection[v]) > 0.9999, qPrintable(action->text()));
      QVERIFY2(Dot3(camera->GetViewUp(), up[v]) > 0.9999, qPrintable(action->text()));
      double w = 0, h = 0;
      QVERIFY(this->surfaceInView(w, h));
      QVERIFY2(std::max(w, h) > 0.3, qPrintable(QString("%1 %2").arg(w).arg(h)));
    }
    // Reset camera: the anterior view again, whatever the rotation.
    camera->Azimuth(70);
    camera->Roll(30);
    this->Window->actions()->ResetCamera->trigger();
    double d[3];
    camera->GetDirectionOfProjection(d);
    QVERIFY(Dot3(d, projection[0]) > 0.9999);
    QVERIFY(Dot3(camera->GetViewUp(), up[0]) > 0.9999);
  }

  void scaleBarGivesMillimetresAtTheFocalPoint()
  {
    for (double zoom : { 1.0, 2.5, 0.3 })
    {
      this->Window->actions()->ResetCamera->trigger();
      this->Window->renderer()->GetActiveCamera()->Zoom(zoom);
      this->Window->render();
      const double mm = this->view()->scaleBarMillimetres();
      const double pixels = this->view()->scaleBarPixels();
      QVERIFY(mm > 0 && pixels > 20 && pixels < 400);
      // mm is 1, 2 or 5 times a power of ten.
      const double mantissa = mm / std::pow(10.0, std::floor(std::log10(mm) + 1e-9));
      QVERIFY(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
        std::abs(mantissa - 5) < 1e-6);
      // Two points `mm` apart across the screen at the focal point are `pixels` apart.
      vtkCamera* camera = this->Window->renderer()->GetActiveCamera();
      double focal[3], dop[3], right[3];
      camera->GetFocalPoint(focal);
      camera->GetDirectionOfProjection(dop);
      const double* vu = camera->GetViewUp();
      right[0] = dop[1] * vu[2] - dop[2] * vu[1];
      right[1] = dop[2] * vu[0] - dop[0] * vu[2];
      right[2] = dop[0] * vu[1] - dop[1] * vu[0];
      const double a[3] = { focal[0] - 0.5 * mm * right[0],
        focal[1] - 0.5 * mm * right[1],
        focal[2] - 0.5 * mm * right[2] };
      const double b[3] = { focal[0] + 0.5 * mm * right[0],
        focal[1] + 0.5 * mm * right[1],
        focal[2] + 0.5 * mm * right[2] };
      double da[3], db[3];
      Display(this->Window->renderer(), a, da);
      Display(this->Window->renderer(), b, db);
      QVERIFY2(std::abs(std::hypot(db[0] - da[0], db[1] - da[1]) - pixels) < 1.0,
        qPrintable(QString("%1 vs %2").arg(std::hypot(db[0] - da[0], db[1] - da[1])).arg(pixels)));
      QCOMPARE(QString(this->view()->scaleBarText()->GetInput()), QString("%1 mm").arg(mm));
    }
    this->Window->actions()->ResetCamera->trigger();
  }

  void originalShapeIsAGhostOnceBent()
  {
    bender::BenderSession& session = this->Window->session();
    QVERIFY(!this->view()->originalShown());
    auto* rep = this->Window->ribbonWidget()->GetRibbonRepresentation();
    QVERIFY(this->Window->grab());
    bender::RibbonSpec moved = rep->GetRibbon();
    moved.end.position = moved.end.position + bender::Vec3{ 8.0, 0, 3.0 };
    this->Window->setRibbon(moved);
    QVERIFY(this->view()->originalShown());
    QVERIFY(this->Window->release());
    QVERIFY(this->Window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QVERIFY(this->view()->originalShown());
    // The ghost draws the part of the original the bend moved (elsewhere it lies under the
    // surface): the original's own points, the triangles with a moved point.
    vtkPolyData* ghost =
      vtkPolyData::SafeDownCast(this->view()->originalActor()->GetMapper()->GetInput());
    QVERIFY(ghost);
    QCOMPARE(ghost, session.GetOriginalInPlay());
    QCOMPARE(ghost->GetPoints(), session.GetOriginalSurface()->GetPoints());
    QVERIFY(ghost->GetNumberOfPolys() > 0);
    QVERIFY(ghost->GetNumberOfPolys() < session.GetOriginalSurface()->GetNumberOfPolys());
    this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/view-ghost.png");
    this->Window->actions()->ShowOriginal->trigger();
    QVERIFY(!this->view()->originalShown());
    this->Window->actions()->ShowOriginal->trigger();
    QVERIFY(this->view()->originalShown());
    this->Window->actions()->Undo->trigger();
    QVERIFY(!this->view()->originalShown());
  }

  void bigSurfacesRotateAsADecimatedCopy()
  {
    BenderView* view = this->view();
    vtkRenderWindowInteractor* interactor = view->renderer()->GetRenderWindow()->GetInteractor();
    const long long triangles = this->Window->session().GetSurface()->GetNumberOfPolys();
    // The demo is small: drawn whole while rotating, with the default threshold.
    QVERIFY(triangles < view->levelOfDetailThreshold());
    const int* size = view->renderer()->GetSize();
    auto drag = [&](bool release)
    {
      interactor->SetEventInformation(size[0] / 2 + 150, size[1] / 2 + 150);
      interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
      interactor->SetEventInformation(size[0] / 2 + 170, size[1] / 2 + 140);
      interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
      if (release)
        interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
    };
    drag(true);
    QVERIFY(!view->isShowingProxy());
    // Above the threshold: the copy while the button is down, the whole surface after.
    view->setLevelOfDetailThreshold(triangles / 2);
    drag(false);
    QVERIFY(view->isShowingProxy());
    QVERIFY(!view->surfaceActor()->GetVisibility());
    QVERIFY(view->levelOfDetailProxy());
    QVERIFY(view->levelOfDetailProxy()->GetNumberOfPolys() > 100);
    QVERIFY(view->levelOfDetailProxy()->GetNumberOfPolys() < triangles);
    interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
    QVERIFY(!view->isShowingProxy());
    QVERIFY(view->surfaceActor()->GetVisibility());
    view->setLevelOfDetailThreshold(500000);
    this->Window->actions()->ResetCamera->trigger();
  }

  void aMeshOfAnotherSizeIsFramed()
  {
    // After the demo (about 80 mm), the bunny (2 units wide) must fill the view.
    QVERIFY(this->Window->openFile(QString(BENDER_EXTERNAL_DATA_DIR) + "/bunny.obj"));
    QVERIFY(this->Window->waitUntilIdle(60000));
    double bounds[6];
    this->Window->session().GetSurface()->GetBounds(bounds);
    QVERIFY(bounds[1] - bounds[0] < 3.0);
    // The demo's ribbon, far outside the bunny, is put away.
    QVERIFY(!this->Window->ribbonWidget()->GetEnabled());
    double w = 0, h = 0;
    QVERIFY(this->surfaceInView(w, h));
    QVERIFY2(std::max(w, h) > 0.3, qPrintable(QString("%1 %2").arg(w).arg(h)));
    this->Window->saveScreenshot(QString(BENDER_ARTIFACT_DIR) + "/view-bunny.png");
    // frameIfNewScene on its own: a camera far away from the surface comes back.
    vtkCamera* camera = this->Window->renderer()->GetActiveCamera();
    camera->SetFocalPoint(500, 500, 500);
    camera->SetPosition(500, 400, 500);
    QVERIFY(!this->view()->frameIfNewScene()); // the same scene: the user's camera is kept
    QVERIFY(!this->surfaceInView(w, h));
    this->Window->actions()->ResetCamera->trigger();
    QVERIFY(this->surfaceInView(w, h));
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("ViewAppTest");
  ViewAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "ViewAppTest.moc"
