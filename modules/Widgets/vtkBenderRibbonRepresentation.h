/**
 * @class   vtkBenderRibbonRepresentation
 * @brief   the ribbon of the Bender paper as a 3D widget representation
 *
 * Draws a ribbon (two end frames, see bender::RibbonSpec) with six handles: the two end
 * positions, a tangent handle at each end (on the tangent line, outside the ribbon: behind the
 * start, beyond the end) and a normal handle at each end (on the ribbon normal, which sets the
 * twist). The twisted strip and the region of influence (radius Radius around the wire) are
 * drawn through vtkBenderRibbonSource: the region as its outline seen from the camera (always
 * clean, also on software OpenGL) plus, with RegionOpacity > 0, a translucent tube (VTK's
 * order-independent translucency, which draws stripes on llvmpipe: hence off by default).
 *
 * An invalid ribbon (spec convention 11: coincident ends, cusp, unstable near-parallel case)
 * is drawn as a red straight line between red handles, with GetValid() false and
 * GetLastError() saying why; the widget still reports it, and the application never applies
 * it.
 *
 * The handles say what they are: the end points are blue spheres ("end: drag to move"), the
 * tangent handles green cones pointing along the tangent ("tangent: drag to bend"), the normal
 * handles magenta cubes ("twist: drag to twist"); the handle under the cursor turns yellow and
 * its hint is drawn beside it (GetHoverText()). An application that draws the ribbon over an
 * opaque surface puts the widget in a renderer of a higher layer sharing the camera, so that
 * handles and strip stay visible through the vessel (as the Bender window does).
 *
 * Moving a handle: an end position moves with its tangent and normal handles; a tangent handle
 * sets the tangent to the direction from (start) or to (end) the position, the normal is made
 * orthogonal again; a normal handle sets the normal to the handle's direction made orthogonal
 * to the tangent. MoveHandle() does the same from code (tests, trackers, scripts).
 *
 * Coordinates: the model's (LPS mm for segmented vessels). HandleLength (the distance of the
 * tangent and normal handles from the end points) and HandleRadius are in model units; they
 * are set from the bounds by PlaceWidget and can be set directly.
 */

#ifndef vtkBenderRibbonRepresentation_h
#define vtkBenderRibbonRepresentation_h

#include "vtkBenderWidgetsModule.h"
#include "vtkWidgetRepresentation.h"

#include "WarpPlan.h"

#include <vtkSmartPointer.h>

#include <string>

class vtkActor;
class vtkBenderRibbonSource;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkBenderRegionOutline;
class vtkProperty;
class vtkConeSource;
class vtkCubeSource;
class vtkSphereSource;
class vtkTextActor;

