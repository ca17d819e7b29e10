#ifndef MainWindow_h
#define MainWindow_h

#include "BenderSession.h"
#include "DemoPipeline.h"
#include "TrackerSession.h"

#include <QFutureWatcher>
#include <QImage>
#include <QMainWindow>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <atomic>
#include <functional>
#include <memory>

class BendPanel;
class QAction;
class QDoubleSpinBox;
class QCheckBox;
class QComboBox;
class QLabel;
class QMenu;
class QPlainTextEdit;
class QProgressBar;
class QSplitter;
class QPushButton;
class QTabWidget;
class QTimer;
class QVTKOpenGLNativeWidget;
class SliceViews;
class TrackersPanel;
class vtkActor;
class vtkBenderRibbonWidget;
class vtkCallbackCommand;
class vtkGenericOpenGLRenderWindow;
class vtkImageData;
class vtkObject;
class vtkPolyDataMapper;
class vtkRenderer;

struct MainWindowOptions
{
  /// Where the session autosaves; empty: the user's application data folder.
  QString autosavePath;
  /// Offer recovery at start when an autosave is left from a crash (tests turn it off).
  bool offerRecovery = true;
  /// Ask before exporting a surface whose check found problems (tests answer themselves).
  bool interactive = true;
};

/// The Bender main window: the 3D view with the ribbon widget, slice views when a volume is
/// loaded, the Data / Segment / Bend / Trackers / Export panels, menus with recent files,
/// shortcuts, drag and drop, and a status bar showing the logic layer's messages. Long work
/// (reading, segmentation, checks) runs on a worker thread with progress and Cancel. The window
/// holds no algorithm: everything goes through bender::BenderSession.
class MainWindow : public QMainWindow
{
  Q_OBJECT
public:
  explicit MainWindow(const MainWindowOptions& options = {}, QWidget* parent = nullptr);
  ~MainWindow() override;

  bender::BenderSession& session() { return this->Session; }
  bender::TrackerSession& trackers() { return *this->Trackers; }
  vtkBenderRibbonWidget* ribbonWidget() { return this->RibbonWidget; }
  vtkRenderer* renderer() { return this->Renderer; }
  QVTKOpenGLNativeWidget* view() { return this->View; }
  BendPanel* bendPanel() { return this->Bend; }
  TrackersPanel* trackersPanel() { return this->TrackersUi; }
  QLabel* statusLabel() { return this->StatusText; }

  /// Opens a file by its kind: mesh (.stl .obj .ply .vtp .vtk .off), plan (.bender.json),
  /// session (.bender-session.json), volume (.nrrd .nhdr .nii .nii.gz .mha .mhd .vti or a
  /// folder). Meshes and volumes load on the worker; returns false when refused at once.
  bool openFile(const QString& path);
  /// Starts the built-in demo on the worker: MRA-like volume, segmentation, ribbon on a branch.
  void startDemo();
  /// True while the worker runs.
  bool isBusy() const;
  /// Waits (processing events) until the worker is idle; false on timeout.
  bool waitUntilIdle(int milliseconds);

  /// The gesture, as the buttons and keys do it.
  bool grab();
  bool release();
  /// Places a straight ribbon along the vessel at a model point (the "place ribbon" helper).
  bool placeRibbonAt(const double point[3]);
  /// True after "place ribbon" (P) until the next click on the surface.
  bool isPlacingRibbon() const { return this->PlacingRibbon; }
  /// Sets the ribbon of the widget (and moves the live warp when grabbed).
  void setRibbon(const bender::RibbonSpec& ribbon);

  /// Exports the committed surface after its check. With problems: asks when interactive,
  /// else goes on only when `proceedOnProblems`.
  bool exportSurface(const QString& path, bool proceedOnProblems = false);
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
  void workFinished(bool succeeded);

protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void keyReleaseEvent(QKeyEvent* event) override;
  void closeEvent(QCloseEvent* event) override;
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  using Finisher = std::function<void()>;
  using Work = std::function<Finisher(const bender::ProgressReporter&)>;

  void buildView();
  void buildPanels();
  void buildMenus();
  void runInBackground(const QString& title, Work work);
  void finishWork();
  void showMessage(const bender::LogicMessage& message);
  void refresh();
  void resetCamera();
  void addRecentFile(const QString& path);
  void updateRecentMenu();
  void applyParameters();
  void onRibbonInteraction();
  void onPickForPlacement();
  void alignTrackers();
  void offerRecovery();
  void segmentLoadedVolume();
  void runCheck();
  void showSlices(vtkImageData* volume, vtkImageData* mask);
  QString exportFilter() const;

  static void RibbonCallback(vtkObject*, unsigned long, void* clientData, void*);
  static void PickCallback(vtkObject*, unsigned long, void* clientData, void*);

  MainWindowOptions Options;
  bender::BenderSession Session;
  std::unique_ptr<bender::TrackerSession> Trackers;

  QVTKOpenGLNativeWidget* View = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> RenderWindow;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> SurfaceMapper;
  vtkNew<vtkActor> SurfaceActor;
  vtkNew<vtkBenderRibbonWidget> RibbonWidget;
  vtkNew<vtkCallbackCommand> RibbonObserver;
  vtkNew<vtkCallbackCommand> PickObserver;
  bool PlacingRibbon = false;
  int RenderSuppressed = 0; // > 0 while a caller renders itself after the session's change
  bool SpaceHeld = false;

  SliceViews* Slices = nullptr;
  QSplitter* Splitter = nullptr;
  QTabWidget* Panels = nullptr;
  BendPanel* Bend = nullptr;
  TrackersPanel* TrackersUi = nullptr;
  QTimer* TrackerTimer = nullptr;
  QDoubleSpinBox* ThresholdSpin = nullptr;
  QDoubleSpinBox* SmoothingSpin = nullptr;
  QComboBox* MethodCombo = nullptr;
  QComboBox* FormatCombo = nullptr;
  QComboBox* PatchesCombo = nullptr;
  QComboBox* FrameCombo = nullptr;
  QCheckBox* CapCheck = nullptr;
  QPlainTextEdit* CheckReport = nullptr;
  QLabel* DataInfo = nullptr;
  QLabel* StatusText = nullptr;
  QProgressBar* Progress = nullptr;
  QPushButton* CancelButton = nullptr;
  QMenu* RecentMenu = nullptr;
  QAction* UndoAction = nullptr;
  QAction* RedoAction = nullptr;

  QFutureWatcher<Finisher>* Watcher = nullptr;
  std::atomic<bool> CancelFlag{ false };
  bool WorkPending = false; // from runInBackground until its finisher has run
  std::unique_ptr<bender::Volume> LoadedVolume;
};

#endif
