// Issue 22, items 1, 2 and 10, each path repeated as written on the real window (QTest events on
// the real widgets, under Xvfb):
//  1. Demo > Export > Prepare for CFD > Ctrl+E > preset "OpenFOAM (m, named solids)" > Export:
//     no bend, so no problem is found (the check compares with the prepared surface) and the
//     file is written; `bender-cli check` finds the written file clean too. With problems, the
//     status line claims no result while the question is open.
//  2. Prepare for CFD is a step of the history: Undo and Redo after it, Ctrl+S saves it in the
//     plan with its ends, names and extension factors, and `bender-cli warp` replays the saved
//     plan to the window's surface (unbent, and after a bend).
//  10. The export dialog proposes a folder and a name from the data (never the working folder,
//     no spaces or parentheses) and never replaces a file without asking (default No).
#include "AppTestUtilities.h"
#include "ExportFlow.h"
#include "ExportPanel.h"
#include "MainActions.h"
#include "MainWindow.h"

#include "ApplyPlan.h"
#include "DemoPipeline.h"
#include "LogicTestUtilities.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "PolyDataCopy.h"
#include "WarpPlanIO.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QProcess>
#include <QPushButton>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>
#include <QtTest>

#include <vtkAppendPolyData.h>
#include <vtkPolyData.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <functional>
#include <memory>

namespace
{
/// Same cells and the same points, exactly.
bool SameSurface(vtkPolyData* a, vtkPolyData* b)
{
  return a && b && a->GetNumberOfCells() == b->GetNumberOfCells() &&
    bender::test::MaxDifference(a, b) == 0.0;
}

/// Runs bender-cli with `arguments`; its exit code, output in `output`.
int RunCli(const QStringList& arguments, QString& output)
{
  QProcess cli;
  cli.start(BENDER_CLI_PATH, arguments);
  if (!cli.waitForFinished(300000))
  {
    output = "bender-cli did not finish";
    return -1;
  }
  output = QString::fromLocal8Bit(cli.readAllStandardOutput() + cli.readAllStandardError());
  return cli.exitCode();
}

/// Calls `answer` with the first modal widget of type T that opens within `milliseconds`
/// (a QMessageBox or a QFileDialog opened with exec()): from a timer, while it is open.
template<typename T>
void AnswerWhenOpen(std::function<void(T*)> answer, int milliseconds = 60000)
{
  auto* poll = new QTimer;
  auto waited = std::make_shared<int>(0);
  poll->setInterval(20);
  QObject::connect(poll,
    &QTimer::timeout,
    [poll, waited, answer, milliseconds]()
    {
      *waited += 20;
      if (auto* widget = qobject_cast<T*>(QApplication::activeModalWidget()))
      {
        poll->stop();
        poll->deleteLater();
        answer(widget);
      }
      else if (*waited > milliseconds)
      {
        poll->stop();
        poll->deleteLater();
      }
    });
  poll->start();
}
} // namespace

class CfdExportAppTest : public QObject
{
  Q_OBJECT

private:
  QTemporaryDir Folder;
  std::unique_ptr<MainWindow> Window;
  vtkSmartPointer<vtkPolyData> First;    // the demo's surface, before Prepare
  vtkSmartPointer<vtkPolyData> Prepared; // after Prepare
  QString Exported;                      // the OpenFOAM export of item 1

  ExportPanel* panel() { return this->Window->findChild<ExportPanel*>(); }

  QString report()
  {
    return this->panel()->findChild<QPlainTextEdit*>("checkReport")->toPlainText();
  }

  // Ctrl+E on the window; the dialog once it is open (window-modal, not blocking).
  ExportDialog* openDialog() { return bendertest::OpenExportDialog(*this->Window); }

  // Types `path` into the dialog's file field (all of it replaced).
  static void typePath(ExportDialog* dialog, const QString& path)
  {
    auto* edit = dialog->findChild<QLineEdit*>("exportPath");
    edit->setFocus();
    edit->selectAll();
    QTest::keyClick(edit, Qt::Key_Delete);
    QTest::keyClicks(edit, path);
  }

  // Presses the Prepare for CFD button of the Export panel and waits for the job.
  bool prepare()
  {
    bendertest::ShowPanel(*this->Window, this->panel());
    QApplication::processEvents();
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QTest::mouseClick(this->panel()->Prepare, Qt::LeftButton);
    return this->Window->waitUntilIdle(300000) && finished.count() == 1 &&
      finished.first().first().toBool();
  }

