/**
 * @class   vtkBenderCapFilter
 * @brief   close the planar-ish open ends of a vessel surface with flat, well-shaped, labelled caps
 *
 * Real vessel surfaces are open at their inlets and outlets. This filter finds the boundary
 * loops of its input (a triangle surface, polygons fanned, strips converted) and closes each
 * loop that is planar-ish with a flat cap:
 *  - the loop's least-squares plane (centroid and smallest principal axis) is computed and the
 *    rim vertices are moved onto it (ProjectRim, default on: they move by at most Planarity x
 *    the loop's diameter, usually by nothing for a rim cut by a plane), so that every cap point
 *    lies exactly on one plane;
 *  - the cap is a constrained Delaunay triangulation of the rim polygon and of interior points
 *    on a triangular lattice whose spacing is the rim's mean edge length (lattice points closer
 *    than 0.6 spacing to the rim are dropped), then three passes of Laplacian smoothing of the
 *    interior points each followed by a new Delaunay triangulation: triangles away from the rim
 *    are close to equilateral (minimum angle well above 20 degrees), triangles on the rim follow
 *    the rim's own spacing;
 *  - the rim vertices are shared with the wall (no new point on the rim): the result is
 *    watertight, and each cap triangle runs its rim edge the other way from the wall triangle,
 *    so a consistently oriented open surface becomes a consistently oriented closed one. When
 *    the output is closed and its signed volume is negative, every triangle is reversed so that
 *    the surface faces outwards.
 *
 * Output labels (modules/IO/PatchLabels.h, written by WritePatchLabels): CellEntityIds and
 * ModelFaceID 1 on the wall (every input triangle), 2..n+1 on the caps, ordered by decreasing
 * cap area (ties by smallest rim vertex id: reproducible); PatchNames / PatchTypes: the largest
 * cap is "inlet" (Inlet), the others "outlet_1", "outlet_2", ... (Outlet) in that order. Names
 * can be given by position (AddCapName): the cap whose centre is nearest to the point gets the
 * name, and an entry marked inlet makes its cap the inlet instead of the largest one. An input
 * that already carries labels keeps them (ids, names, types); its new caps get the ids after
 * the largest one, and none is the default inlet when the input already has an inlet.
 *
 * Other cell data is copied for wall triangles and zero for caps; point data is copied, and
 * interior cap points get the average over their rim. Normals are dropped.
 *
 * A loop is planar-ish when every vertex lies within Planarity x (largest distance between
 * loop vertices) of the loop's least-squares plane. Other loops are left open and counted in
 * GetNumberOfSkippedLoops() (they usually mean a hole in the wall, not a vessel end).
 * Coordinates and units are those of the input (LPS mm for segmented vessels).
 *
 * Errors (vtkErrorMacro, return 0, empty output, GetLastError() one line): a non-finite input
 * coordinate, a planar-ish loop whose rim is not a simple polygon in its plane (coincident
 * vertices, no area, or edges that cross: a corrupt surface, which the triangulator must not
 * see; the message names the loop's first point and the problem), an invalid or duplicated cap
 * name, two names pointing at the same cap, invalid labels on the input. An empty input or a closed
 * surface is not an error (output = input, triangulated, all wall unless labelled).
 */

#ifndef vtkBenderCapFilter_h
#define vtkBenderCapFilter_h

#include "vtkBenderFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <array>
#include <string>
#include <vector>

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

  ///@{
  /** Move the rim vertices onto the cap's plane (default on). Off: the cap's interior points
   * are on the plane, the rim stays where it is (the cap is then only as flat as its rim). */
  vtkSetMacro(ProjectRim, bool);
  vtkGetMacro(ProjectRim, bool);
  vtkBooleanMacro(ProjectRim, bool);
  ///@}

  /** Names a cap by position: the cap whose centre is nearest to `point` gets `name` (a valid
   * patch name, see bender::IsValidPatchName). inlet: this cap is the inlet (at most one). */
  void AddCapName(const double point[3], const std::string& name, bool inlet = false);
  void ClearCapNames();

  /** One cap of the last update. */
  struct CapInfo
  {
    int id = 0; ///< CellEntityIds value (2..n+1 on an unlabelled input)
    std::string name;
    bool inlet = false;
    std::array<double, 3> centre{ { 0, 0, 0 } }; ///< area centroid, on the cap's plane
    std::array<double, 3> normal{ { 0, 0, 1 } }; ///< unit, outwards (as the triangles face)
    double area = 0.0;
    double radius = 0.0;           ///< equivalent radius sqrt(area / pi)
    int rimPoints = 0;             ///< vertices of the rim
    double maxRimDistance = 0.0;   ///< largest distance of an input rim vertex to the plane
    double minInteriorAngle = 0.0; ///< degrees, over triangles with no rim vertex (0 if none)
    double minAngle = 0.0;         ///< degrees, over all the cap's triangles
  };
  /** Caps added by the last update, in id order. */
  const std::vector<CapInfo>& GetCaps() const { return this->Caps; }
  /** Caps added by the last update. */
  int GetNumberOfCaps() const { return static_cast<int>(this->Caps.size()); }
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

  struct CapName
  {
    std::array<double, 3> point;
    std::string name;
    bool inlet = false;
  };

  double Planarity = 0.1;
  bool ProjectRim = true;
  std::vector<CapName> Names;
  std::vector<CapInfo> Caps;
  int NumberOfSkippedLoops = 0;
  std::string LastError;
};

#endif
