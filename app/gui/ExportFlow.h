#ifndef ExportFlow_h
#define ExportFlow_h

#include <QDialog>
#include <QObject>
#include <QString>

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <memory>

class vtkPolyData;

namespace bender
{
class BenderSession;
struct PrepareForCfdResult;
}
class BenderView;
class CfdEndsOverlay;
class ExportOptionsForm;
class ExportPanel;
class MainActions;
class QLabel;
class QLineEdit;
class QWidget;
class VesselController;
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
  /// The Export panel's "Prepare for CFD": runs bender::PrepareForCfd on a copy of the
  /// session's surface with the panel's options (the cuts where the ends' discs are, the
  /// centerlines the discs were placed on) as a job on the worker (progress and Cancel in the
  /// status bar; the window keeps working). On the GUI thread the result becomes the session's
  /// surface (a new start: the history is dropped), its ends are listed in the panel and its
  /// caps shown labelled in the view; nothing is applied when the surface changed meanwhile or
  /// the job was cancelled. Pressed again on the surface it made, it starts again from the
  /// surface before (with the names, extensions and cuts as edited). Problems go to the
  /// panel's report. Returns whether the job started.
  bool prepareForCfd();

  /// Shows the vessel ends in `view` (CfdEndsOverlay: a disc per end, draggable along its
  /// centerline, two-way synced with the panel's cut column) from the centerlines of
  /// `vessels`, while the Export panel is shown; after Prepare, the labelled caps.
  void attachView(BenderView* view, VesselController* vessels);
  CfdEndsOverlay* endsOverlay() const { return this->Overlay; }

private:
  void askToExportAnyway(const QString& path, const QString& problems);
  /// New centerlines: the ends of the committed surface listed and drawn (unless it is the
  /// prepared surface, whose caps stay shown).
  void listEnds();
  /// After a job: forgets the ends drawn for a surface that is no longer the session's.
  void followSurface();
  void applyPrepared(const std::shared_ptr<bender::PrepareForCfdResult>& result,
    const vtkSmartPointer<vtkPolyData>& source,
    const vtkSmartPointer<vtkPolyData>& centerlines,
    vtkPolyData* from,
    vtkMTimeType fromTime);
  /// The overlay drawn while the Export panel is shown: the caps after Prepare, the discs
  /// while the ends are to be clipped.
  void showOverlay();
  void renderView();

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
  vtkSmartPointer<vtkPolyData> PreparedCenterlines; ///< those the last preparation clipped by
  BenderView* View = nullptr;
  VesselController* Vessels = nullptr;
  CfdEndsOverlay* Overlay = nullptr;
  vtkSmartPointer<vtkPolyData> EndCenterlines; ///< a copy of those the listed ends come from
  vtkPolyData* EndsFor = nullptr;              ///< the surface they belong to (not owned)
  vtkMTimeType EndsForTime = 0;
};

#endif
