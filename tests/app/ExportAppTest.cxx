// The export side of the window (issue 11): the Ctrl+E dialog offers the preset "OpenFOAM (m,
// named solids)", caps, patches, frame, unit and the sidecar, and writes what it shows; named
// solids never turn a binary STL into ASCII silently; the TetGen preset writes a .smesh; --cap
// on a closed surface fails the export. Run under Xvfb (QT_QPA_PLATFORM=xcb); the dialog's
// screenshot is kept in test-artifacts/.
#include "AppTestUtilities.h"
#include "ExportFlow.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "MainWindow.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QSurfaceFormat>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include "PatchLabels.h"

class ExportAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;

  ExportOptionsForm* panelForm()
  {
    auto* panel = this->Window->findChild<ExportPanel*>();
    return panel ? panel->form() : nullptr;
  }

  // Opens the dialog with the window's Ctrl+E shortcut.
  ExportDialog* openDialog()
  {
    this->Window->activateWindow();
    QApplication::setActiveWindow(this->Window.get());
    if (!QTest::qWaitForWindowActive(this->Window.get()))
    {
      return nullptr;
    }
    QTest::keyClick(this->Window.get(), Qt::Key_E, Qt::ControlModifier);
    // The dialog opens window-modal, without blocking: wait for it to appear.
    ExportDialog* dialog = nullptr;
    for (int waited = 0; waited < 5000 && !dialog; waited += 20)
    {
      dialog = this->Window->findChild<ExportDialog*>("exportDialog");
      if (!dialog)
      {
        QTest::qWait(20);
      }
    }
    return dialog;
  }

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
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
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
    QCOMPARE(form->Formats->currentIndex(), int(ExportOptionsForm::StlAscii));
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
    form->Formats->setCurrentIndex(ExportOptionsForm::StlBinary);
    QVERIFY(form->note().isEmpty());
    form->Patches->setCurrentIndex(1);
    QCOMPARE(form->Formats->currentIndex(), int(ExportOptionsForm::StlAscii));
    QVERIFY2(form->note().contains("STL (ASCII)"), qPrintable(form->note()));
    form->Formats->setCurrentIndex(ExportOptionsForm::StlBinary);
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
    form->Formats->setCurrentIndex(ExportOptionsForm::Vtp);
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
