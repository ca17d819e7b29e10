#ifndef HandMarkers_h
#define HandMarkers_h

#include "WarpPlan.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <optional>

class vtkActor;
class vtkBillboardTextActor3D;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkSphereSource;

/// Where the two tracked hands map now, drawn in the view's ribbon layer (above the surface):
/// an orange ball per hand labelled "left hand" / "right hand", and a line from each ball to
/// the ribbon end that hand holds (nothing when they coincide, after an anchoring). VTK only;
/// the Trackers panel says what to show.
class HandMarkers
{
public:
  HandMarkers();
  /// Removes the actors from the layer they were added to.
  ~HandMarkers();
  HandMarkers(const HandMarkers&) = delete;
  HandMarkers& operator=(const HandMarkers&) = delete;

  /// Adds the (hidden) actors to `layer`, which is held: the view may be deleted first.
  void attach(vtkRenderer* layer);
  /// `hands`: where the hands map (start: left); `held`: the ribbon whose ends they hold. The
  /// balls' radius follows the ribbon's length (9%, within 0.3..25 mm).
  void show(const bender::RibbonSpec& hands, const std::optional<bender::RibbonSpec>& held);
  void hide();

  bool shown() const { return this->Shown; }
  /// Where hand 0 (left) or 1 (right) is drawn (model mm); false when hidden or no such hand.
  bool position(int hand, double position[3]) const;

private:
  bool Shown = false;
  double Position[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } };
  vtkSmartPointer<vtkRenderer> Layer;
  vtkNew<vtkSphereSource> Sphere[2];
  vtkNew<vtkPolyDataMapper> Mapper[2];
  vtkNew<vtkActor> Ball[2];
  vtkNew<vtkBillboardTextActor3D> Label[2];
  vtkNew<vtkPolyData> TetherData;
  vtkNew<vtkPolyDataMapper> TetherMapper;
  vtkNew<vtkActor> Tether;
};

#endif