  // Ctrl+S, the plan's file typed into the (Qt) file dialog; waits until it is written.
  bool savePlan(const QString& path)
  {
    QCoreApplication::setAttribute(Qt::AA_DontUseNativeDialogs, true);
    AnswerWhenOpen<QFileDialog>(
      [path](QFileDialog* dialog)
      {
        bendertest::TypeFileName(*dialog, path);
        static_cast<QDialog*>(dialog)->accept(); // QFileDialog::accept, as Save does
      });
    this->Window->activateWindow();
    QTest::keyClick(this->Window.get(), Qt::Key_S, Qt::ControlModifier);
    for (int waited = 0; waited < 10000 && !QFileInfo::exists(path); waited += 20)
    {
      QTest::qWait(20);
    }
    return QFileInfo::exists(path);
  }

  // The first proposal for the demo, data made here: the user's documents (or home), never the
  // working folder; named after the data, without spaces or parentheses.
  void expectTheDemoProposal(const QString& path)
  {
    const QFileInfo proposed(path);
    QString documents = QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation);
    if (documents.isEmpty() || !QDir(documents).exists())
    {
      documents = QDir::homePath();
    }
    QCOMPARE(proposed.absolutePath(), QDir(documents).absolutePath());
    QVERIFY(proposed.absolutePath() != QDir::currentPath());
    QVERIFY2(proposed.fileName().startsWith("demo_vessel"), qPrintable(path));
    for (const QChar c : { QChar(' '), QChar('('), QChar(')') })
    {
      QVERIFY2(!proposed.fileName().contains(c), qPrintable(path));
    }
  }

  // `bender-cli warp FIRST PLAN OUT` on the demo's first surface: the window's surface?
  void expectTheCliReplaysTheWindow(const QString& plan, const QString& name)
  {
    const QString first = this->Folder.filePath(name + "-first.vtp");
    const QString out = this->Folder.filePath(name + "-replayed.vtp");
    bender::WriteMesh(this->First, first.toStdString());
    QString output;
    QCOMPARE(RunCli({ "warp", first, plan, out }, output), 0);
    QVERIFY2(output.contains("Prepare for CFD"), qPrintable(output));
    const vtkSmartPointer<vtkPolyData> replayed = bender::ReadMesh(out.toStdString());
    vtkPolyData* shown = this->Window->session().GetSurface();
    QVERIFY2(SameSurface(replayed, shown),
      qPrintable(QString("replayed %1 points, %2 cells; the window %3, %4")
                   .arg(replayed->GetNumberOfPoints())
                   .arg(replayed->GetNumberOfCells())
                   .arg(shown->GetNumberOfPoints())
                   .arg(shown->GetNumberOfCells())));
    const auto labels = bender::ReadPatchLabels(replayed);
    const auto expected = bender::ReadPatchLabels(shown);
    QCOMPARE(labels.size(), expected.size());
    for (std::size_t k = 0; k < labels.size(); ++k)
    {
      QCOMPARE(labels[k].name, expected[k].name);
    }
  }

