#ifndef MainWindow_h
#define MainWindow_h

#include "BenderSession.h"
#include "SegmentationSession.h"
#include "TrackerSession.h"

#include <QImage>
#include <QMainWindow>

#include <functional>
#include <memory>

class AutosaveController;
class BendPanel;
class BenderView;
class DataPanel;
class ExportFlow;
class ExportPanel;
class FlowPanel;
class FileOpener;
class GestureController;
class MeasurementsPanel;
class MainActions;
class QLabel;
class QSplitter;
class QTabWidget;
class QVTKOpenGLNativeWidget;
class SegmentPanel;
class SliceViews;
class TrackersPanel;
class VesselController;
class vtkBenderRibbonWidget;
class vtkRenderer;
class WorkRunner;

struct MainWindowOptions
{
  /// Where the session autosaves; empty: the user's application data folder.
  QString autosavePath;
  /// Offer recovery at start when an autosave is left from a crash (tests turn it off).
  bool offerRecovery = true;
  /// Ask before exporting a surface whose check found problems (tests answer themselves).
  bool interactive = true;
  /// Called on the worker thread at the start of every background job (tests slow jobs down
  /// with it to see the window keep working).
  std::function<void(const bender::ProgressReporter&)> workHook;
  /// Called on the thread that writes a copy beside the autosave (the demo's volume, a mask)
  /// before it writes (tests hold the write to see the window keep working meanwhile).
  std::function<void()> autosaveCopyHook;
};

/// The Bender main window. It composes and holds no state of its own (its options aside): the
/// surface, the gesture, the history, the jobs and the autosave are bender::BenderSession's, the
/// volume and its segmentation bender::SegmentationSession's (a segmentation's plausibility
/// warning is its own result), the trackers bender::TrackerSession's, what is under way in the
/// window its parts'. It lays out the 3D view
/// (BenderView), the slice views, the Data / Segment / Bend / Trackers / Export panels, the menus
/// (MainActions, one set of actions shared by menus, buttons and application-wide shortcuts) and
/// the status bar, and hands the work to focused parts:
/// - WorkRunner: long work on a worker thread with progress and Cancel (the window keeps drawing);
/// - FileOpener: open by file kind (bender::ClassifyFile), drag and drop, demo, segmentation;
/// - AutosaveController: the window's part of every autosave, the recovery offered at start;
/// - GestureController: grab, release (a job), Space held, ribbon moves, place ribbon, keys,
///   the autosave of a ribbon once it rests;
/// - ExportFlow: check, export (asks on problems), save plan;
/// - VesselController: the centerlines of the committed surface (a background job after every
///   change of it), drawn in the view, and the Measurements panel;
/// - TrackersPanel: the tracker device, polled at the display rate (its stylus release goes
///   through the gesture's release job).
///
/// Adding a panel: write a QWidget class in app/gui that takes the window's MainActions (for
/// buttons) and shows the sessions' state in a `showState(...)`; create it in buildPanels()
/// (or call addPanel from outside) and call its showState from refresh().
class MainWindow : public QMainWindow
{
  Q_OBJECT
public:
  explicit MainWindow(const MainWindowOptions& options = {}, QWidget* parent = nullptr);
  ~MainWindow() override;

  bender::BenderSession& session() { return this->Session; }
  bender::SegmentationSession& segmentation() { return this->Segmentation; }
  bender::TrackerSession& trackers() { return *this->Trackers; }
  MainActions* actions() { return this->Actions; }
  GestureController* gesture() { return this->Gesture; }
  FileOpener* files() { return this->Files; }
  ExportFlow* exports() { return this->Exports; }
  /// The centerlines and the measurements (VesselController, MeasurementsPanel).
  VesselController* vessels() { return this->Vessels; }
  MeasurementsPanel* measurementsPanel() { return this->Measurements; }
  /// For tests and scripts: waits (processing events) until the centerlines of the committed
  /// surface have been computed (or failed); false on timeout.
  bool waitForCenterlines(int milliseconds);
  vtkBenderRibbonWidget* ribbonWidget();
  vtkRenderer* renderer();
  QVTKOpenGLNativeWidget* view();
  BendPanel* bendPanel() { return this->Bend; }
  TrackersPanel* trackersPanel() { return this->TrackersUi; }
  SegmentPanel* segmentPanel() { return this->Segment; }
  FlowPanel* flowPanel() { return this->Flow; }
  SliceViews* sliceViews() { return this->Slices; }
  BenderView* benderView() { return this->View; }
  QLabel* statusLabel() { return this->StatusText; }
  /// Adds a panel as a tab of the panel dock.
  void addPanel(QWidget* panel, const QString& title);

