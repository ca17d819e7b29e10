#ifndef BenderView_h
#define BenderView_h

#include <QVTKOpenGLNativeWidget.h>

#include <vtkNew.h>

#include <functional>

class vtkActor;
class vtkAlgorithmOutput;
class vtkBenderRibbonWidget;
class vtkCallbackCommand;
class vtkGenericOpenGLRenderWindow;
class vtkObject;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;

/// The 3D view: the session's live surface (its output port, connected once: the pipeline
/// updates the mapper when the warp moves, nothing is copied or forced) and the ribbon widget.
/// Emits ribbonInteraction while a handle is dragged, and surfacePicked for a click on the
/// surface while picking is on ("place ribbon").
class BenderView : public QVTKOpenGLNativeWidget
{
  Q_OBJECT
public:
  explicit BenderView(vtkAlgorithmOutput* surface, QWidget* parent = nullptr);
  ~BenderView() override;

  vtkRenderer* renderer() const { return this->Renderer; }
  vtkActor* surfaceActor() const { return this->SurfaceActor; }
  /// The vessel centerlines (polylines) drawn inside the surface; null hides them. While they
  /// are shown, the surface is drawn translucent so that they can be seen through it.
  void setCenterlines(vtkPolyData* lines);
  void setCenterlinesVisible(bool visible);
  /// Replaces the drawn centerlines' data (the same lines carried by the live warp) without
  /// drawing a frame (the caller's interaction draws it).
  void moveCenterlines(vtkPolyData* lines);
  bool centerlinesShown() const;
  vtkBenderRibbonWidget* ribbonWidget() const { return this->RibbonWidget; }
  /// Draws a frame, unless inside quietly().
  void render();
  /// Runs `call` with render() doing nothing (the session's change callbacks during a widget
  /// interaction or a tracker poll): the caller draws one frame itself.
  void quietly(const std::function<void()>& call);
  void resetCamera();

  /// The next left click on the surface emits surfacePicked (else pickMissed) instead of
  /// rotating the camera.
  void setPicking(bool picking) { this->Picking = picking; }
  bool isPicking() const { return this->Picking; }

signals:
  void ribbonInteraction();
  void surfacePicked(double x, double y, double z);
  void pickMissed();

private:
  static void RibbonCallback(vtkObject*, unsigned long, void* clientData, void*);
  static void PickCallback(vtkObject*, unsigned long, void* clientData, void*);
  void pick();

  vtkNew<vtkGenericOpenGLRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> SurfaceMapper;
  vtkNew<vtkActor> SurfaceActor;
  vtkNew<vtkPolyDataMapper> CenterlineMapper;
  vtkNew<vtkActor> CenterlineActor;
  bool CenterlinesVisible = true;
  vtkNew<vtkBenderRibbonWidget> RibbonWidget;
  vtkNew<vtkCallbackCommand> RibbonObserver;
  vtkNew<vtkCallbackCommand> PickObserver;
  bool Picking = false;
  int Quiet = 0;
};

#endif
