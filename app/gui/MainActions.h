#ifndef MainActions_h
#define MainActions_h

#include <QObject>

class QAction;
class QMenu;
class QMenuBar;
class QToolButton;
class QWidget;

/// The window's commands, one QAction each, shared by the menus, the panels' buttons and the
/// keyboard shortcuts (a button is a QToolButton showing its action, so that text, shortcut,
/// tooltip and enabled state are the same everywhere). The shortcuts are application-wide and do
/// not auto-repeat (but Undo/Redo). MainWindow and its controllers connect `triggered`.
class MainActions : public QObject
{
  Q_OBJECT
public:
  explicit MainActions(QWidget* window);

  /// File (with Open Recent), Edit, Bend, View menus.
  void addMenus(QMenuBar* bar);
  /// Puts `path` first in the recent files (QSettings "recentFiles", ten at most).
  void addRecentFile(const QString& path);

  QAction* Open;
  QAction* Demo;
  QAction* LoadPlan;
  QAction* SavePlan;
  QAction* Check;
  QAction* Export;
  QAction* Screenshot;
  QAction* Quit;
  QAction* Undo;
  QAction* Redo;
  QAction* PlaceRibbon;
  QAction* Grab;
  QAction* CancelBend;
  QAction* Segment;
  QAction* ResetCamera;
  QAction* ShowCenterline; ///< checkable, on by default

signals:
  void recentFileChosen(const QString& path);

private:
  void updateRecentMenu();
  QMenu* Recent = nullptr;
};

/// A full-width panel button for `action` (its text, tooltip, enabled state and shortcut).
QToolButton* ActionButton(QAction* action, QWidget* parent, const char* objectName);

#endif
