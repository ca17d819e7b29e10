#include "MainActions.h"

#include <QAction>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFileInfo>
#include <QHeaderView>
#include <QKeySequence>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QScreen>
#include <QScrollBar>
#include <QSettings>
#include <QSizePolicy>
#include <QStringList>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>
#include <QWidget>

#include <algorithm>

namespace
{
QAction* Make(QWidget* window, const QString& text, const QKeySequence& shortcut, const char* name)
{
  auto* action = new QAction(text, window);
  action->setObjectName(name);
  action->setShortcut(shortcut);
  // Shortcuts work wherever the focus is (the 3D view, a panel's button, a floating panel);
  // a text field being typed in keeps its letters (it takes the shortcut override). A held key
  // triggers once: G held must not grab, release and grab again.
  action->setShortcutContext(Qt::ApplicationShortcut);
  action->setAutoRepeat(false);
  window->addAction(action);
  return action;
}
}

MainActions::MainActions(QWidget* window)
  : QObject(window)
  , Window(window)
{
  this->Open = Make(window, "&Open mesh, volume or plan...", QKeySequence::Open, "openAction");
  this->OpenDicomFolder =
    Make(window, "Open DICOM &folder...", QKeySequence("Ctrl+Shift+D"), "openDicomFolderAction");
  this->Demo = Make(window, "Run the &demo", QKeySequence("Ctrl+D"), "demoAction");
  this->LoadPlan =
    Make(window, "&Load plan and replay...", QKeySequence("Ctrl+L"), "loadPlanAction");
  this->SavePlan = Make(window, "&Save plan...", QKeySequence::Save, "savePlanAction");
  this->Check = Make(window, "&Check the surface", QKeySequence(), "checkAction");
  this->Export = Make(window, "&Export surface...", QKeySequence("Ctrl+E"), "exportAction");
  this->RunFlow = Make(
    window, "Run &flow for the original and the current shape", QKeySequence(), "runFlowAction");
  this->Screenshot = Make(window, "Screens&hot...", QKeySequence("F12"), "screenshotAction");
  this->Quit = Make(window, "&Quit", QKeySequence::Quit, "quitAction");
  this->Undo = Make(window, "&Undo", QKeySequence("Ctrl+Z"), "undoAction");
  this->Redo = Make(window, "&Redo", QKeySequence("Ctrl+Shift+Z"), "redoAction");
  this->PlaceRibbon = Make(window, "&Place ribbon on surface", QKeySequence("P"), "placeAction");
  this->Grab = Make(window, "&Grab / release", QKeySequence("G"), "grabAction");
  this->CancelBend = Make(window, "&Cancel bend", QKeySequence("Esc"), "cancelBendAction");
  this->Segment = Make(window, "&Segment the loaded volume", QKeySequence(), "segmentAction");
  this->ResetCamera = Make(window, "&Reset camera", QKeySequence("Ctrl+R"), "resetCameraAction");
  this->ShowCenterline =
    Make(window, "Show &centerline", QKeySequence("Ctrl+Shift+C"), "showCenterlineAction");
  this->ShowCenterline->setCheckable(true);
  this->ShowCenterline->setChecked(true);
  this->ShowCenterline->setToolTip("The vessel's centerline inside the surface (the surface is "
                                   "drawn translucent while it is shown)");
  this->ShowOriginal =
    Make(window, "Show &original shape", QKeySequence("Ctrl+Shift+O"), "showOriginalAction");
  this->ShowOriginal->setCheckable(true);
  this->ShowOriginal->setChecked(true);
  this->ShowOriginal->setToolTip(
    "The surface before any warp, drawn as a faint ghost behind the bent surface");
  const char* views[6][4] = {
    { "&Anterior view", "Ctrl+1", "viewAnteriorAction", "Look at the patient from the front" },
    { "&Posterior view", "Ctrl+2", "viewPosteriorAction", "Look from behind" },
    { "&Left view", "Ctrl+3", "viewLeftAction", "Look from the patient's left side" },
    { "&Right view", "Ctrl+4", "viewRightAction", "Look from the patient's right side" },
    { "&Superior view", "Ctrl+5", "viewSuperiorAction", "Look down from the head (anterior up)" },
    { "&Inferior view", "Ctrl+6", "viewInferiorAction", "Look up from the feet (anterior up)" }
  };
  for (int v = 0; v < 6; ++v)
  {
    this->StandardViews[v] = Make(window, views[v][0], QKeySequence(views[v][1]), views[v][2]);
    this->StandardViews[v]->setToolTip(
      QString(views[v][3]) + ", framing the surface (LPS: the marker's letters)");
  }
  this->Shortcuts = Make(window, "&Keyboard shortcuts", QKeySequence("F1"), "shortcutsAction");
  this->Shortcuts->setToolTip("The list of every shortcut of the window");
  this->About = Make(window, "&About Bender", QKeySequence(), "aboutAction");
  this->About->setToolTip("What Bender is and where its documentation lies");

  // Every command says what it does (menus show it in the status tip, buttons as a tooltip).
  this->Open->setToolTip("Open a surface mesh (STL, OBJ, PLY, VTP, VTK, OFF), a volume (NRRD, "
                         "NIfTI, MHA, VTI, a DICOM folder), a plan or a saved session");
  this->OpenDicomFolder->setToolTip("Open the DICOM series of a folder as a volume (a folder "
                                    "with several series: the largest, and the status bar says "
                                    "which)");
  this->Demo->setToolTip(
    "Segment the built-in MRA-like demo volume and place a ribbon on a branch, ready to bend");
  this->LoadPlan->setToolTip("Load a .bender.json plan and replay its warps onto the surface");
  this->SavePlan->setToolTip("Save the committed warps as a .bender.json plan");
  this->Check->setToolTip("Check the surface: watertight, manifold, orientation, degenerate "
                          "and self-intersecting triangles, flips against the original");
  this->Export->setToolTip("Check, then export the surface for CFD (STL, VTP, PLY, OBJ)");
  this->RunFlow->setToolTip("Solve the flow (OpenFOAM) of the original vessel and of the current "
                            "shape, prepared for CFD alike, and compare them (Flow panel)");
  this->Screenshot->setToolTip("Save the window as a PNG image");
  this->Quit->setToolTip("Close Bender");
  this->Undo->setToolTip(
    "Undo the last step, a committed warp or Prepare for CFD (exact coordinates restored)");
  this->Redo->setToolTip("Redo the step undone last");
  this->CancelBend->setToolTip("Cancel the bend in progress; the committed shape stays");
  this->Segment->setToolTip(
    "Segment the loaded volume with the Segment panel's settings and make its surface");
  this->ResetCamera->setToolTip(
    "Frame the surface from the front (anterior view), resetting the rotation");
  this->Undo->setAutoRepeat(true);
  this->Redo->setAutoRepeat(true);
  this->PlaceRibbon->setToolTip("Then click on the vessel: with its centerline, two clicks (the "
                                "ribbon's ends) place the ribbon on the centerline; without, "
                                "one click places a straight ribbon along its axis");
  this->Grab->setToolTip(
    "Capture the ribbon (G, or hold Space) and drag its handles; G again commits");
}

