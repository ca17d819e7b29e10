#ifndef MainActions_h
#define MainActions_h

#include <QList>
#include <QObject>
#include <QStringList>

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

  /// File (with Open Recent), Edit, Bend, View, Help menus.
  void addMenus(QMenuBar* bar);
  /// Every command of the window that has a keyboard shortcut (the QActions of the window,
  /// MainActions' and any added later), in menu order, then the keys that are no actions
  /// (Space held, the slice views' wheel): rows of key, command, description.
  QList<QStringList> shortcutRows() const;
  /// The Help > Keyboard shortcuts dialog (a table of shortcutRows(); not modal).
  void showShortcuts();
  /// Puts `path` first in the recent files (QSettings "recentFiles", ten at most).
  void addRecentFile(const QString& path);

  QAction* Open;
  QAction* OpenDicomFolder; ///< a DICOM series chosen by its folder
  QAction* Demo;
  QAction* LoadPlan;
  QAction* SavePlan;
  QAction* Check;
  QAction* Export;
  QAction* RunFlow; ///< the Flow panel's run of the original and the current shape
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
  QAction* ShowOriginal;   ///< checkable, on by default: the original shape as a ghost
  /// The standard views: anterior, posterior, left, right, superior, inferior
  /// (BenderView::StandardView order).
  QAction* StandardViews[6];
  QAction* Shortcuts;
  QAction* About;

signals:
  void recentFileChosen(const QString& path);

private:
  void updateRecentMenu();
  QWidget* Window = nullptr;
  QMenu* Recent = nullptr;
  QList<QMenu*> Menus;
};

/// A full-width panel button for `action` (its text, tooltip, enabled state and shortcut).
QToolButton* ActionButton(QAction* action, QWidget* parent, const char* objectName);

#endif
