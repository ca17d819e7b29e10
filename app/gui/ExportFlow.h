#ifndef ExportFlow_h
#define ExportFlow_h

#include <QDialog>
#include <QObject>
#include <QString>

#include <vtkSmartPointer.h>
#include <vtkType.h>

class vtkPolyData;

namespace bender
{
class BenderSession;
}
class ExportOptionsForm;
class ExportPanel;
class MainActions;
class QLabel;
class QLineEdit;
class QWidget;
class WorkRunner;

/// The Ctrl+E export dialog: where (a file, with Browse...) and how (an ExportOptionsForm:
/// preset, format, caps, patches, frame, unit, sidecar), started from the Export panel's
/// choices. The file's extension follows the format.
class ExportDialog : public QDialog
{
  Q_OBJECT
public:
  ExportDialog(const ExportOptionsForm& start, const QString& path, QWidget* parent);
  QString path() const;
  void setPath(const QString& path);
  ExportOptionsForm* form() const { return this->Form; }
  /// Accepts unless the file is empty (then says so in the dialog).
  void accept() override;

private:
  void browse();
  void followFormat();

  QLineEdit* Path;
  ExportOptionsForm* Form;
  QLabel* Problem;
};

/// What leaves a window: Check, Export (the Ctrl+E dialog, then check, ask on problems, write)
/// and Save plan. The check and the export are session jobs on the window's worker; the report
/// goes to the Export panel.
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
  /// Opens the export dialog (window-modal, not blocking; the Export action's slot). On
  /// Export it copies its options to the Export panel and exports. Deleted when closed.
  ExportDialog* openExportDialog();
  /// The Export panel's "Prepare for CFD": runs bender::PrepareForCfd on the session's surface
  /// with the panel's options and makes the result the session's surface (a new start: the
  /// history is dropped), listing its ends in the panel. Pressed again on the surface it made,
  /// it starts again from the surface before (with the names and extensions as edited).
  /// Problems go to the panel's report. Returns whether the surface was prepared.
  bool prepareForCfd();

private:
  void askToExportAnyway(const QString& path, const QString& problems);

  bender::BenderSession& Session;
  WorkRunner* Worker;
  MainActions* Actions;
  ExportPanel* Panel;
  bool Interactive;
  QWidget* Window;
  QString LastPath;
  vtkSmartPointer<vtkPolyData> PreparedFrom; ///< the surface before the last preparation
  vtkPolyData* Prepared = nullptr;           ///< the session's surface it made (not owned)
  vtkMTimeType PreparedTime = 0;
};

#endif