void MainActions::addMenus(QMenuBar* bar)
{
  QMenu* file = bar->addMenu("&File");
  file->addAction(this->Open);
  file->addAction(this->OpenDicomFolder);
  this->Recent = file->addMenu("Open &Recent");
  this->updateRecentMenu();
  file->addAction(this->Demo);
  file->addSeparator();
  file->addAction(this->LoadPlan);
  file->addAction(this->SavePlan);
  file->addAction(this->Check);
  file->addAction(this->Export);
  file->addAction(this->RunFlow);
  file->addAction(this->Screenshot);
  file->addSeparator();
  file->addAction(this->Quit);
  QMenu* edit = bar->addMenu("&Edit");
  edit->addAction(this->Undo);
  edit->addAction(this->Redo);
  QMenu* bend = bar->addMenu("&Bend");
  bend->addAction(this->Segment);
  bend->addAction(this->PlaceRibbon);
  bend->addAction(this->Grab);
  bend->addAction(this->CancelBend);
  QMenu* view = bar->addMenu("&View");
  view->addAction(this->ResetCamera);
  view->addSeparator();
  for (QAction* standard : this->StandardViews)
  {
    view->addAction(standard);
  }
  view->addSeparator();
  view->addAction(this->ShowCenterline);
  view->addAction(this->ShowOriginal);
  QMenu* help = bar->addMenu("&Help");
  help->addAction(this->Shortcuts);
  help->addAction(this->About);
  this->Menus = { file, edit, bend, view, help };
  for (QMenu* menu : this->Menus)
  {
    menu->setToolTipsVisible(true);
  }
  connect(this->Shortcuts, &QAction::triggered, this, &MainActions::showShortcuts);
  connect(this->About,
    &QAction::triggered,
    this,
    [this]()
    {
      QMessageBox::about(this->Window,
        "About Bender",
        "<b>Bender</b>: bend a vessel surface with a ribbon held by the mouse or by two "
        "trackers, undo, save the plan, export for CFD.<br><br>Press F1 for the keyboard "
        "shortcuts. Hover a handle of the ribbon to see what it does: blue spheres move the "
        "ends, green cones bend (tangents), magenta cubes twist.<br>Coordinates: LPS, mm.");
    });
}

