// A planning session that loses nothing and mixes no patients (issue 22, items 4, 7, 8 and the
// small ones), on the real window under Xvfb, with the keys and dialogs a user has: a failed
// Ctrl+O changes nothing (the warps, their unsaved state, the autosave; Ctrl+Q still asks); a
// mesh is asked about only once it has been read; another patient's volume closes the surface
// with its warps, ribbon and centerlines (asking first); an export in metres and in RAS opens
// again where it was in LPS millimetres, in every format that states its unit and frame; the
// Bend panel says a ribbon is
// placed, counts say "1 warp", F1's table fits without sideways scrolling, the region's outline
// stays one simple closed curve while the ribbon is dragged.
#include "AppTestUtilities.h"
#include "OutlineCrossings.h"
#include "SwungRibbon.h"

#include "BendPanel.h"
#include "BenderSession.h"
#include "BenderView.h"
#include "ExportPanel.h"
#include "FileOpener.h"
#include "GestureController.h"
#include "MainActions.h"
#include "MainWindow.h"
#include "MeshIO.h"
#include "SegmentationSession.h"
#include "VesselController.h"
#include "VolumeIO.h"
#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QElapsedTimer>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QHeaderView>
#include <QLabel>
#include <QMessageBox>
#include <QMouseEvent>
#include <QScreen>
#include <QScrollBar>
#include <QSettings>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTimer>
#include <QtTest>

#include <vtkPolyData.h>

#include <cmath>
#include <memory>
#include <string>

namespace
{

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

// The largest difference between the bounds of two surfaces.
double BoundsDifference(vtkPolyData* a, vtkPolyData* b)
{
  double p[6], q[6];
  a->GetBounds(p);
  b->GetBounds(q);
  double worst = 0.0;
  for (int k = 0; k < 6; ++k)
    worst = std::max(worst, std::abs(p[k] - q[k]));
  return worst;
}

vtkSmartPointer<vtkPolyData> Copy(vtkPolyData* surface)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(surface);
  return copy;
}

QByteArray ReadAll(const QString& path)
{
  QFile file(path);
  return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

using bendertest::VisibleTopLevel;

// Answers every "Save changes?" box with `button` while it lives, counting them.
class SaveChangesAnswer
{
public:
  explicit SaveChangesAnswer(QMessageBox::StandardButton button)
  {
    this->Timer.setInterval(30);
    QObject::connect(&this->Timer,
      &QTimer::timeout,
      [this, button]()
      {
        auto* box = VisibleTopLevel<QMessageBox>("saveChanges");
        if (!box)
          return;
        ++this->Count;
        this->Text = box->text();
        QTest::mouseClick(box->button(button), Qt::LeftButton);
      });
    this->Timer.start();
  }
  int count() const { return this->Count; }
  const QString& text() const { return this->Text; }

private:
  QTimer Timer;
  int Count = 0;
  QString Text;
};

// Picks `path` in the next File > Open dialog (Qt's own dialog, the widget): types it in the
// file name box and presses Open once the dialog reads it (bendertest::TypeFileName).
class OpenDialogAnswer
{
public:
  explicit OpenDialogAnswer(const QString& path)
  {
    QCoreApplication::setAttribute(Qt::AA_DontUseNativeDialogs, true);
    this->Timer.setInterval(30);
    QObject::connect(&this->Timer,
      &QTimer::timeout,
      [this, path]()
      {
        auto* dialog = VisibleTopLevel<QFileDialog>();
        // Answered once the dialog reads the name typed (on a later tick otherwise).
        if (!dialog || !bendertest::TypeFileName(*dialog, path))
          return;
        ++this->Count;
        QMetaObject::invokeMethod(dialog, "accept"); // as the Open button does
      });
    this->Timer.start();
  }
  /// The dialogs answered: one per Ctrl+O.
  int count() const { return this->Count; }

private:
  QTimer Timer;
  int Count = 0;
};

// A key typed on the window, as the user does once it is the active window again (after a
// dialog, the window manager gives it back the focus).
bool TypeOnWindow(MainWindow& window, Qt::Key key, Qt::KeyboardModifiers modifiers)
{
  window.activateWindow();
  if (!QTest::qWaitForWindowActive(&window))
    return false;
  QTest::keyClick(&window, key, modifiers);
  return true;
}

// A tube along x, 60 mm long, its ribbon placed along the middle third.
bender::RibbonSpec TubeRibbon()
{
  bender::RibbonSpec ribbon;
  ribbon.start.position = { 20, 0, 0 };
  ribbon.end.position = { 40, 0, 0 };
  return ribbon;
}

// The ribbon from x = 20 to the open end (x = 60) of the tube of 0 to 60: its bends turn the
// tube's end whole and pass the lumen guard (one ending mid-tube shears the tube beyond it, a
// waist the guard holds).
bender::RibbonSpec OpenEndRibbon()
{
  bender::RibbonSpec ribbon = TubeRibbon();
  ribbon.end.position = { 60, 0, 0 };
  return ribbon;
}

} // namespace

class SessionAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;

  // A window on a tube bent by one warp, not saved (autosaved in `folder`).
  std::unique_ptr<MainWindow> bentTubeWindow(const QString& folder, bool interactive)
  {
    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(folder));
    if (!bendertest::ShowTestWindow(*window, true))
      return nullptr;
    bender::BenderSession& session = window->session();
    if (!session.SetSurface(bendertest::Tube(0, 60, 3), "patient A tube"))
      return nullptr;
    // The lumen guard on (its default), the bend to the open end passes it.
    if (!session.GetLumenGuard().enabled)
      return nullptr;
    bender::WarpParameters parameters = session.GetParameters();
    parameters.radius = 6;
    session.SetParameters(parameters);
    window->bendPanel()->setParameters(parameters);
    window->gesture()->showRibbon(OpenEndRibbon(), 3.0);
    if (!window->grab())
      return nullptr;
    window->setRibbon(bendertest::Swung(OpenEndRibbon(), 25));
    if (!window->release() || !window->waitUntilIdle(60000) || session.GetHistoryPosition() != 1)
      return nullptr;
    window->files()->setInteractive(interactive);
    return window;
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
    QCoreApplication::setOrganizationName("BenderSessionTest");
    QSettings().clear();
  }

  void cleanupTestCase() { QSettings().clear(); }

  void aFailedOpenChangesNothing()
  {
    // Make warps -> Ctrl+O a truncated STL -> (Save changes? -> Discard) -> the error, the
    // warps still there -> Ctrl+Q asks, the autosave stays.
    QTemporaryDir folder;
    const QString autosave = folder.filePath("autosave.bender-session.json");
    auto window = this->bentTubeWindow(folder.path(), true);
    QVERIFY(window);
    bender::BenderSession& session = window->session();
    QVERIFY(session.HasUnsavedChanges());
    QVERIFY(QFileInfo::exists(autosave));
    const QByteArray autosaved = ReadAll(autosave);
    const auto bent = Copy(session.GetSurface());

    const QString whole = folder.filePath("whole.stl");
    bender::WriteMesh(bendertest::Tube(0, 80, 4), whole.toStdString());
    const QString truncated = folder.filePath("truncated.stl");
    QVERIFY(QFile::copy(whole, truncated));
    QFile cut(truncated);
    QVERIFY(cut.resize(cut.size() - 120));

    {
      OpenDialogAnswer choose(truncated);
      SaveChangesAnswer discard(QMessageBox::Discard);
      QVERIFY(TypeOnWindow(*window, Qt::Key_O, Qt::ControlModifier));
      QTRY_COMPARE(choose.count(), 1);
      QVERIFY(window->waitUntilIdle(60000));
      // Read first: a file that cannot be read is not asked about.
      QCOMPARE(discard.count(), 0);
    }
    QVERIFY2(window->statusLabel()->text().contains("truncated"),
      qPrintable(window->statusLabel()->text()));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QCOMPARE(MaxDifference(session.GetSurface(), bent), 0.0);
    QVERIFY(session.HasUnsavedChanges());
    QCOMPARE(ReadAll(autosave), autosaved);
    QVERIFY(window->actions()->Undo->isEnabled());

    // A readable mesh is asked about once read: Cancel keeps everything.
    {
      OpenDialogAnswer choose(whole);
      SaveChangesAnswer cancel(QMessageBox::Cancel);
      QVERIFY(TypeOnWindow(*window, Qt::Key_O, Qt::ControlModifier));
      QTRY_COMPARE(choose.count(), 1);
      QVERIFY(window->waitUntilIdle(60000));
      QCOMPARE(cancel.count(), 1);
      QVERIFY2(cancel.text().contains("not saved"), qPrintable(cancel.text()));
    }
    QVERIFY2(window->statusLabel()->text().contains("not opened"),
      qPrintable(window->statusLabel()->text()));
    QCOMPARE(session.GetSurfaceName(), std::string("patient A tube"));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QVERIFY(session.HasUnsavedChanges());
    QCOMPARE(ReadAll(autosave), autosaved);
    QVERIFY(!window->isBusy());

    // Ctrl+Q asks (the warps are unsaved): Cancel keeps the window and the autosave.
    {
      SaveChangesAnswer cancel(QMessageBox::Cancel);
      QVERIFY(TypeOnWindow(*window, Qt::Key_Q, Qt::ControlModifier));
      QTRY_COMPARE(cancel.count(), 1);
    }
    QVERIFY(window->isVisible());
    QVERIFY(QFileInfo::exists(autosave));

    // Ctrl+O the readable mesh and Discard: the new surface replaces the work, nothing unsaved.
    {
      OpenDialogAnswer choose(whole);
      SaveChangesAnswer discard(QMessageBox::Discard);
      QVERIFY(TypeOnWindow(*window, Qt::Key_O, Qt::ControlModifier));
      QTRY_COMPARE(choose.count(), 1);
      QVERIFY(window->waitUntilIdle(60000));
      QCOMPARE(discard.count(), 1);
    }
    QCOMPARE(session.GetSurfaceName(), std::string("whole.stl"));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(0));
    QVERIFY(!session.HasUnsavedChanges());
    QVERIFY(!window->ribbonWidget()->GetEnabled());
    window->files()->setInteractive(false);
    window->close();
  }

  void anotherPatientsVolumeClosesTheSurface()
  {
    QTemporaryDir folder;
    const QString autosave = folder.filePath("autosave.bender-session.json");
    auto window = this->bentTubeWindow(folder.path(), true);
    QVERIFY(window);
    bender::BenderSession& session = window->session();
    QVERIFY(window->waitForCenterlines(120000));
    QVERIFY(window->vessels()->vessels().HasCenterlines());
    QVERIFY(window->benderView()->centerlinesShown());
    auto* info = window->findChild<QLabel*>("dataInfo");
    QVERIFY(info);
    QVERIFY(info->text().contains("patient A tube"));

    // Patient B's volume (another file).
    bender::Volume volume;
    volume.geometry.size = { { 24, 20, 16 } };
    volume.geometry.spacing = { { 0.8, 0.8, 1.0 } };
    volume.voxels.assign(volume.geometry.VoxelCount(), 0.0f);
    for (std::size_t i = 0; i < volume.voxels.size(); ++i)
      volume.voxels[i] = static_cast<float>(i % 97);
    const QString nrrd = folder.filePath("patient-b.nrrd");
    bender::WriteVolume(volume, nrrd.toStdString());

    // Cancel: the volume is not opened, patient A's work stays as it was.
    {
      OpenDialogAnswer choose(nrrd);
      SaveChangesAnswer cancel(QMessageBox::Cancel);
      QVERIFY(TypeOnWindow(*window, Qt::Key_O, Qt::ControlModifier));
      QTRY_COMPARE(choose.count(), 1);
      QVERIFY(window->waitUntilIdle(60000));
      QCOMPARE(cancel.count(), 1);
    }
    QVERIFY(!window->segmentation().HasVolume());
    QVERIFY(session.HasSurface());
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    QVERIFY(session.HasUnsavedChanges());
    QVERIFY(QFileInfo::exists(autosave));

    // Discard: patient B's volume, and nothing of patient A left: no surface, warps, ribbon,
    // centerlines, autosave; the Data panel says so.
    {
      OpenDialogAnswer choose(nrrd);
      SaveChangesAnswer discard(QMessageBox::Discard);
      QVERIFY(TypeOnWindow(*window, Qt::Key_O, Qt::ControlModifier));
      QTRY_COMPARE(choose.count(), 1);
      QVERIFY(window->waitUntilIdle(60000));
      QCOMPARE(discard.count(), 1);
    }
    QVERIFY(window->segmentation().HasVolume());
    QVERIFY(!session.HasSurface());
    QCOMPARE(session.GetHistoryPosition(), std::size_t(0));
    QVERIFY(!session.GetRibbon().has_value());
    QVERIFY(!session.HasUnsavedChanges());
    QVERIFY(!window->actions()->Undo->isEnabled());
    QVERIFY(!window->ribbonWidget()->GetEnabled());
    QVERIFY(window->waitForCenterlines(60000));
    QVERIFY(!window->vessels()->vessels().HasCenterlines());
    QVERIFY(!window->benderView()->centerlinesShown());
    QVERIFY2(!info->text().contains("patient A"), qPrintable(info->text()));
    QVERIFY2(info->text().contains("patient-b"), qPrintable(info->text()));
    QVERIFY(!QFileInfo::exists(autosave));
    QVERIFY(window->saveScreenshot(this->artefact("session-another-patient.png")));

    // Nothing unsaved is left: Ctrl+Q closes without a question.
    {
      SaveChangesAnswer asked(QMessageBox::Cancel);
      QVERIFY(TypeOnWindow(*window, Qt::Key_Q, Qt::ControlModifier));
      QTRY_VERIFY(!window->isVisible());
      QCOMPARE(asked.count(), 0);
    }
  }

  void anExportInRasMetresOpensWhereItWas()
  {
    QTemporaryDir folder;
    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*window, false));
    bender::BenderSession& session = window->session();
    QVERIFY(session.SetSurface(bendertest::Tube(-20, 40, 5, 61, 32), "tube"));
    const auto original = Copy(session.GetSurface());
    ExportOptionsForm* form = window->findChild<ExportPanel*>()->form();
    form->Presets->setCurrentIndex(ExportOptionsForm::Custom);
    form->Patches->setCurrentIndex(0);
    form->Unit->setCurrentIndex(1);
    QVERIFY2(form->Unit->currentText().contains("(m"), qPrintable(form->Unit->currentText()));
    // RAS too: the tube lies from x = -20 to 40, so that x read back unturned moves its bounds.
    form->Frame->setCurrentIndex(1);
    QVERIFY2(form->Frame->currentText().startsWith("RAS"), qPrintable(form->Frame->currentText()));
    for (const char* format : { "stl", "obj", "ply", "vtp", "vtk", "off", "smesh" })
    {
      QVERIFY(session.SetSurface(original, "tube"));
      const int row = form->formatIndex(format);
      QVERIFY2(row >= 0, format);
      form->Formats->setCurrentIndex(row);
      form->Unit->setCurrentIndex(1);
      form->Frame->setCurrentIndex(1);
      // Capped (its patches named) for TetGen, which needs a closed surface; the others whole.
      form->Cap->setChecked(std::string(format) == "smesh");
      const QString path = folder.filePath(QString("tube-in-metres") + form->suffix());
      QVERIFY(window->exportSurface(path, true));
      QVERIFY(window->waitUntilIdle(120000));
      QVERIFY2(QFileInfo::exists(path), format);
      // Written in RAS metres, it opens where it was in LPS millimetres, saying so.
      QVERIFY(window->openFile(path));
      QVERIFY(window->waitUntilIdle(120000));
      QVERIFY2(session.GetSurfaceName() == QFileInfo(path).fileName().toStdString(),
        qPrintable(QString("%1: %2").arg(format).arg(window->statusLabel()->text())));
      QVERIFY2(BoundsDifference(session.GetSurface(), original) < 1e-3,
        qPrintable(QString("%1: %2 mm off")
                     .arg(format)
                     .arg(BoundsDifference(session.GetSurface(), original))));
      QVERIFY2(window->statusLabel()->text().contains("RAS metres"),
        qPrintable(window->statusLabel()->text()));
    }
    window->close();
  }

  // A window on a tube, its ribbon placed.
  std::unique_ptr<MainWindow> tubeWindow(const QString& folder)
  {
    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(folder));
    if (!bendertest::ShowTestWindow(*window, true) ||
      !window->session().SetSurface(bendertest::Tube(0, 60, 3), "tube"))
      return nullptr;
    window->gesture()->showRibbon(TubeRibbon(), 3.0);
    return window;
  }

  void theBendPanelSaysARibbonIsPlaced()
  {
    QTemporaryDir folder;
    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*window, true));
    QVERIFY(window->session().SetSurface(bendertest::Tube(0, 60, 3), "tube"));
    auto* state = window->bendPanel()->findChild<QLabel*>("bendState");
    QVERIFY(state);
    QVERIFY2(state->text().contains("place the ribbon"), qPrintable(state->text()));
    window->gesture()->showRibbon(TubeRibbon(), 3.0);
    QVERIFY(window->session().GetRibbon().has_value());
    QTRY_VERIFY2(!state->text().contains("place the ribbon"), qPrintable(state->text()));
    QVERIFY2(state->text().contains("placed"), qPrintable(state->text()));
    window->close();
  }

  void oneWarpIsOneWarp()
  {
    QTemporaryDir folder;
    auto window = this->tubeWindow(folder.path());
    QVERIFY(window);
    bender::BenderSession& session = window->session();
    QVERIFY(session.GetLumenGuard().enabled); // the bend to the open end passes it
    window->gesture()->showRibbon(OpenEndRibbon(), 3.0);
    bender::WarpParameters parameters = session.GetParameters();
    parameters.radius = 6;
    window->bendPanel()->setParameters(parameters);
    window->gesture()->applyParameters();
    QVERIFY(window->grab());
    window->setRibbon(bendertest::Swung(OpenEndRibbon(), 20));
    QVERIFY(window->release());
    QVERIFY(window->waitUntilIdle(60000));
    QCOMPARE(session.GetHistoryPosition(), std::size_t(1));
    auto* info = window->findChild<QLabel*>("dataInfo");
    auto* state = window->bendPanel()->findChild<QLabel*>("bendState");
    QTRY_VERIFY2(info->text().contains("1 warp committed"), qPrintable(info->text()));
    QVERIFY2(state->text().contains("1 warp committed"), qPrintable(state->text()));
    QVERIFY(session.SavePlan(folder.filePath("one.bender.json").toStdString()));
    QVERIFY2(window->statusLabel()->text().contains("(1 warp)"),
      qPrintable(window->statusLabel()->text()));
    for (const auto& message : session.GetMessages())
      QVERIFY2(message.text.find("1 warps") == std::string::npos, message.text.c_str());
    window->close();
  }

  void theRegionOutlineStaysOneSimpleCurveWhileDragging()
  {
    // G, then the end handle dragged round the ribbon's start with the mouse: the region's
    // outline (R = 10 mm around a 20 mm ribbon) is one closed curve that never crosses itself.
    QTemporaryDir folder;
    auto window = this->tubeWindow(folder.path());
    QVERIFY(window);
    bender::BenderSession& session = window->session();
    bender::WarpParameters parameters = session.GetParameters();
    parameters.radius = 10;
    window->bendPanel()->setParameters(parameters);
    window->gesture()->applyParameters();
    bendertest::Look(*window, { 30, 0, 0 }, { 0, 0, 1 }, 50);
    QVERIFY(window->grab());
    vtkBenderRibbonRepresentation* rep = window->ribbonWidget()->GetRibbonRepresentation();
    QCOMPARE(rep->GetRadius(), 10.0);
    const bender::Vec3 start = TubeRibbon().start.position;
    const bender::Vec3 end = TubeRibbon().end.position;
    QWidget* view = window->view();
    QPoint at = bendertest::Project(*window, end);
    QTest::mouseMove(view, at);
    QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, at);
    int checked = 0;
    for (int step = 1; step <= 9; ++step)
    {
      const double a = 10.0 * step * 3.14159265358979323846 / 180.0;
      at = bendertest::Project(*window, start + bender::Rotate({ 0, 0, 1 }, a, end - start));
      QMouseEvent move(QEvent::MouseMove, at, Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
      QApplication::sendEvent(view, &move);
      QCoreApplication::processEvents();
      window->render();
      if (!rep->GetValid())
        continue;
      const auto loops = bendertest::DisplayLoops(rep->GetRegionOutline(), window->renderer());
      QVERIFY2(bendertest::IsSimpleClosedCurve(loops),
        qPrintable(QString("%1 degrees: %2 loops, %3 crossings")
                     .arg(10 * step)
                     .arg(loops.size())
                     .arg(bendertest::Crossings(loops))));
      ++checked;
      if (step == 6)
        QVERIFY(window->saveScreenshot(this->artefact("session-region-outline.png")));
    }
    QVERIFY2(checked >= 6, qPrintable(QString::number(checked)));
    // The drag moved the ribbon's end.
    QVERIFY(bender::Distance(rep->GetRibbon().end.position, end) > 5.0);
    QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, at);
    session.CancelGrab("the outline was what was tested");
    window->close();
  }

  void theShortcutTableFitsWithoutScrollingSideways()
  {
    QTemporaryDir folder;
    auto window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*window, true));
    QVERIFY(TypeOnWindow(*window, Qt::Key_F1, Qt::NoModifier));
    QDialog* dialog = nullptr;
    QTRY_VERIFY((dialog = window->findChild<QDialog*>("shortcutsDialog")) && dialog->isVisible());
    auto* table = dialog->findChild<QTableWidget*>("shortcutsTable");
    QVERIFY(table);
    QCoreApplication::processEvents();
    QVERIFY2(table->horizontalHeader()->length() <= table->viewport()->width(),
      qPrintable(QString("%1 > %2")
                   .arg(table->horizontalHeader()->length())
                   .arg(table->viewport()->width())));
    QVERIFY(!table->horizontalScrollBar()->isVisible());
    const QRect screen = window->screen()->availableGeometry();
    QVERIFY(dialog->frameGeometry().width() <= screen.width());
    QVERIFY(dialog->frameGeometry().height() <= screen.height());
    QVERIFY(dialog->grab().save(this->artefact("session-shortcuts.png")));
    dialog->close();
    window->close();
  }
};

QTEST_MAIN(SessionAppTest)
#include "SessionAppTest.moc"