class VTKBENDERWIDGETS_EXPORT vtkBenderRibbonRepresentation : public vtkWidgetRepresentation
{
public:
  static vtkBenderRibbonRepresentation* New();
  vtkTypeMacro(vtkBenderRibbonRepresentation, vtkWidgetRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Interaction states: which handle is under the cursor / being dragged. */
  enum Handle
  {
    Outside = 0,
    StartPosition,
    EndPosition,
    StartTangent,
    EndTangent,
    StartNormal,
    EndNormal,
    NumberOfHandles = 7
  };

  ///@{
  /** The ribbon (end frames and extra turns), model units. Default: (0,0,0)-(1,0,0). */
  void SetRibbon(const bender::RibbonSpec& ribbon);
  const bender::RibbonSpec& GetRibbon() const { return this->Ribbon; }
  ///@}

  ///@{
  /** Radius of the region-of-influence tube, >= 0 (0 hides it). Default 0. */
  void SetRadius(double radius);
  double GetRadius() const { return this->Radius; }
  ///@}

  ///@{
  /** Show the region-of-influence tube (default on). */
  void SetRegionVisibility(bool visible);
  bool GetRegionVisibility() const { return this->RegionVisibility; }
  ///@}

  ///@{
  /** Opacity of the translucent region tube, [0, 1]; 0 (default) draws only the outline. */
  void SetRegionOpacity(double opacity);
  double GetRegionOpacity() const { return this->RegionOpacity; }
  ///@}

  ///@{
  /** Distance of tangent/normal handles from the ends, and handle sphere radius, > 0. */
  void SetHandleLength(double length);
  double GetHandleLength() const { return this->HandleLength; }
  void SetHandleRadius(double radius);
  double GetHandleRadius() const { return this->HandleRadius; }
  ///@}

  ///@{
  /** Half-width of the drawn strip, >= 0. Default 1. */
  void SetStripWidth(double width);
  double GetStripWidth() const;
  ///@}

  ///@{
  /** Picking tolerance around a handle, pixels, [1, 100]. Default 12. */
  vtkSetClampMacro(Tolerance, int, 1, 100);
  vtkGetMacro(Tolerance, int);
  ///@}

  /** Whether the current ribbon is valid, and why not. */
  /** The region's outline as last drawn (closed polylines, see vtkBenderRegionOutline). */
  vtkPolyData* GetRegionOutline();
  bool GetValid() const { return this->Valid; }
  const std::string& GetLastError() const { return this->LastError; }

  ///@{
  /**
   * What a handle is: "end", "tangent" or "twist" (empty for Outside), and the hint shown
   * when the cursor is over it ("end: drag to move", "tangent: drag to bend", "twist: drag to
   * twist").
   */
  static const char* GetHandleRole(int handle);
  static const char* GetHandleHint(int handle);
  ///@}

  /** The hint drawn beside the handle under the cursor; empty when none is. */
  const char* GetHoverText() const;

  /** A handle's actor (its shape and current property), null for Outside; for tests. */
  vtkActor* GetHandleActor(int handle);

  /** World position of a handle (model units). */
  void GetHandlePosition(int handle, double position[3]) const;

  /** Moves a handle to a world position as a drag would. Returns false for Outside. */
  bool MoveHandle(int handle, const double position[3]);

  /** Places a straight ribbon across the middle of the bounds along their longest axis. */
  void PlaceWidget(double bounds[6]) override;

  ///@{
  /** Widget representation API. */
  void BuildRepresentation() override;
  int ComputeInteractionState(int X, int Y, int modify = 0) override;
  void StartWidgetInteraction(double eventPosition[2]) override;
  void WidgetInteraction(double eventPosition[2]) override;
  void EndWidgetInteraction(double eventPosition[2]) override;
  void Highlight(int highlight) override;
  double* GetBounds() override;
  void GetActors(vtkPropCollection* actors) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  int RenderOpaqueGeometry(vtkViewport* viewport) override;
  int RenderTranslucentPolygonalGeometry(vtkViewport* viewport) override;
  int RenderOverlay(vtkViewport* viewport) override;
  vtkTypeBool HasTranslucentPolygonalGeometry() override;
  ///@}

  /** The strip actor (for tests and styling). */
  vtkActor* GetStripActor();
  vtkBenderRibbonSource* GetRibbonSource();

protected:
  vtkBenderRibbonRepresentation();
  ~vtkBenderRibbonRepresentation() override;

private:
  vtkBenderRibbonRepresentation(const vtkBenderRibbonRepresentation&) = delete;
  void operator=(const vtkBenderRibbonRepresentation&) = delete;

  void UpdateValidity();
  /// Puts the hover hint beside the handle under the cursor; false when none is shown.
  bool PlaceHoverLabel(vtkViewport* viewport);

  bender::RibbonSpec Ribbon;
  double Radius = 0.0;
  bool RegionVisibility = true;
  double RegionOpacity = 0.0;
  double HandleLength = 1.0;
  double HandleRadius = 0.1;
  int Tolerance = 12;
  bool Valid = true;
  std::string LastError;

  // Drag state: the handle's depth and the offset between the cursor and the handle at press.
  double DragDepth = 0.0;
  double DragOffset[3] = { 0, 0, 0 };

  vtkSmartPointer<vtkBenderRibbonSource> Source;
  vtkSmartPointer<vtkPolyDataMapper> StripMapper;
  vtkSmartPointer<vtkActor> StripActor;
  vtkSmartPointer<vtkPolyDataMapper> RegionMapper;
  vtkSmartPointer<vtkActor> RegionActor;
  vtkSmartPointer<vtkBenderRibbonSource> CageSource; // copy of the ribbon for the outline
  vtkSmartPointer<vtkBenderRegionOutline> Outline;   // the region as the camera sees it
  vtkSmartPointer<vtkPolyDataMapper> CageMapper;
  vtkSmartPointer<vtkActor> CageActor;
  vtkSmartPointer<vtkPolyData> Lines; // handle arms, or the red line of an invalid ribbon
  vtkSmartPointer<vtkPolyDataMapper> LinesMapper;
  vtkSmartPointer<vtkActor> LinesActor;
  vtkSmartPointer<vtkSphereSource> Sphere; // end handles
  vtkSmartPointer<vtkPolyDataMapper> SphereMapper;
  vtkSmartPointer<vtkConeSource> Cones[2]; // tangent handles, along the start / end tangent
  vtkSmartPointer<vtkPolyDataMapper> ConeMappers[2];
  vtkSmartPointer<vtkCubeSource> Cube; // twist handles
  vtkSmartPointer<vtkPolyDataMapper> CubeMapper;
  vtkSmartPointer<vtkActor> HandleActors[NumberOfHandles];
  vtkSmartPointer<vtkProperty> RoleProperties[3]; // end, tangent, twist
  vtkSmartPointer<vtkTextActor> HoverLabel;
  vtkSmartPointer<vtkProperty> SelectedProperty;
  vtkSmartPointer<vtkProperty> InvalidProperty;
  double Bounds[6];
};

#endif