QList<QStringList> MainActions::shortcutRows() const
{
  QList<QStringList> rows;
  QList<QAction*> seen;
  auto add = [&](QAction* action)
  {
    if (!action || seen.contains(action) || action->shortcut().isEmpty())
    {
      return;
    }
    seen.append(action);
    QString tip = action->toolTip();
    const QString text = action->text().remove('&').remove("...");
    if (tip.remove('&') == action->text().remove('&'))
    {
      tip.clear();
    }
    rows.append({ action->shortcut().toString(QKeySequence::NativeText), text, tip });
  };
  // Menu order first, then any other action of the window.
  for (QMenu* menu : this->Menus)
  {
    for (QAction* action : menu->actions())
    {
      add(action);
    }
  }
  if (this->Window)
  {
    for (QAction* action : this->Window->findChildren<QAction*>())
    {
      add(action);
    }
  }
  rows.append({ "Space (held)", "Grab while held", "Release (commit) on letting go" });
  rows.append({ "Mouse wheel, Up/Down",
    "Move the slice",
    "In a slice view, one voxel a step; the cursor moves with it" });
  rows.append({ "Left click or drag (slice view)",
    "Move the cursor",
    "The other slices and the 3D crosshair follow" });
  rows.append({ "Shift+left drag (slice view)", "Window/level", "Of the volume's slice" });
  rows.append({ "R (slice view)", "Frame the view", "The slice stays at the cursor" });
  rows.append({ "Shift+click (3D view)",
    "Move the cursor to the surface",
    "The slices follow; a Shift+drag pans the camera" });
  rows.append({ "Left drag",
    "Rotate the 3D view, or drag a ribbon handle",
    "Blue sphere: move an end; green cone: bend (tangent); magenta cube: twist" });
  return rows;
}

void MainActions::showShortcuts()
{
  auto* dialog = new QDialog(this->Window);
  dialog->setObjectName("shortcutsDialog");
  dialog->setWindowTitle("Bender: keyboard shortcuts");
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  auto* layout = new QVBoxLayout(dialog);
  const QList<QStringList> rows = this->shortcutRows();
  auto* table = new QTableWidget(rows.size(), 3, dialog);
  table->setObjectName("shortcutsTable");
  table->setHorizontalHeaderLabels({ "Key", "Command", "What it does" });
  table->verticalHeader()->hide();
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  for (int r = 0; r < rows.size(); ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      table->setItem(r, c, new QTableWidgetItem(rows[r].value(c)));
    }
  }
  // Sized to fit, never scrolled sideways: the key and command columns as wide as their text,
  // the explanations wrapped in a column of at most 420 px, the dialog as wide as the table
  // (within the screen) and as tall as the screen allows.
  table->setWordWrap(true);
  table->resizeColumnsToContents();
  table->setColumnWidth(2, std::min(table->columnWidth(2), 420));
  table->horizontalHeader()->setStretchLastSection(true);
  table->resizeRowsToContents();
  layout->addWidget(table);
  auto* close = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  connect(close, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  layout->addWidget(close);
  const QMargins margins = layout->contentsMargins();
  const int tableWidth = table->horizontalHeader()->length() + 2 * table->frameWidth() +
    table->verticalScrollBar()->sizeHint().width();
  const QRect screen = (this->Window && this->Window->screen())
    ? this->Window->screen()->availableGeometry()
    : QRect(0, 0, 1280, 900);
  const int rowsHeight = table->verticalHeader()->length() + table->horizontalHeader()->height() +
    2 * table->frameWidth();
  dialog->resize(std::min(tableWidth + margins.left() + margins.right(), screen.width() - 40),
    std::min(rowsHeight + close->sizeHint().height() + margins.top() + margins.bottom() +
        layout->spacing(),
      screen.height() - 80));
  dialog->show();
}

void MainActions::addRecentFile(const QString& path)
{
  QSettings settings;
  QStringList files = settings.value("recentFiles").toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  files.removeAll(absolute);
  files.prepend(absolute);
  while (files.size() > 10)
  {
    files.removeLast();
  }
  settings.setValue("recentFiles", files);
  this->updateRecentMenu();
}

void MainActions::updateRecentMenu()
{
  if (!this->Recent)
  {
    return;
  }
  this->Recent->clear();
  const QStringList files = QSettings().value("recentFiles").toStringList();
  for (const QString& file : files)
  {
    this->Recent
      ->addAction(
        QFileInfo(file).fileName(), this, [this, file]() { emit this->recentFileChosen(file); })
      ->setToolTip(file);
  }
  this->Recent->setEnabled(!files.isEmpty());
}

QToolButton* ActionButton(QAction* action, QWidget* parent, const char* objectName)
{
  auto* button = new QToolButton(parent);
  button->setDefaultAction(action);
  button->setObjectName(objectName);
  button->setToolButtonStyle(Qt::ToolButtonTextOnly);
  button->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
  return button;
}
