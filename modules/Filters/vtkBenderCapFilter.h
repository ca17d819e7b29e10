/**
 * @class   vtkBenderCapFilter
 * @brief   close the planar-ish open ends of a vessel surface with flat, labelled caps
 *
 * Real vessel surfaces are open at their inlets and outlets. This filter finds the boundary
 * loops of its input (a triangle surface, polygons fanned, strips converted) and closes each
 * loop that is planar-ish with a flat cap: one new point at the loop's centroid and a fan of
 * triangles to the loop's edges, oriented consistently with the wall (each boundary edge is
 * traversed the other way by its cap triangle), so that a consistently oriented open surface
 * becomes a closed, consistently oriented one.
 *
 * Output cell data: the int array "PatchId" (see PatchIdArrayName()): 0 on the wall, 1..n on
 * the caps, numbered by decreasing loop length (ties by smallest vertex id) so that the
 * numbering is reproducible. Other cell data is copied for wall triangles and zero for caps;
 * point data is copied and averaged over the loop at each centroid. Normals are dropped.
 *
 * A loop is planar-ish when every vertex lies within Planarity x (largest distance between
 * loop vertices) of the loop's least-squares plane. Other loops are left open and counted in
 * GetNumberOfSkippedLoops() (they usually mean a hole in the wall, not a vessel end).
 * Coordinates and units are those of the input (LPS mm for segmented vessels).
 *
 * Errors: a non-finite input coordinate (vtkErrorMacro, return 0, empty output). An empty
 * input or a closed surface is not an error (output = input, triangulated, PatchId all 0).
 */

#ifndef vtkBenderCapFilter_h
#define vtkBenderCapFilter_h

#include "vtkBenderFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class VTKBENDERFILTERS_EXPORT vtkBenderCapFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkBenderCapFilter* New();
  vtkTypeMacro(vtkBenderCapFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Planarity threshold as a fraction of the loop's diameter, [0, 1]. Default 0.1. */
  vtkSetClampMacro(Planarity, double, 0.0, 1.0);
  vtkGetMacro(Planarity, double);
  ///@}

  /** Name of the per-cell patch label array (wall 0, caps 1..n). */
  static const char* PatchIdArrayName() { return "PatchId"; }

  /** Caps added by the last update. */
  int GetNumberOfCaps() const { return this->NumberOfCaps; }
  /** Boundary loops left open by the last update (not planar-ish, or not closed chains). */
  int GetNumberOfSkippedLoops() const { return this->NumberOfSkippedLoops; }
  /** The message of the last failure, empty after a successful update. */
  const std::string& GetLastError() const { return this->LastError; }

protected:
  vtkBenderCapFilter() = default;
  ~vtkBenderCapFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkBenderCapFilter(const vtkBenderCapFilter&) = delete;
  void operator=(const vtkBenderCapFilter&) = delete;

  double Planarity = 0.1;
  int NumberOfCaps = 0;
  int NumberOfSkippedLoops = 0;
  std::string LastError;
};

#endif
