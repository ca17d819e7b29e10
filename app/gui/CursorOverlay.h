#ifndef CursorOverlay_h
#define CursorOverlay_h

#include <QObject>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <functional>

class vtkActor;
class vtkCallbackCommand;
class vtkObject;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkProp;
class vtkRenderWindowInteractor;
class vtkRenderer;

/// The slice views' cursor (one point in LPS mm) drawn in a 3D view, and the 3D view's way of
/// moving it: a Shift+click on a pickable prop (the surface) emits picked() with the point hit.
///
/// Drawn as a small three-axis crosshair through the cursor (white, its arms 6% of the
/// volume's diagonal) and, optionally, the outlines of the three slice planes through it over
/// the volume's box, in the slice views' colours: axial red, coronal green, sagittal yellow.
/// The actors go into `layer` (a renderer layer drawn above the surface, sharing its camera,
/// so that the cursor shows through the vessel); picks are made in `pickRenderer`.
///
/// Shift+click: Shift+left drag still pans the camera (vtkInteractorStyleTrackballCamera);
/// only a press and release within 3 pixels picks. The press is left to the others (the camera
/// style, the ribbon widget) and nothing is picked while the view is placing a ribbon (the
/// caller's `busy` says so), so the overlay never takes a click from them.
class CursorOverlay : public QObject
{
  Q_OBJECT
public:
  enum Style
  {
    Hidden = 0,
    Crosshair,
    CrosshairAndPlanes
  };

  /// `layer`: where the cursor is drawn; `pickRenderer` and `pickable`: what a Shift+click
  /// picks (the surface's renderer and actor). The interactor is the layer's window's.
  CursorOverlay(vtkRenderer* layer,
    vtkRenderer* pickRenderer,
    vtkProp* pickable,
    QObject* parent = nullptr);
  ~CursorOverlay() override;

  /// The volume's box in LPS (the planes' outlines, the crosshair's size); an empty box
  /// (min > max) hides the cursor.
  void setBounds(const double bounds[6]);
  void setPosition(const double position[3]);
  void position(double position[3]) const;
  void setStyle(Style style);
  Style style() const { return this->CurrentStyle; }
  /// Drawn: a style other than Hidden and a volume's box.
  bool isShown() const;
  /// While `busy` returns true, Shift+clicks are left alone (placing a ribbon).
  void setBusy(std::function<bool()> busy) { this->Busy = std::move(busy); }

  /// Picks at display pixel (x, y) (VTK's, origin bottom left) on the pickable prop; false
  /// on a miss.
  bool pickAt(int x, int y, double point[3]) const;

  ///@{ For tests: the crosshair's and the planes' lines (LPS mm).
  vtkPolyData* crosshairLines() const { return this->CrossData; }
  vtkPolyData* planeOutlines() const { return this->PlaneData; }
  vtkActor* crosshairActor() const { return this->Cross; }
  vtkActor* planesActor() const { return this->Planes; }
  ///@}

signals:
  /// A Shift+click hit the pickable prop at (x, y, z), LPS mm.
  void picked(double x, double y, double z);

private:
  static void OnMouse(vtkObject* caller, unsigned long event, void* clientData, void*);
  void rebuild();

  // Held: the 3D view may go before the overlay's owner (Qt deletes the central widget first).
  vtkSmartPointer<vtkRenderer> Layer;
  vtkSmartPointer<vtkRenderer> PickRenderer;
  vtkSmartPointer<vtkProp> Pickable;
  vtkSmartPointer<vtkRenderWindowInteractor> Interactor;
  std::function<bool()> Busy;
  vtkNew<vtkPolyData> CrossData;
  vtkNew<vtkPolyDataMapper> CrossMapper;
  vtkNew<vtkActor> Cross;
  vtkNew<vtkPolyData> PlaneData;
  vtkNew<vtkPolyDataMapper> PlaneMapper;
  vtkNew<vtkActor> Planes;
  vtkNew<vtkCallbackCommand> MouseObserver;
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
  double Position[3] = { 0, 0, 0 };
  Style CurrentStyle = Crosshair;
  bool Pressed = false;
  int PressedAt[2] = { 0, 0 };
};

#endif
