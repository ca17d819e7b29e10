#ifndef CfdEndsOverlay_h
#define CfdEndsOverlay_h

#include "PrepareForCfd.h"
#include "VesselClip.h"

#include <QObject>
#include <QString>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <vector>

class vtkActor;
class vtkCallbackCommand;
class vtkObject;
class vtkPolyData;
class vtkRenderer;
class vtkTextActor;

/// The vessel ends of Prepare for CFD in the 3D view (issue 11).
///
/// Before Prepare: each vessel end's clip plane as a translucent disc (1.5 x the inscribed
/// radius at the cut, perpendicular to the centerline's tangent there: bender::ClipPlaneAt,
/// the plane bender::ClipVesselEnds cuts by), a handle at its centre and a label (the end's
/// name and role). Dragging a handle with the left button slides its disc along the end's
/// centerline (bender::CenterlineEndPath), perpendicular to the local tangent, clamped to
/// [0, CenterlineEndPath::maximumDistance]: the mouse is followed by the centerline point whose
/// screen position is nearest it. The drag is the overlay's (the camera, the ribbon widget and
/// picking do not see it); a press away from every handle is left to them.
///
/// After Prepare: the caps of the labelled surface (bender::PatchLabels: CellEntityIds >= 2)
/// drawn over the surface in their role's colour (inlet red, outlets blue) with the patch name
/// at each cap's centre.
///
/// The discs go into `surfaceLayer` (with depth: they cross the wall where it is cut); the
/// handles, the labels and the caps' names into `topLayer` (a layer above the surface sharing
/// its camera, so that they show through the vessel). Hidden (nothing drawn, no mouse taken)
/// while setVisible(false).
class CfdEndsOverlay : public QObject
{
  Q_OBJECT
public:
  CfdEndsOverlay(vtkRenderer* surfaceLayer, vtkRenderer* topLayer, QObject* parent = nullptr);
  ~CfdEndsOverlay() override;

  ///@{ Before Prepare: the ends and their clip planes
  /// Shows the ends (one disc each, labelled "end k" until setLabel) at their paths' default
  /// distances; replaces what was shown (the patches too).
  void setEnds(const std::vector<bender::CenterlineEndPath>& paths);
  int numberOfEnds() const { return static_cast<int>(this->Ends.size()); }
  const bender::CenterlineEndPath& path(int end) const;
  /// Moves an end's disc (clamped to its path's range); no signal.
  void setDistance(int end, double distance);
  double distance(int end) const;
  /// The end's label and its colour: the inlet's red, the outlets' blue.
  void setLabel(int end, const QString& label, bool inlet);
  QString label(int end) const;
  /// The plane the disc shows now.
  bender::ClipPlane plane(int end) const;
  /// The handle's display position (VTK's pixels, origin bottom left); false when not shown.
  bool handleDisplayPosition(int end, double position[2]) const;
  /// The display position of the centerline point at `distance` along the end's path.
  bool pathDisplayPosition(int end, double distance, double position[2]) const;
  /// The disc's polygon, in model coordinates (tests).
  vtkPolyData* disc(int end) const;
  /// Discs drawn now (visible and not replaced by the patches).
  int numberOfDiscsShown() const;
  /// The end whose handle is being dragged, -1 when none.
  int draggedEnd() const { return this->Dragged; }
  ///@}

  ///@{ After Prepare: the labelled caps
  /// Shows the caps of `surface` (CellEntityIds >= 2) with the names of `ends` at their
  /// centres; the discs go.
  void setPatches(vtkPolyData* surface, const std::vector<bender::CfdEnd>& ends);
  int numberOfPatchLabelsShown() const;
  /// The patch names drawn now (tests), in the order of the ends given.
  std::vector<QString> patchLabels() const;
  vtkPolyData* caps() const { return this->CapData; }
  ///@}

  /// Removes the discs and the patches.
  void clear();
  void setVisible(bool visible);
  bool isVisible() const { return this->Visible; }
  bool showsPatches() const { return this->ShowingPatches; }

signals:
  /// A drag moved an end's disc (the distance along its path).
  void distanceChanged(int end, double distance);
  /// The drag of an end's handle ended.
  void dragFinished(int end);

private:
  struct EndActors
  {
    bender::CenterlineEndPath path;
    double distance = 0.0;
    QString label;
    bool inlet = false;
    vtkSmartPointer<vtkPolyData> disc;
    vtkSmartPointer<vtkActor> discActor;
    vtkSmartPointer<vtkActor> rimActor;
    vtkSmartPointer<vtkActor> handle;
    vtkSmartPointer<vtkTextActor> text;
  };
  static void OnMouse(vtkObject* caller, unsigned long event, void* clientData, void*);
  void mouse(unsigned long event);
  void removeEnds();
  void removePatches();
  void updateEnd(EndActors& end);
  void updateVisibility();
  int handleAt(int x, int y) const;
  double distanceAt(int end, int x, int y) const;
  void render();

  vtkSmartPointer<vtkRenderer> SurfaceLayer; // held: the view may go first at window close
  vtkSmartPointer<vtkRenderer> TopLayer;
  std::vector<EndActors> Ends;
  vtkNew<vtkPolyData> CapData;
  vtkSmartPointer<vtkActor> CapActor;
  std::vector<vtkSmartPointer<vtkTextActor>> PatchTexts;
  vtkNew<vtkCallbackCommand> MouseObserver;
  bool Visible = false;
  bool ShowingPatches = false;
  int Dragged = -1;
};

#endif