private slots:
  void initTestCase()
  {
    QVERIFY(this->Folder.isValid());
    this->Window = std::make_unique<MainWindow>(bendertest::TestWindowOptions(this->Folder.path()));
    QVERIFY(bendertest::ShowTestWindow(*this->Window, true));
    this->Window->actions()->Demo->trigger();
    QVERIFY(this->Window->waitUntilIdle(300000));
    QVERIFY(this->Window->waitForCenterlines(300000));
    this->First = bender::DeepCopyOf(this->Window->session().GetSurface());
  }

  void cleanupTestCase()
  {
    this->Window->close();
    this->Window.reset();
  }

  // Item 1, as written.
  void aPreparedVesselExportsForOpenFoamWithoutAFalseAlarm()
  {
    QVERIFY2(this->prepare(), qPrintable(this->report()));
    this->Prepared = bender::DeepCopyOf(this->Window->session().GetSurface());
    QCOMPARE(bender::ReadPatchLabels(this->Prepared).size(), std::size_t(4));
    ExportDialog* dialog = this->openDialog();
    QVERIFY(dialog);
    this->expectTheDemoProposal(dialog->path());
    auto* presets = dialog->form()->Presets;
    presets->setFocus();
    presets->setCurrentIndex(ExportOptionsForm::OpenFoam);
    QCOMPARE(presets->currentText(), QString("OpenFOAM (m, named solids)"));
    this->Exported = this->Folder.filePath("demo_cfd.stl");
    typePath(dialog, this->Exported);
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QTest::mouseClick(dialog->findChild<QPushButton*>("exportOk"), Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(300000));
    QCOMPARE(finished.count(), 1);
    QVERIFY2(finished.first().first().toBool(), qPrintable(this->report()));
    QVERIFY2(this->report().startsWith("demo_cfd.stl: clean") &&
        this->report().contains("flipped triangles since before the warp 0"),
      qPrintable(this->report()));
    QVERIFY(QFileInfo(this->Exported).size() > 1000);
    QVERIFY2(!this->Window->statusLabel()->text().contains("not written"),
      qPrintable(this->Window->statusLabel()->text()));
    // The command line agrees on the written file.
    QString output;
    QCOMPARE(RunCli({ "check", this->Exported }, output), 0);
    QVERIFY2(output.contains("clean"), qPrintable(output));
  }

  // Item 2, as written: the history and the plan keep the step.
  void prepareIsAStepOfTheHistoryAndThePlan()
  {
    bender::BenderSession& session = this->Window->session();
    MainActions* actions = this->Window->actions();
    QVERIFY(SameSurface(session.GetSurface(), this->Prepared));
    QVERIFY(actions->Undo->isEnabled());
    // The Data panel counts warps, not history steps: Prepare is named, not counted as a warp.
    auto* info = this->Window->findChild<QLabel*>("dataInfo");
    QTRY_VERIFY2(
      info->text().contains("0 warps committed, prepared for CFD"), qPrintable(info->text()));
    const QString plan = this->Folder.filePath("prepared.bender.json");
    QVERIFY(this->savePlan(plan));
    QVERIFY2(this->Window->statusLabel()->text().contains("Prepare for CFD"),
      qPrintable(this->Window->statusLabel()->text()));
    const bender::WarpPlan saved = bender::ReadWarpPlan(plan.toStdString());
    QCOMPARE(saved.warps.size(), std::size_t(0));
    QCOMPARE(saved.cfdSteps.size(), std::size_t(1));
    const bender::CfdStep& step = saved.cfdSteps.front();
    QVERIFY(step.clip && step.cap);
    QCOMPARE(step.ends.size(), std::size_t(3));
    QCOMPARE(step.names.size(), std::size_t(3));
    QCOMPARE(step.extensionFactors.size(), std::size_t(3));
    this->expectTheCliReplaysTheWindow(plan, "unbent");

    // Ctrl+Z: the surface before Prepare, exactly; Ctrl+Shift+Z: the prepared one again.
    this->Window->activateWindow();
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier);
    QApplication::processEvents();
    QVERIFY(SameSurface(session.GetSurface(), this->First));
    QVERIFY(!actions->Undo->isEnabled());
    QVERIFY(actions->Redo->isEnabled());
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QApplication::processEvents();
    QVERIFY(SameSurface(session.GetSurface(), this->Prepared));

    // Undo, bend (the demo plan's warp), Prepare: the plan has the warp, then the step, and
    // the command line replays both to the window's surface.
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier);
    QApplication::processEvents();
    const bender::WarpPlan demo = bender::ReadWarpPlan(bender::DemoPlanPath());
    QVERIFY(session.ApplyWarp(demo.warps.front()));
    QVERIFY(this->Window->waitUntilIdle(300000));
    QVERIFY(this->Window->waitForCenterlines(300000));
    QVERIFY2(this->prepare(), qPrintable(this->report()));
    const QString bentPlan = this->Folder.filePath("bent.bender.json");
    QVERIFY(this->savePlan(bentPlan));
    const bender::WarpPlan both = bender::ReadWarpPlan(bentPlan.toStdString());
    QCOMPARE(both.warps.size(), std::size_t(1));
    QCOMPARE(both.cfdSteps.size(), std::size_t(1));
    QCOMPARE(both.cfdSteps.front().afterWarps, std::size_t(1));
    this->expectTheCliReplaysTheWindow(bentPlan, "bent");
    // Undo: the bent surface and its warp, before the step.
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier);
    QApplication::processEvents();
    QCOMPARE(session.GetPlan().warps.size(), std::size_t(1));
    QVERIFY(session.GetPlan().cfdSteps.empty());
    QVERIFY(SameSurface(session.GetSurface(), bender::ApplyPlan(this->First, demo).steps.front()));
  }

  // Item 10, as written.
  void theExportDialogProposesTheDataAndNeverOverwritesSilently()
  {
    // The prepared surface again (item 2 undid it), for the OpenFOAM preset's caps.
    this->Window->activateWindow();
    QTest::keyClick(this->Window.get(), Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QApplication::processEvents();
    QVERIFY(this->Window->session().GetCurrentCfdStep());
    // After item 1's export: the same data's last folder, the data's name (not the last file's).
    ExportDialog* dialog = this->openDialog();
    QVERIFY(dialog);
    QCOMPARE(QFileInfo(dialog->path()).absolutePath(), QFileInfo(this->Exported).absolutePath());
    QVERIFY2(
      QFileInfo(dialog->path()).fileName().startsWith("demo_vessel"), qPrintable(dialog->path()));

    // An existing file: asked, No by default (Enter), and nothing is written.
    const QDateTime written = QFileInfo(this->Exported).lastModified();
    QFile before(this->Exported);
    QVERIFY(before.open(QIODevice::ReadOnly));
    const QByteArray content = before.readAll();
    before.close();
    dialog->form()->Presets->setCurrentIndex(ExportOptionsForm::OpenFoam);
    typePath(dialog, this->Exported);
    QString question;
    QMessageBox::StandardButton defaultButton = QMessageBox::NoButton;
    AnswerWhenOpen<QMessageBox>(
      [&](QMessageBox* box)
      {
        question = box->text();
        defaultButton = box->standardButton(box->defaultButton());
        QTest::keyClick(box, Qt::Key_Return);
      });
    QTest::mouseClick(dialog->findChild<QPushButton*>("exportOk"), Qt::LeftButton);
    QVERIFY2(question.contains("demo_cfd.stl") && question.contains("demo_cfd.patches.json"),
      qPrintable(question));
    QCOMPARE(defaultButton, QMessageBox::No);
    QVERIFY(dialog->isVisible());
    QVERIFY(!this->Window->isBusy());
    QTest::qWait(200);
    QCOMPARE(QFileInfo(this->Exported).lastModified(), written);
    QFile after(this->Exported);
    QVERIFY(after.open(QIODevice::ReadOnly));
    QCOMPARE(after.readAll(), content);

    // Yes replaces it.
    AnswerWhenOpen<QMessageBox>(
      [](QMessageBox* box) { QTest::mouseClick(box->button(QMessageBox::Yes), Qt::LeftButton); });
    QSignalSpy finished(this->Window.get(), &MainWindow::workFinished);
    QTest::mouseClick(dialog->findChild<QPushButton*>("exportOk"), Qt::LeftButton);
    QVERIFY(this->Window->waitUntilIdle(300000));
    QCOMPARE(finished.count(), 1);
    QVERIFY2(finished.first().first().toBool(), qPrintable(this->report()));

    // A surface opened from a file: its folder, its name made a file name.
    const QString data = this->Folder.filePath("data folder");
    QVERIFY(QDir().mkpath(data));
    const QString mesh = data + "/patient 7 (left).vtp";
    bender::WriteMesh(bendertest::Tube(-20, 20, 5), mesh.toStdString());
    QVERIFY(this->Window->session().LoadSurface(mesh.toStdString()));
    dialog = this->openDialog();
    QVERIFY(dialog);
    QCOMPARE(QFileInfo(dialog->path()).absolutePath(), QFileInfo(data).absoluteFilePath());
    QVERIFY2(QFileInfo(dialog->path()).fileName().startsWith("patient_7_left_export."),
      qPrintable(dialog->path()));
    dialog->reject();
  }

  // Item 1, the status line: while the export's question is open, no result is claimed.
  void theStatusClaimsNoResultWhileTheQuestionIsOpen()
  {
    MainWindowOptions options = bendertest::TestWindowOptions(this->Folder.path() + "/asking");
    options.interactive = true;
    QVERIFY(QDir().mkpath(this->Folder.path() + "/asking"));
    MainWindow window(options);
    QVERIFY(bendertest::ShowTestWindow(window, false));
    // Two tubes crossing each other: self-intersections, a problem for the check.
    vtkNew<vtkTransform> turn;
    turn->RotateZ(90);
    vtkNew<vtkTransformPolyDataFilter> turned;
    turned->SetInputData(bendertest::Tube(-20, 20, 5, 41, 32));
    turned->SetTransform(turn);
    vtkNew<vtkAppendPolyData> both;
    both->AddInputData(bendertest::Tube(-20, 20, 5, 41, 32));
    both->AddInputConnection(turned->GetOutputPort());
    both->Update();
    QVERIFY(window.session().SetSurface(both->GetOutput(), "crossing tubes"));
    const QString stl = this->Folder.filePath("crossing.stl");
    QString statusWhileAsked;
    bool asked = false;
    AnswerWhenOpen<QMessageBox>(
      [&](QMessageBox* box)
      {
        asked = true;
        statusWhileAsked = window.statusLabel()->text();
        QTest::mouseClick(box->button(QMessageBox::No), Qt::LeftButton);
      });
    QVERIFY(window.exportSurface(stl));
    QVERIFY(window.waitUntilIdle(300000));
    for (int waited = 0; waited < 10000 && !asked; waited += 20)
    {
      QTest::qWait(20);
    }
    QVERIFY(asked);
    QVERIFY2(!statusWhileAsked.contains("not written") && !statusWhileAsked.contains("Exported"),
      qPrintable(statusWhileAsked));
    QTest::qWait(50);
    QVERIFY2(window.statusLabel()->text().contains("Export not written"),
      qPrintable(window.statusLabel()->text()));
    QVERIFY(!QFileInfo::exists(stl));
    window.close();
  }
};

int main(int argc, char** argv)
{
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication application(argc, argv);
  QCoreApplication::setOrganizationName("BenderTests");
  QCoreApplication::setApplicationName("CfdExportAppTest");
  CfdExportAppTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "CfdExportAppTest.moc"
