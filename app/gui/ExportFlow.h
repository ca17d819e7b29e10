#ifndef ExportFlow_h
#define ExportFlow_h

#include <QObject>
#include <QString>

namespace bender
{
class BenderSession;
}
class ExportPanel;
class MainActions;
class QWidget;
class WorkRunner;

/// What leaves a window: Check, Export (check, ask on problems, write) and Save plan. The check
/// and the export are session jobs on the window's worker; the report goes to the Export panel.
class ExportFlow : public QObject
{
  Q_OBJECT
public:
  /// `interactive`: ask before writing a surface whose check found problems (tests answer
  /// themselves through exportSurface's `proceedOnProblems`).
  ExportFlow(bender::BenderSession& session,
    WorkRunner* worker,
    MainActions* actions,
    ExportPanel* panel,
    bool interactive,
    QWidget* window);

  /// See MainWindow::exportSurface.
  bool exportSurface(const QString& path, bool proceedOnProblems = false);
  bool checkSurface();

private:
  void askToExportAnyway(const QString& path, const QString& problems);

  bender::BenderSession& Session;
  WorkRunner* Worker;
  MainActions* Actions;
  ExportPanel* Panel;
  bool Interactive;
  QWidget* Window;
};

#endif
