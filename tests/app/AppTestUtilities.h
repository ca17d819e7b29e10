#ifndef bender_AppTestUtilities_h
#define bender_AppTestUtilities_h

// Pieces shared by the window test suites (AppTests, IgtlAppTests, VesselAppTests).

#include "CfdVerificationTubes.h"
#include "ExportFlow.h"
#include "MainWindow.h"
#include "Vec3.h"

#include <QApplication>
#include <QFileDialog>
#include <QFileInfo>
#include <QLineEdit>
#include <QMouseEvent>
#include <QPoint>
#include <QString>
#include <QTabWidget>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkCamera.h>
#include <vtkInteractorObserver.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <cmath>

namespace bendertest
{

/// A tube along x of radius r from x0 to x1, `rings` x `sides` points, open at both ends (the
/// one tube generator, CfdVerificationTubes.h; each ring starts on +y).
inline vtkSmartPointer<vtkPolyData> Tube(double x0,
  double x1,
  double r,
  int rings = 121,
  int sides = 24)
{
  return bender::SweepOpenTube(bender::StraightCentreline(x0, x1, rings - 1), r, sides);
}

/// A window for tests: autosave in `folder`, no recovery offer, no questions asked.
inline MainWindowOptions TestWindowOptions(const QString& folder)
{
  MainWindowOptions options;
  options.autosavePath = folder + "/autosave.bender-session.json";
  options.offerRecovery = false;
  options.interactive = false;
  return options;
}

/// Shows a test window at the suites' size (1280 x 900) and waits until it is exposed (and,
/// with `active`, the active window, for keyboard input). False when the wait timed out.
inline bool ShowTestWindow(MainWindow& window, bool active)
{
  window.resize(1280, 900);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window))
  {
    return false;
  }
  if (!active)
  {
    return true;
  }
  window.activateWindow();
  return QTest::qWaitForWindowActive(&window);
}

/// Types `path` (made absolute) into the file name box of a file dialog (Qt's own, the widget),
/// as a user does before pressing Open or Save; true once the dialog reads it. Not
/// QFileDialog::selectFile: that leaves the box alone while it has the keyboard focus (Qt keeps
/// what the user is typing), and once the dialog is active, Open or Save then takes the empty
/// box for its folder, opens the folder and waits for a name that never comes.
inline bool TypeFileName(QFileDialog& dialog, const QString& path)
{
  auto* name = dialog.findChild<QLineEdit*>("fileNameEdit");
  if (!name)
  {
    return false;
  }
  const QString absolute = QFileInfo(path).absoluteFilePath();
  name->setText(absolute);
  return dialog.selectedFiles() == QStringList{ absolute };
}

/// Ctrl+E on the window; the export dialog once it is open (it opens window-modal, without
/// blocking: waited for up to 5 s). Null when the window cannot be activated or no dialog came.
inline ExportDialog* OpenExportDialog(MainWindow& window)
{
  window.activateWindow();
  QApplication::setActiveWindow(&window);
  if (!QTest::qWaitForWindowActive(&window))
  {
    return nullptr;
  }
  QTest::keyClick(&window, Qt::Key_E, Qt::ControlModifier);
  ExportDialog* dialog = nullptr;
  for (int waited = 0; waited < 5000 && !dialog; waited += 20)
  {
    dialog = window.findChild<ExportDialog*>("exportDialog");
    if (!dialog)
    {
      QTest::qWait(20);
    }
  }
  return dialog;
}

/// The visible top-level widget of type T (named `name` when given): a dialog on screen, whether
/// or not it is the active modal widget yet.
template<typename T>
T* VisibleTopLevel(const QString& name = {})
{
  for (QWidget* widget : QApplication::topLevelWidgets())
  {
    auto* found = qobject_cast<T*>(widget);
    if (found && found->isVisible() && (name.isEmpty() || found->objectName() == name))
    {
      return found;
    }
  }
  return nullptr;
}

/// Brings `panel` to the front of the window's panel dock (as a click on its tab would). False
/// when the window has no panel dock or `panel` is not one of its tabs.
inline bool ShowPanel(MainWindow& window, QWidget* panel)
{
  auto* panels = window.findChild<QTabWidget*>("panels");
  if (!panels || panels->indexOf(panel) < 0)
  {
    return false;
  }
  panels->setCurrentWidget(panel);
  return true;
}

/// Points the 3D view's camera at `target` from `direction` (unit), far enough to see `span` mm
/// around it, and renders.
inline void Look(MainWindow& window,
  const bender::Vec3& target,
  const bender::Vec3& direction,
  double span)
{
  vtkCamera* camera = window.renderer()->GetActiveCamera();
  camera->SetFocalPoint(target.x, target.y, target.z);
  const bender::Vec3 eye = target + 3.0 * span * direction;
  camera->SetPosition(eye.x, eye.y, eye.z);
  const bender::Vec3 up =
    std::abs(direction.z) < 0.9 ? bender::Vec3{ 0, 0, 1 } : bender::Vec3{ 0, 1, 0 };
  camera->SetViewUp(up.x, up.y, up.z);
  camera->SetViewAngle(30);
  window.renderer()->ResetCameraClippingRange();
  window.render();
}

/// A real drag with the left button in `view` (a 3D view), from `from` to `to` in eight moves.
inline void Drag(QWidget* view, const QPoint& from, const QPoint& to)
{
  QTest::mouseMove(view, from);
  QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, from);
  for (int step = 1; step <= 8; ++step)
  {
    const QPoint at = from + (to - from) * step / 8;
    QMouseEvent move(QEvent::MouseMove, at, Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(view, &move);
    QCoreApplication::processEvents();
  }
  QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, to);
  QCoreApplication::processEvents();
}

/// The 3D view's widget (Qt) coordinates of a model point.
inline QPoint Project(MainWindow& window, const bender::Vec3& p)
{
  double display[3];
  vtkInteractorObserver::ComputeWorldToDisplay(window.renderer(), p.x, p.y, p.z, display);
  const double ratio = window.view()->devicePixelRatioF();
  const int height = window.view()->height();
  return QPoint(static_cast<int>(std::lround(display[0] / ratio)),
    height - 1 - static_cast<int>(std::lround(display[1] / ratio)));
}

} // namespace bendertest

#endif
