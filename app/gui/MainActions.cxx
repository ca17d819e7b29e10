#include "MainActions.h"

#include <QAction>
#include <QFileInfo>
#include <QKeySequence>
#include <QMenu>
#include <QMenuBar>
#include <QSettings>
#include <QSizePolicy>
#include <QStringList>
#include <QToolButton>
#include <QWidget>

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
{
  this->Open = Make(window, "&Open mesh, volume or plan...", QKeySequence::Open, "openAction");
  this->Demo = Make(window, "Run the &demo", QKeySequence("Ctrl+D"), "demoAction");
  this->LoadPlan =
    Make(window, "&Load plan and replay...", QKeySequence("Ctrl+L"), "loadPlanAction");
  this->SavePlan = Make(window, "&Save plan...", QKeySequence::Save, "savePlanAction");
  this->Check = Make(window, "&Check the surface", QKeySequence(), "checkAction");
  this->Export = Make(window, "&Export surface...", QKeySequence("Ctrl+E"), "exportAction");
  this->Screenshot = Make(window, "Screens&hot...", QKeySequence("F12"), "screenshotAction");
  this->Quit = Make(window, "&Quit", QKeySequence::Quit, "quitAction");
  this->Undo = Make(window, "&Undo warp", QKeySequence("Ctrl+Z"), "undoAction");
  this->Redo = Make(window, "&Redo warp", QKeySequence("Ctrl+Shift+Z"), "redoAction");
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
  this->Recent = file->addMenu("Open &Recent");
  this->updateRecentMenu();
  file->addAction(this->Demo);
  file->addSeparator();
  file->addAction(this->LoadPlan);
  file->addAction(this->SavePlan);
  file->addAction(this->Check);
  file->addAction(this->Export);
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
  view->addAction(this->ShowCenterline);
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
