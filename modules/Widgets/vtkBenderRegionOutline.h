/**
 * @class   vtkBenderRegionOutline
 * @brief   the outline of a ribbon's region of influence as seen from a camera
 *
 * Input: a wire, one polyline (vtkBenderRibbonSource's output port 1). Output: the outline of
 * the region {P : dist(P, wire) < Radius} as the camera sees it: closed polylines, the boundary
 * of the union of the discs of radius Radius around the wire's projection on the view plane,
 * each point at the depth of the nearest point of the wire.
 *
 * The outline is the zero level of the distance to the projected wire minus Radius, sampled on
 * a grid of the view plane (Radius / 8 apart, at most GridCells per side) and contoured:
 * a level set never crosses itself, however the wire bends. The silhouette of the region's
 * tube (vtkPolyDataSilhouette) does not have that property: where the wire bends tighter than
 * Radius the swept tube folds, and its silhouette is a tangle of loops while dragging.
 *
 * The projection is orthographic along the camera's direction of projection (a perspective
 * camera: the direction from the camera to the wire's centre), which the drawn outline
 * follows to within the perspective of the region's own depth.
 */

#ifndef vtkBenderRegionOutline_h
#define vtkBenderRegionOutline_h

#include "vtkBenderWidgetsModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <vtkSmartPointer.h>

class vtkCamera;

class VTKBENDERWIDGETS_EXPORT vtkBenderRegionOutline : public vtkPolyDataAlgorithm
{
public:
  static vtkBenderRegionOutline* New();
  vtkTypeMacro(vtkBenderRegionOutline, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Radius of the region, >= 0 (0: no outline). Default 0. */
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /** Grid cells per side of the view plane's sampling at most, [16, 1024]. Default 160. */
  vtkSetClampMacro(GridCells, int, 16, 1024);
  vtkGetMacro(GridCells, int);
  ///@}

  /** The camera the outline is seen from; without one, the output is empty. */
  void SetCamera(vtkCamera* camera);
  vtkCamera* GetCamera() const;

  /** Includes the camera's modification time: a moved camera redraws the outline. */
  vtkMTimeType GetMTime() override;

protected:
  vtkBenderRegionOutline();
  ~vtkBenderRegionOutline() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Radius = 0.0;
  int GridCells = 160;
  vtkSmartPointer<vtkCamera> Camera;

private:
  vtkBenderRegionOutline(const vtkBenderRegionOutline&) = delete;
  void operator=(const vtkBenderRegionOutline&) = delete;
};

#endif
