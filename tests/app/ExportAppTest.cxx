// The export side of the window (issue 11): the Ctrl+E dialog offers the preset "OpenFOAM (m,
// named solids)", caps, patches, frame, unit and the sidecar, and writes what it shows; named
// solids never turn a binary STL into ASCII silently; the TetGen preset writes a .smesh; --cap
// on a closed surface fails the export. The Prepare for CFD step on the demo vessel: a disc
// per vessel end in the 3D view, dragged with the mouse along its centerline (the table's cut
// distance follows, and a typed distance moves the disc), then Prepare (a worker job: the
// window keeps processing events) cuts exactly there and shows the labelled caps; a cancelled
// Prepare changes nothing. Run under Xvfb (QT_QPA_PLATFORM=xcb); the screenshots are kept in
// test-artifacts/.
#include "AppTestUtilities.h"
#include "BenderView.h"
#include "CfdEndsOverlay.h"
#include "ExportFlow.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "MainWindow.h"
#include "VesselController.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileDialog>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QMouseEvent>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QStatusBar>
#include <QSurfaceFormat>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include "MeshFormats.h"
#include "PatchLabels.h"
#include "VesselClip.h"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <thread>

namespace
{
using P3 = std::array<double, 3>;

double Dot(const P3& a, const P3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

P3 Minus(const P3& a, const P3& b)
{
  return { { a[0] - b[0], a[1] - b[1], a[2] - b[2] } };
}

/// The area centroid of the cells labelled `id` (a cap).
P3 CapCentre(vtkPolyData* surface, int id)
{
  vtkDataArray* ids = surface->GetCellData()->GetArray(bender::kCellEntityIdsArrayName);
  P3 sum{ { 0, 0, 0 } };
  double area = 0;
  for (vtkIdType c = 0; ids && c < surface->GetNumberOfCells(); ++c)
  {
    if (static_cast<int>(ids->GetTuple1(c)) != id)
      continue;
    vtkIdType n;
    const vtkIdType* pts;
    surface->GetCellPoints(c, n, pts);
    P3 p[3];
    for (int k = 0; k < 3; ++k)
      surface->GetPoint(pts[k], p[k].data());
    const P3 u = Minus(p[1], p[0]), v = Minus(p[2], p[0]);
    const P3 cr{
      { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] }
    };
    const double a = 0.5 * std::sqrt(Dot(cr, cr));
    for (int e = 0; e < 3; ++e)
      sum[e] += a * (p[0][e] + p[1][e] + p[2][e]) / 3.0;
    area += a;
  }
  return { { sum[0] / area, sum[1] / area, sum[2] / area } };
}
} // namespace

class ExportAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  // While HoldJobs, every worker job waits at its start until Released (or cancelled): the
  // test sees the window while Prepare for CFD runs.
  std::atomic<bool> HoldJobs{ false };
  std::atomic<bool> Released{ false };
  // Saved between the Prepare tests.
  vtkMTimeType PreparedTime = 0;

  QVTKOpenGLNativeWidget* view() { return this->Window->view(); }

  QPoint widgetPoint(const double display[2])
  {
    const double ratio = this->view()->devicePixelRatioF();
    return QPoint(static_cast<int>(std::lround(display[0] / ratio)),
      this->view()->height() - 1 - static_cast<int>(std::lround(display[1] / ratio)));
  }

  void sendMouseMove(const QPoint& at, Qt::MouseButtons buttons)
  {
    QMouseEvent move(QEvent::MouseMove, at, Qt::NoButton, buttons, Qt::NoModifier);
    QApplication::sendEvent(this->view(), &move);
    QCoreApplication::processEvents();
  }

  ExportOptionsForm* panelForm()
  {
    auto* panel = this->Window->findChild<ExportPanel*>();
    return panel ? panel->form() : nullptr;
  }

  // Opens the dialog with the window's Ctrl+E shortcut.
  ExportDialog* openDialog() { return bendertest::OpenExportDialog(*this->Window); }

  static QString readAll(const QString& path)
  {
    QFile file(path);
    return file.open(QIODevice::ReadOnly) ? QString::fromLatin1(file.readAll()) : QString();
  }

  bool exportWith(ExportDialog* dialog, const QString& path)
  {
    dialog->setPath(path);
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QTest::mouseClick(dialog->findChild<QPushButton*>("exportOk"), Qt::LeftButton);
    return this->Window->waitUntilIdle(120000) && finished.count() == 1 &&
      finished.first().first().toBool();
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    MainWindowOptions options = bendertest::TestWindowOptions(this->Folder.path());
    options.workHook = [this](const bender::ProgressReporter& progress)
    {
      // A safety limit only: the test releases the job long before.
      for (int waited = 0;
           this->HoldJobs && !this->Released && !progress.Cancelled() && waited < 60000;
           waited += 5)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    };
    this->Window = std::make_unique<MainWindow>(options);
    QVERIFY(bendertest::ShowTestWindow(*this->Window, false));
    // An open tube of radius 5 mm from x = -20 to 20: two open ends to cap.
    QVERIFY(this->Window->session().SetSurface(bendertest::Tube(-20, 20, 5, 41, 32), "tube"));
  }

  void cleanupTestCase()
  {
    this->Window->close();
    this->Window.reset();
  }

  void theDialogOffersTheOpenFoamPreset()
  {
    QCOMPARE(this->Window->actions()->Export->shortcut(), QKeySequence("Ctrl+E"));
    ExportDialog* dialog = this->openDialog();
    QVERIFY(dialog);
    ExportOptionsForm* form = dialog->form();
    for (const char* name : { "presetCombo",
           "formatCombo",
           "capCheck",
           "patchesCombo",
           "frameCombo",
           "unitCombo",
           "sidecarCheck" })
    {
      QVERIFY2(dialog->findChild<QWidget*>(name), name);
    }
    QCOMPARE(form->Presets->itemText(ExportOptionsForm::OpenFoam), "OpenFOAM (m, named solids)");
    form->Presets->setCurrentIndex(ExportOptionsForm::OpenFoam);
    QCOMPARE(form->Formats->currentIndex(), form->formatIndex("stl", true));
    QCOMPARE(form->Patches->currentIndex(), 1);
    QCOMPARE(form->Unit->currentIndex(), 1);
    QVERIFY(form->Cap->isChecked());
    QVERIFY(form->Sidecar->isChecked());
    QVERIFY(dialog->path().endsWith(".stl"));
    QApplication::processEvents();
    const QString shots = QString(BENDER_ARTIFACT_DIR);
    QDir().mkpath(shots);
    QVERIFY(dialog->grab().save(shots + "/export-dialog-openfoam.png"));

    const QString stl = this->Folder.filePath("vessel.stl");
    QVERIFY(this->exportWith(dialog, stl));
    const QString text = readAll(stl);
    for (const char* solid : { "solid wall\n", "solid inlet\n", "solid outlet_1\n" })
    {
      QVERIFY2(text.contains(solid), solid);
    }
    QVERIFY(!text.contains("solid outlet_2"));
    QVERIFY(text.contains("unit m\n"));
    // Metres: the tube's 5 mm radius is 0.005.
    QFile json(this->Folder.filePath("vessel.patches.json"));
    QVERIFY(json.open(QIODevice::ReadOnly));
    const QJsonObject sidecar = QJsonDocument::fromJson(json.readAll()).object();
    QCOMPARE(sidecar["unit"].toString(), QString("m"));
    const QJsonArray patches = sidecar["patches"].toArray();
    QCOMPARE(patches.size(), 3);
    const double diameter = patches[1].toObject()["equivalentDiameter"].toDouble();
    QVERIFY2(std::abs(diameter - 0.010) < 0.0002, qPrintable(QString::number(diameter)));
    QVERIFY(sidecar["insidePoint"].isArray());
    // The panel keeps the dialog's choices.
    QCOMPARE(this->panelForm()->Presets->currentIndex(), int(ExportOptionsForm::OpenFoam));
    QCOMPARE(this->panelForm()->Unit->currentIndex(), 1);
  }

  void namedSolidsNeverMakeABinaryStlAsciiSilently()
  {
    ExportOptionsForm* form = this->panelForm();
    QVERIFY(form);
    form->Presets->setCurrentIndex(ExportOptionsForm::Custom);
    form->Patches->setCurrentIndex(0);
    form->Formats->setCurrentIndex(form->formatIndex("stl"));
    QVERIFY(form->note().isEmpty());
    form->Patches->setCurrentIndex(1);
    QCOMPARE(form->Formats->currentIndex(), form->formatIndex("stl", true));
    QVERIFY2(form->note().contains("STL (ASCII)"), qPrintable(form->note()));
    form->Formats->setCurrentIndex(form->formatIndex("stl"));
    QCOMPARE(form->Patches->currentIndex(), 0);
    QVERIFY2(form->note().contains("One surface"), qPrintable(form->note()));
    // The binary STL written is binary.
    form->Cap->setChecked(false);
    form->Unit->setCurrentIndex(0);
    const QString stl = this->Folder.filePath("binary.stl");
    QVERIFY(this->Window->exportSurface(stl, true));
    QVERIFY(this->Window->waitUntilIdle(120000));
    QFile file(stl);
    QVERIFY(file.open(QIODevice::ReadOnly));
    const QByteArray head = file.read(80);
    QVERIFY(!head.startsWith("solid"));
    QVERIFY(head.contains("unit mm"));
    // Patches are for STL only: the combo follows the format.
    form->Formats->setCurrentIndex(form->formatIndex("vtp"));
    QVERIFY(!form->Patches->isEnabled());
  }

  void theTetgenPresetWritesASmesh()
  {
    ExportDialog* dialog = this->openDialog();
    QVERIFY(dialog);
    dialog->setPath(this->Folder.filePath("tet.stl"));
    dialog->form()->Presets->setCurrentIndex(ExportOptionsForm::Tetgen);
    QCOMPARE(dialog->path(), this->Folder.filePath("tet.smesh"));
    QVERIFY(this->exportWith(dialog, dialog->path()));
    const QString text = readAll(this->Folder.filePath("tet.smesh"));
    QVERIFY(text.contains("1=wall 2=inlet 3=outlet_1"));
    QVERIFY(text.contains("unit m"));
    QVERIFY(QFileInfo::exists(this->Folder.filePath("tet.patches.json")));
  }

  void aRegisteredFormatIsInTheOpenDialogAndTheExportFormats()
  {
    // A dummy format, registered for this test only (bender::MeshFormats' registry).
    bender::MeshFormat dummy;
    dummy.name = "dummy";
    dummy.extensions = { ".dummy" };
    dummy.label = "Dummy test mesh";
    dummy.read = [](const std::string&, std::uintmax_t)
    { return vtkSmartPointer<vtkPolyData>::New(); };
    dummy.write = [](
                    vtkPolyData*, const std::string&, const bender::MeshWriteOptions&, std::string&)
    { return true; };
    const bender::ScopedMeshFormat registered(dummy);
    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*window, false));

    // The Export panel's formats are the table's writable rows: the dummy is one of them, and
    // choosing it gives its extension.
    ExportOptionsForm* form = window->findChild<ExportPanel*>()->form();
    const int entry = form->formatIndex("dummy");
    QVERIFY(entry >= 0);
    QCOMPARE(form->Formats->itemText(entry), QString("Dummy test mesh"));
    form->Formats->setCurrentIndex(entry);
    QCOMPARE(form->suffix(), QString(".dummy"));
    QVERIFY(!form->Patches->isEnabled());
    QVERIFY(ExportPanel::fileFilter().contains("Dummy test mesh (*.dummy)"));

    // File > Open: Qt's own dialog (the widget), read while it is open, then cancelled.
    QCoreApplication::setAttribute(Qt::AA_DontUseNativeDialogs, true);
    QStringList filters;
    QTimer poll;
    poll.setInterval(50);
    connect(&poll,
      &QTimer::timeout,
      [&filters, &poll]()
      {
        if (auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget()))
        {
          filters = dialog->nameFilters();
          dialog->reject();
          poll.stop();
        }
      });
    poll.start();
    window->actions()->Open->trigger();
    poll.stop();
    QVERIFY(!filters.isEmpty());
    QVERIFY2(filters.front().startsWith("All supported (") && filters.front().contains("*.dummy"),
      qPrintable(filters.front()));
    QVERIFY2(filters.contains("Dummy test mesh (*.dummy)"), qPrintable(filters.join(" | ")));
    QVERIFY(filters.contains("STL (*.stl)"));
    window->close();
  }

  void anEmptyFileIsRefusedInTheDialog()
  {
    ExportDialog* dialog = this->openDialog();
    QVERIFY(dialog);
    dialog->setPath("");
    QTest::mouseClick(dialog->findChild<QPushButton*>("exportOk"), Qt::LeftButton);
    QVERIFY(dialog->isVisible());
    QVERIFY(!dialog->findChild<QLabel*>("exportProblem")->text().isEmpty());
    dialog->reject();
  }

  void prepareForCfdListsTheEndsWithEditableNames()
  {
    bender::BenderSession& session = this->Window->session();
    QVERIFY(session.SetSurface(bendertest::Tube(-20, 20, 5, 41, 32), "tube"));
    auto* panel = this->Window->findChild<ExportPanel*>();
    QVERIFY(panel);
    auto* panels = this->Window->findChild<QTabWidget*>("panels");
    if (panels)
    {
      panels->setCurrentWidget(panel);
    }
    panel->Clip->setChecked(false); // the tube's ends are open already
    QTest::mouseClick(panel->Prepare, Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(120000)); // a job on the worker
    QCOMPARE(panel->Ends->rowCount(), 2);
    int inletRow = -1, outletRow = -1;
    for (int row = 0; row < 2; ++row)
    {
      const QString role = panel->Ends->item(row, 1)->text();
      (role == "inlet" ? inletRow : outletRow) = row;
    }
    QVERIFY(inletRow >= 0 && outletRow >= 0);
    QCOMPARE(panel->Ends->item(inletRow, 0)->text(), QString("inlet"));
    QCOMPARE(panel->Ends->item(outletRow, 0)->text(), QString("outlet_1"));
    const auto extent = [&session]()
    {
      double b[6];
      session.GetSurface()->GetBounds(b);
      return b[1] - b[0];
    };
    // 40 mm of tube, 10 radii (about 5 mm) at the inlet and 5 at the outlet.
    QVERIFY2(std::abs(extent() - 115.0) < 2.0, qPrintable(QString::number(extent())));
    auto labels = bender::ReadPatchLabels(session.GetSurface());
    QCOMPARE(labels.size(), std::size_t(3));
    QVERIFY(static_cast<QWidget*>(this->Window.get())
              ->grab()
              .save(QString(BENDER_ARTIFACT_DIR) + "/export-panel-prepared.png"));

    // Renamed, without an outlet extension: prepared again from the surface before.
    panel->Ends->item(outletRow, 0)->setText("aorta_out");
    panel->Ends->item(outletRow, 3)->setText("0");
    QTest::mouseClick(panel->Prepare, Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(120000));
    QCOMPARE(panel->Ends->rowCount(), 2);
    labels = bender::ReadPatchLabels(session.GetSurface());
    QCOMPARE(labels.size(), std::size_t(3));
    bool renamed = false;
    for (const auto& label : labels)
    {
      renamed = renamed || label.name == "aorta_out";
    }
    QVERIFY(renamed);
    QVERIFY2(std::abs(extent() - 90.0) < 2.0, qPrintable(QString::number(extent())));
    // A bad name is refused with one line in the report; the surface stays.
    panel->Ends->item(outletRow, 0)->setText("no spaces");
    QTest::mouseClick(panel->Prepare, Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(120000));
    QVERIFY(panel->findChild<QPlainTextEdit*>("checkReport")
              ->toPlainText()
              .startsWith("Prepare for CFD failed"));
    QVERIFY2(std::abs(extent() - 90.0) < 2.0, qPrintable(QString::number(extent())));
  }

  void cappingAClosedSurfaceFailsTheExport()
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(5);
    sphere->SetThetaResolution(24);
    sphere->SetPhiResolution(12);
    sphere->Update();
    QVERIFY(this->Window->session().SetSurface(sphere->GetOutput(), "sphere"));
    ExportOptionsForm* form = this->panelForm();
    form->Presets->setCurrentIndex(ExportOptionsForm::OpenFoam);
    const QString stl = this->Folder.filePath("sphere.stl");
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    this->Window->exportSurface(stl, true);
    QVERIFY(this->Window->waitUntilIdle(120000));
    QCOMPARE(finished.count(), 1);
    QCOMPARE(finished.first().first().toBool(), false);
    QVERIFY(!QFileInfo::exists(stl));
    QVERIFY(!QFileInfo::exists(this->Folder.filePath("sphere.patches.json")));
  }

  void theVesselEndsAreDiscsDraggedAlongTheCenterlineAndPreparedThere()
  {
    auto* panel = this->Window->findChild<ExportPanel*>();
    auto* panels = this->Window->findChild<QTabWidget*>("panels");
    QVERIFY(panel && panels);
    this->Window->startDemo();
    QVERIFY(this->Window->waitUntilIdle(180000));
    QVERIFY(this->Window->waitForCenterlines(180000));
    panels->setCurrentWidget(panel);
    QApplication::processEvents();
    panel->showReport(QString());
    panel->Clip->setChecked(true);
    CfdEndsOverlay* overlay = this->Window->exports()->endsOverlay();
    QVERIFY(overlay);
    QVERIFY(overlay->isVisible());
    QVERIFY(!overlay->showsPatches());

    // One disc per vessel end of the centerlines, on its plane, 1.5 inscribed radii wide.
    QVERIFY2(this->Window->vessels()->vessels().HasCenterlines(),
      qPrintable(this->Window->statusLabel()->text()));
    const std::vector<bender::CenterlineEnd> ends =
      bender::FindCenterlineEnds(this->Window->vessels()->vessels().GetPaths());
    QCOMPARE(ends.size(), std::size_t(3)); // the demo: an inlet and two outlets
    QCOMPARE(overlay->numberOfEnds(), 3);
    QCOMPARE(overlay->numberOfDiscsShown(), 3);
    QVERIFY(panel->listsCenterlineEnds());
    QCOMPARE(panel->Ends->rowCount(), 3);
    int inlets = 0;
    for (int k = 0; k < 3; ++k)
    {
      const bender::ClipPlane plane = overlay->plane(k);
      QVERIFY(plane.radius > 0.5);
      vtkPolyData* disc = overlay->disc(k);
      QVERIFY(disc && disc->GetNumberOfPoints() >= 24);
      for (vtkIdType i = 0; i < disc->GetNumberOfPoints(); ++i)
      {
        P3 p;
        disc->GetPoint(i, p.data());
        const P3 d = Minus(p, plane.centre);
        QVERIFY(std::abs(Dot(d, plane.normal)) < 1e-6 * plane.radius);
        QVERIFY(std::abs(std::sqrt(Dot(d, d)) - 1.5 * plane.radius) < 1e-6 * plane.radius);
      }
      // The disc starts where the clip cuts by default; the table says so.
      QCOMPARE(overlay->distance(k), overlay->path(k).defaultDistance);
      QCOMPARE(panel->Ends->item(k, ExportPanel::CutColumn)->text(),
        QString::number(overlay->distance(k), 'f', 2));
      QVERIFY(overlay->label(k).startsWith(panel->endName(k)));
      inlets += panel->endIsInlet(k) ? 1 : 0;
    }
    QCOMPARE(inlets, 1);
    // Another panel: the discs go; back to Export: they come back.
    panels->setCurrentIndex(0);
    QApplication::processEvents();
    QCOMPARE(overlay->numberOfDiscsShown(), 0);
    panels->setCurrentWidget(panel);
    QApplication::processEvents();
    QCOMPARE(overlay->numberOfDiscsShown(), 3);
    // Not clipping (the surface's open ends as they are): no disc.
    panel->Clip->setChecked(false);
    QCOMPARE(overlay->numberOfDiscsShown(), 0);
    panel->Clip->setChecked(true);
    QCOMPARE(overlay->numberOfDiscsShown(), 3);

    // Drag the end whose move shows best on the screen, by about two radii inwards.
    this->Window->benderView()->resetCamera();
    this->Window->render();
    int end = -1;
    double best = 0, target = 0;
    for (int k = 0; k < 3; ++k)
    {
      const bender::CenterlineEndPath& path = overlay->path(k);
      const double d0 = overlay->distance(k);
      const double t = d0 + std::min(2.0 * path.radius, 0.8 * (path.maximumDistance - d0));
      double a[2], b[2];
      QVERIFY(overlay->pathDisplayPosition(k, d0, a));
      QVERIFY(overlay->pathDisplayPosition(k, t, b));
      const double pixels = std::hypot(b[0] - a[0], b[1] - a[1]);
      if (pixels > best)
      {
        best = pixels;
        end = k;
        target = t;
      }
    }
    QVERIFY2(best > 20, qPrintable(QString::number(best)));
    const double start = overlay->distance(end);
    const double radius = overlay->plane(end).radius;
    const bender::ClipPlane before = overlay->plane(end);
    double handle[2], goal[2];
    QVERIFY(overlay->handleDisplayPosition(end, handle));
    QVERIFY(overlay->pathDisplayPosition(end, target, goal));
    QVERIFY(handle[0] > 0 && handle[0] < this->view()->width() && handle[1] > 0 &&
      handle[1] < this->view()->height());
    vtkCamera* camera = this->Window->renderer()->GetActiveCamera();
    double eye[3];
    camera->GetPosition(eye);
    QTest::mousePress(this->view(), Qt::LeftButton, Qt::NoModifier, this->widgetPoint(handle));
    QCOMPARE(overlay->draggedEnd(), end);
    for (int step = 1; step <= 8; ++step)
    {
      const double at[2] = { handle[0] + (goal[0] - handle[0]) * step / 8.0,
        handle[1] + (goal[1] - handle[1]) * step / 8.0 };
      this->sendMouseMove(this->widgetPoint(at), Qt::LeftButton);
    }
    QTest::mouseRelease(this->view(), Qt::LeftButton, Qt::NoModifier, this->widgetPoint(goal));
    QCOMPARE(overlay->draggedEnd(), -1);
    // The disc moved along the centerline by the drag (to a pixel), perpendicular to it there;
    // the camera did not move (the drag was the disc's).
    const double dragged = overlay->distance(end);
    QVERIFY2(std::abs(dragged - target) < 0.25 * radius,
      qPrintable(QString("%1 -> %2, wanted %3").arg(start).arg(dragged).arg(target)));
    QVERIFY(dragged - start > 1.0 * radius);
    double eyeAfter[3];
    camera->GetPosition(eyeAfter);
    QCOMPARE(eyeAfter[0], eye[0]);
    QCOMPARE(eyeAfter[2], eye[2]);
    const bender::ClipPlane moved = overlay->plane(end);
    const bender::ClipPlane expected = bender::ClipPlaneAt(overlay->path(end), dragged);
    QCOMPARE(moved.centre, expected.centre);
    QVERIFY(std::sqrt(Dot(Minus(moved.centre, before.centre), Minus(moved.centre, before.centre))) >
      0.9 * radius);
    // The table follows the drag.
    QCOMPARE(panel->cutDistance(end), dragged);
    QCOMPARE(
      panel->Ends->item(end, ExportPanel::CutColumn)->text(), QString::number(dragged, 'f', 2));

    // A distance typed in the table moves another end's disc.
    const int typed = (end + 1) % 3;
    const double typedDistance = std::round((overlay->distance(typed) + 1.5) * 100.0) / 100.0;
    panel->Ends->item(typed, ExportPanel::CutColumn)
      ->setText(QString::number(typedDistance, 'f', 2));
    QVERIFY(std::abs(overlay->distance(typed) - typedDistance) < 1e-9);
    // Past the range: clamped, in the table too.
    const int third = (end + 2) % 3;
    panel->Ends->item(third, ExportPanel::CutColumn)->setText("100000");
    QCOMPARE(overlay->distance(third), overlay->path(third).maximumDistance);
    QCOMPARE(panel->cutDistance(third), overlay->path(third).maximumDistance);
    panel->Ends->item(third, ExportPanel::CutColumn)
      ->setText(QString::number(overlay->path(third).defaultDistance, 'f', 2));
    QApplication::processEvents();
    const QString shots = QString(BENDER_ARTIFACT_DIR);
    QDir().mkpath(shots);
    const auto obliqueView = [this, camera]()
    {
      // From the right, a little from above: the outlets' ends face the camera.
      this->Window->benderView()->resetCamera();
      camera->Azimuth(-60);
      camera->Elevation(20);
      camera->OrthogonalizeViewUp();
      this->Window->renderer()->ResetCameraClippingRange();
      this->Window->render();
    };
    obliqueView();
    QVERIFY(this->Window->grabWindowImage().save(shots + "/cfd-ends.png"));

    // Prepare for CFD, no flow extension (the caps are the cuts), on the worker: the window
    // keeps processing events (a timer ticks, the progress bar shows) while it runs.
    const bender::ClipPlane cutDragged = overlay->plane(end);
    const bender::ClipPlane cutTyped = overlay->plane(typed);
    panel->InletFactor->setValue(0.0);
    panel->OutletFactor->setValue(0.0);
    this->HoldJobs = true;
    this->Released = false;
    int ticksWhileBusy = 0;
    bool progressShown = false;
    QTimer timer;
    timer.setInterval(10);
    connect(&timer,
      &QTimer::timeout,
      [&]()
      {
        if (!this->Window->isBusy())
          return;
        ++ticksWhileBusy;
        for (QProgressBar* bar : this->Window->statusBar()->findChildren<QProgressBar*>())
          progressShown = progressShown || bar->isVisible();
        if (ticksWhileBusy >= 5)
          this->Released = true;
      });
    timer.start();
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QTest::mouseClick(panel->Prepare, Qt::LeftButton);
    QVERIFY(this->Window->isBusy()); // started, not done: the click returned at once
    QVERIFY(this->Window->waitUntilIdle(180000));
    timer.stop();
    this->HoldJobs = false;
    QVERIFY(ticksWhileBusy >= 5);
    QVERIFY(progressShown);
    QCOMPARE(finished.count(), 1);
    QVERIFY2(finished.first().first().toBool(),
      qPrintable(panel->findChild<QPlainTextEdit*>("checkReport")->toPlainText()));

    // The caps are where the discs were: on the dragged plane, centred on the centerline.
    vtkPolyData* surface = this->Window->session().GetSurface();
    const auto labels = bender::ReadPatchLabels(surface);
    QCOMPARE(labels.size(), std::size_t(4)); // wall and three ends
    for (const bender::ClipPlane& cut : { cutDragged, cutTyped })
    {
      int nearest = -1;
      double nearestDistance = 1e300;
      for (const auto& label : labels)
      {
        if (label.id < 2)
          continue;
        const P3 c = CapCentre(surface, label.id);
        const double d = std::sqrt(Dot(Minus(c, cut.centre), Minus(c, cut.centre)));
        if (d < nearestDistance)
        {
          nearestDistance = d;
          nearest = label.id;
        }
      }
      QVERIFY(nearest >= 2);
      const P3 c = CapCentre(surface, nearest);
      const double off = Dot(Minus(c, cut.centre), cut.normal);
      QVERIFY2(std::abs(off) < 0.05 * cut.radius,
        qPrintable(QString("cap %1 off its plane by %2 mm").arg(nearest).arg(off)));
      QVERIFY2(nearestDistance < 0.5 * cut.radius,
        qPrintable(
          QString("cap %1 is %2 mm from the centerline").arg(nearest).arg(nearestDistance)));
    }
    // Not where the dragged end is cut by default.
    {
      const P3 shift = Minus(cutDragged.centre, before.centre);
      QVERIFY(std::abs(Dot(shift, before.normal)) > 0.8 * radius);
    }

    // After Prepare the discs go, the caps are shown labelled with their names; the table
    // lists the prepared ends with their cuts.
    QVERIFY(overlay->showsPatches());
    QCOMPARE(overlay->numberOfDiscsShown(), 0);
    QCOMPARE(overlay->numberOfPatchLabelsShown(), 3);
    std::vector<QString> names = overlay->patchLabels();
    std::sort(names.begin(), names.end());
    QCOMPARE(names, (std::vector<QString>{ "inlet", "outlet_1", "outlet_2" }));
    QVERIFY(overlay->caps()->GetNumberOfCells() > 0);
    QVERIFY(!panel->listsCenterlineEnds());
    QCOMPARE(panel->Ends->rowCount(), 3);
    bool draggedListed = false;
    for (int row = 0; row < 3; ++row)
    {
      draggedListed = draggedListed || std::abs(panel->cutDistance(row) - dragged) < 1e-9;
    }
    QVERIFY(draggedListed);
    // The centerlines of the prepared surface arrive: its caps stay shown.
    QVERIFY(this->Window->waitForCenterlines(180000));
    QApplication::processEvents();
    QVERIFY(overlay->showsPatches());
    QCOMPARE(overlay->numberOfPatchLabelsShown(), 3);
    obliqueView();
    QVERIFY(this->Window->grabWindowImage().save(shots + "/cfd-prepared.png"));
    this->PreparedTime = surface->GetMTime();
  }

  void aCancelledPrepareChangesNothing()
  {
    auto* panel = this->Window->findChild<ExportPanel*>();
    vtkPolyData* surface = this->Window->session().GetSurface();
    QVERIFY(this->PreparedTime != 0 && surface->GetMTime() == this->PreparedTime);
    this->HoldJobs = true;
    this->Released = false;
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QTest::mouseClick(panel->Prepare, Qt::LeftButton); // again, from the surface before
    QVERIFY(this->Window->isBusy());
    auto* cancel = this->Window->statusBar()->findChild<QPushButton*>("cancelWork");
    QVERIFY(cancel && cancel->isVisible());
    QTest::mouseClick(cancel, Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(180000));
    this->HoldJobs = false;
    QCOMPARE(finished.count(), 1);
    QCOMPARE(finished.first().first().toBool(), false);
    QCOMPARE(this->Window->session().GetSurface(), surface);
    QCOMPARE(surface->GetMTime(), this->PreparedTime);
    QVERIFY(this->Window->exports()->endsOverlay()->showsPatches());
    QCOMPARE(bender::ReadPatchLabels(surface).size(), std::size_t(4));
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("ExportAppTest");
  ExportAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "ExportAppTest.moc"
