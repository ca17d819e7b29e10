#ifndef ExportFlow_h
#define ExportFlow_h

#include "PrepareForCfd.h"

#include <QDialog>
#include <QObject>
#include <QString>

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <memory>
#include <utility>
#include <vector>

class vtkPolyData;

namespace bender
{
class BenderSession;
class SegmentationSession;
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
  /// Accepts unless the file is empty (then says so in the dialog) or the export would replace
  /// files that exist (the file, its sidecar, its per-patch files) and the user, asked (default
  /// No), does not want them replaced.
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
  /// Opens the export dialog (window-modal, not blocking; the Export action's slot) on
  /// defaultExportPath(). On Export it copies its options to the Export panel and exports.
  /// Deleted when closed.
  ExportDialog* openExportDialog();
  /// Where the dialog proposes to write: the folder of the data's file (the surface's, else the
  /// volume's it was segmented from; the user's documents, else home, for data made here such
  /// as the demo; the last export's folder when the same data was exported before), never the
  /// process's working folder; the name the data's, without spaces or parentheses, with
  /// "_export" and the format's extension ("demo_vessel_segmented_export.stl").
  QString defaultExportPath() const;
  /// The volume the surface may have been segmented from (for defaultExportPath).
  void setSegmentation(const bender::SegmentationSession* segmentation);
  /// The Export panel's "Prepare for CFD": the plan's step (bender::ApplyCfdStep) with the
  /// panel's options (the cuts where the ends' discs are) on a copy of the session's surface,
  /// as a job on the worker (progress and Cancel in the status bar; the window keeps working).
  /// On the GUI thread the result is committed as a step of the history
  /// (BenderSession::CommitCfdStep: undoable, saved in the plan with every end's cut, name and
  /// extension factor), its ends are listed in the panel and its caps shown labelled in the
  /// view; nothing is applied when the surface changed meanwhile or the job was cancelled.
  /// Pressed again on the surface it made, it starts again from the surface before (with the
  /// names, extensions and cuts as edited) and the new step replaces the old one. Problems go
  /// to the panel's report. Returns whether the job started.
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
    const bender::CfdStep& step,
    bool again,
    vtkPolyData* from,
    vtkMTimeType fromTime);
  /// Whether `surface` is the one the last Prepare made (as committed).
  bool showsPrepared(vtkPolyData* surface) const;
  /// The last Prepare's ends in the panel and its caps in the view.
  void showPreparedEnds();
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
  /// What identifies the data for the last export's folder (its files and name).
  QString dataKey() const;
  /// The folder and file stem proposed for the data's exports and plans (defaultExportPath).
  std::pair<QString, QString> dataFolderAndStem() const;
  /// `path`'s folder is proposed next time for the same data.
  void rememberFolder(const QString& path);

  const bender::SegmentationSession* Segmentation = nullptr;
  QString LastFolder;                  ///< where the last export went
  QString LastFolderData;              ///< the data it was of (dataKey)
  vtkPolyData* PreparedFrom = nullptr; ///< the history's surface before the last Prepare
  vtkPolyData* Prepared = nullptr;     ///< the session's surface it made (not owned)
  vtkMTimeType PreparedTime = 0;
  vtkSmartPointer<vtkPolyData> PreparedCenterlines; ///< those the last Prepare clipped by
  std::vector<bender::CfdEnd> PreparedEnds;         ///< the ends it made
  BenderView* View = nullptr;
  VesselController* Vessels = nullptr;
  CfdEndsOverlay* Overlay = nullptr;
  vtkSmartPointer<vtkPolyData> EndCenterlines; ///< a copy of those the listed ends come from
  vtkPolyData* EndsFor = nullptr;              ///< the surface they belong to (not owned)
  vtkMTimeType EndsForTime = 0;
};

#endif
