#ifndef BenderView_h
#define BenderView_h

#include <QVTKOpenGLNativeWidget.h>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <functional>

class MainActions;
class vtkActor;
class vtkActor2D;
class vtkAlgorithmOutput;
class vtkAnnotatedCubeActor;
class vtkBenderRibbonWidget;
class vtkCallbackCommand;
class vtkGenericOpenGLRenderWindow;
class vtkObject;
class vtkOrientationMarkerWidget;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkPolyDataMapper2D;
class vtkRenderer;
class vtkTextActor;

/// The 3D view: the session's live surface (its output port, connected once: the pipeline
/// updates the mapper when the warp moves, nothing is copied or forced) and the ribbon widget.
/// Emits ribbonInteraction while a handle is dragged, and surfacePicked for a click on the
/// surface while picking is on ("place ribbon").
///
/// The view explains itself: the ribbon widget is drawn in a second layer sharing the camera,
/// so that its handles and strip stay visible through the vessel; an orientation marker (a
/// cube with the patient directions of the LPS frame: L, R, P, A, S, I) follows the camera;
/// a scale bar gives millimetres at the focal point; standard views (anterior, posterior, left,
/// right, superior, inferior) frame the surface; the original shape can be shown as a faint
/// ghost behind a bent surface (a decimated copy of it above levelOfDetailThreshold()
/// triangles).
///
/// Level of detail (setLevelOfDetail): while the camera is rotated, a surface of more than
/// levelOfDetailThreshold() triangles is drawn as its decimated copy (the session's proxy
/// port, made once per surface), the full surface again when the mouse is released; while the
/// session drags a big surface's copy (its own threshold), the warped copy is drawn, and the
/// full surface once the session stops (release). The choice is made before every frame.
class BenderView : public QVTKOpenGLNativeWidget
{
  Q_OBJECT
public:
  /// Standard views, named after the side of the patient the camera looks from (LPS model
  /// coordinates: +x left, +y posterior, +z superior). Superior and inferior have anterior up.
  enum StandardView
  {
    Anterior = 0,
    Posterior,
    Left,
    Right,
    Superior,
    Inferior
  };

  explicit BenderView(vtkAlgorithmOutput* surface, QWidget* parent = nullptr);
  ~BenderView() override;

  vtkRenderer* renderer() const { return this->Renderer; }
  /// The layer above the surface where the ribbon widget is drawn (same camera).
  vtkRenderer* ribbonRenderer() const { return this->RibbonRenderer; }
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
  /// Frames the surface from the front (the anterior standard view): resets the rotation too.
  /// Connects the window's view actions: Reset camera, the six standard views, Show original.
  void attachActions(MainActions* actions);
  void resetCamera();
  /// Looks at the surface from one side of the patient, framing it.
  void setStandardView(StandardView view);
  /// Resets the camera when the surface now shown is far from what was last framed (another
  /// size or place: a new mesh after the demo); returns whether it did. A ribbon left outside
  /// the new surface is then switched off (grab asks for a new one).
  bool frameIfNewScene();

  ///@{
  /// The surface before any warp, drawn as a faint ghost while `differs` (after a warp, while
  /// grabbed) and the toggle is on.
  void setOriginalSurface(vtkPolyData* original, bool differs);
  /// Where the ghost needs drawing: `inPlay()` returns the part of the original that the
  /// surface may differ from (BenderSession::GetOriginalInPlay), null for all of it. Elsewhere
  /// the ghost lies under the surface and is hidden: drawing only that part is the same picture
  /// for a fraction of the triangles. Without it the whole original is drawn.
  void setOriginalInPlay(std::function<vtkPolyData*()> inPlay);
  void setOriginalVisible(bool visible);
  bool originalShown() const;
  vtkActor* originalActor() const { return this->GhostActor; }
  ///@}