  /// Opens a file by its kind (bender::ClassifyFile): mesh (.stl .obj .ply .vtp .vtk .off),
  /// plan (.bender.json), session (.bender-session.json), volume (.nrrd .nhdr .nii .nii.gz
  /// .mha .mhd .vti or a folder). Everything but a plan's parsing runs on the worker; returns
  /// false when refused at once (unknown type, unreadable plan, busy).
  bool openFile(const QString& path);
  /// Starts the built-in demo on the worker: MRA-like volume, segmentation, ribbon on a branch.
  void startDemo();
  /// Segments the loaded volume on the worker with the Segment panel's settings.
  bool segmentVolume();
  /// True while the worker runs (until its result has been taken in).
  bool isBusy() const;
  /// For tests and scripts: waits (processing events) until the worker is idle; false on
  /// timeout. The window itself never waits.
  bool waitUntilIdle(int milliseconds);

  /// The gesture, as the buttons and keys do it (GestureController). release() starts the
  /// commit (exact warp, subdivision, autosave) on the worker and returns whether it started.
  bool grab();
  bool release();
  /// Places a straight ribbon along the vessel at a model point (the "place ribbon" helper).
  bool placeRibbonAt(const double point[3]);
  /// True after "place ribbon" (P) until the next click on the surface.
  bool isPlacingRibbon() const;
  /// Sets the ribbon of the widget (and moves the live warp when grabbed).
  void setRibbon(const bender::RibbonSpec& ribbon);

  /// Checks, then exports the committed surface, on the worker (ExportFlow). With problems:
  /// asks when interactive, else writes only when `proceedOnProblems`. Returns whether the job
  /// started; workFinished says whether the file was written.
  bool exportSurface(const QString& path, bool proceedOnProblems = false);
  /// Checks the committed surface on the worker and shows the report in the Export panel.
  bool checkSurface();
  /// The window's pixels (3D view included) and a PNG of them.
  QImage grabWindowImage();
  bool saveScreenshot(const QString& path);
  /// The 3D view alone, rendered by VTK.
  bool saveViewScreenshot(const QString& path);

  /// Connects the trackers as the panel says and starts polling at the display rate.
  bool connectTrackers();
  void disconnectTrackers();
  /// One poll of the trackers (the timer calls it; tests may too).
  void pollTrackers();

  void render();

signals:
  /// A background job ended; false when it failed or was cancelled.
  void workFinished(bool succeeded);

protected:
  void closeEvent(QCloseEvent* event) override;

private:
  void buildPanels();
  void connectActions();
  void showMessage(const bender::LogicMessage& message);
  void refresh();
  void showSlices();

  MainWindowOptions Options;
  bender::BenderSession Session;
  bender::SegmentationSession Segmentation;
  std::unique_ptr<bender::TrackerSession> Trackers;

  MainActions* Actions = nullptr;
  BenderView* View = nullptr;
  SliceViews* Slices = nullptr;
  QSplitter* Splitter = nullptr;
  QTabWidget* Panels = nullptr;
  DataPanel* Data = nullptr;
  SegmentPanel* Segment = nullptr;
  BendPanel* Bend = nullptr;
  TrackersPanel* TrackersUi = nullptr;
  ExportPanel* Export = nullptr;
  MeasurementsPanel* Measurements = nullptr;
  FlowPanel* Flow = nullptr;
  QLabel* StatusText = nullptr;

  WorkRunner* Worker = nullptr;
  GestureController* Gesture = nullptr;
  FileOpener* Files = nullptr;
  AutosaveController* Recovery = nullptr;
  ExportFlow* Exports = nullptr;
  VesselController* Vessels = nullptr;
};

#endif