  ///@{ The orientation marker and the scale bar (for tests).
  vtkOrientationMarkerWidget* orientationMarker() const { return this->Marker; }
  vtkAnnotatedCubeActor* orientationCube() const { return this->MarkerCube; }
  /// The scale bar's length in mm and in pixels (at the focal point), as last drawn.
  double scaleBarMillimetres() const { return this->ScaleMillimetres; }
  double scaleBarPixels() const { return this->ScalePixels; }
  vtkTextActor* scaleBarText() const { return this->ScaleText; }
  ///@}

  ///@{ Level of detail
  /// `proxy`: the decimated copy of the surface (BenderSession::GetProxyOutputPort), drawn
  /// instead of the surface while rotating a big one and while `dragging()` (the session drags
  /// the copy: BenderSession::IsDraggingProxy). Without it the surface is always drawn whole.
  void setLevelOfDetail(vtkAlgorithmOutput* proxy, std::function<bool()> dragging);
  /// Triangles above which rotating draws the copy, and the ghost is a decimated copy.
  void setLevelOfDetailThreshold(long long triangles) { this->LodThreshold = triangles; }
  long long levelOfDetailThreshold() const { return this->LodThreshold; }
  /// Whether the last frame drew the copy instead of the surface.
  bool isShowingProxy() const;
  /// The copy drawn while rotating or dragging (null before it was first drawn).
  vtkPolyData* levelOfDetailProxy() const;
  ///@}

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
  static void StartRenderCallback(vtkObject*, unsigned long, void* clientData, void*);
  static void CameraInteractionCallback(vtkObject*, unsigned long event, void* clientData, void*);
  void pick();
  /// Before every frame: the clipping range covers the surface and the ribbon layer, and the
  /// scale bar follows the zoom.
  void beforeFrame();
  void updateScaleBar();
  void startCameraInteraction();
  void endCameraInteraction();
  /// Shows the copy or the surface, as rotating and dragging ask.
  void chooseLevelOfDetail();
  /// The ghost's data: the original, or its decimated copy when it is big.
  void updateGhostInput();
  /// The bounds to frame: the surface's (and the ghost's); false when there is nothing.
  bool sceneBounds(double bounds[6]);

  vtkNew<vtkGenericOpenGLRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderer> RibbonRenderer;
  vtkNew<vtkPolyDataMapper> SurfaceMapper;
  vtkNew<vtkActor> SurfaceActor;
  vtkNew<vtkPolyDataMapper> GhostMapper;
  vtkNew<vtkActor> GhostActor;
  bool GhostWanted = true;
  bool GhostDiffers = false;
  vtkNew<vtkPolyDataMapper> ProxyMapper;
  vtkNew<vtkActor> ProxyActor;
  bool HasProxy = false;
  bool Rotating = false; // the camera is moved with the copy shown
  std::function<bool()> DraggingProxy;
  vtkPolyData* GhostOriginal = nullptr; // identity only
  vtkMTimeType GhostOriginalTime = 0;
  vtkSmartPointer<vtkPolyData> GhostCopy;
  std::function<vtkPolyData*()> GhostInPlay;
  long long LodThreshold = 500000;
  vtkNew<vtkPolyDataMapper> CenterlineMapper;
  vtkNew<vtkActor> CenterlineActor;
  bool CenterlinesVisible = true;
  vtkNew<vtkBenderRibbonWidget> RibbonWidget;
  vtkNew<vtkCallbackCommand> RibbonObserver;
  vtkNew<vtkCallbackCommand> PickObserver;
  vtkNew<vtkCallbackCommand> StartRenderObserver;
  vtkNew<vtkCallbackCommand> CameraObserver;
  vtkNew<vtkAnnotatedCubeActor> MarkerCube;
  vtkNew<vtkOrientationMarkerWidget> Marker;
  vtkNew<vtkPolyDataMapper2D> ScaleMapper;
  vtkNew<vtkActor2D> ScaleBar;
  vtkNew<vtkTextActor> ScaleText;
  double ScaleMillimetres = 0.0;
  double ScalePixels = 0.0;
  double FramedBounds[6] = { 0, -1, 0, -1, 0, -1 };
  bool Picking = false;
  int Quiet = 0;
};

#endif
