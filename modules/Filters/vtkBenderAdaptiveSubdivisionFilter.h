/**
 * @class   vtkBenderAdaptiveSubdivisionFilter
 * @brief   warp a surface by a frozen ribbon warp and refine it where the warp bends it
 *
 * Paper 3.9, spec 7. Input port 0 is the surface *before* the warp (pre-warp positions X);
 * the warp W is set with SetWarp (a bender::WarpSpec, as stored in a plan). The output is the
 * warped surface W(X), refined: an edge (a, b) is marked when
 *
 *     | W((X_a + X_b) / 2) - (W(X_a) + W(X_b)) / 2 | > Tolerance
 *
 * and is split at its initial-space midpoint, whose warped position is W of that midpoint.
 * A triangle with m marked edges becomes m + 1 triangles (spec 7 patterns; the quad of m = 2
 * is cut along its shorter diagonal measured in warped positions, ties within a relative 1e-9
 * going to the diagonal whose smaller vertex index is smaller). The split belongs to the edge
 * (an edge -> midpoint hash map), so neighbours share the midpoint: no T-junctions, boundary
 * and non-manifold edges need no special case. Old vertices never move. Only the edges made
 * in a pass are retested in the next, until nothing is marked or MaxPasses is reached.
 *
 * Input: polygons are fan-triangulated and strips converted; vertices and lines are dropped.
 * Output points are double. Point data is interpolated linearly at new vertices (normals are
 * dropped: stale after a warp); cell data is copied from the input cell each triangle comes
 * from (the CFD patch labels of PatchLabels.h: CellEntityIds, ModelFaceID) and field data is
 * passed (their PatchNames, PatchTypes). With KeepInitialPositions, the output carries the pre-warp
 * position of every vertex as the 3-component double point array "InitialPosition", so that the
 * subdivided surface can be compared with the exact warp, or warped again.
 *
 * Coordinates are those of the input (LPS millimetres for segmented vessels); Tolerance is in
 * the same unit.
 *
 * Errors (vtkErrorMacro, RequestData returns 0, empty output, GetLastError() says why): an
 * invalid warp (spec convention 11), a non-finite input coordinate, Tolerance <= 0 or not
 * finite. An empty input is not an error.
 *
 * @warning Each pass evaluates W at one midpoint per retested edge: about 3 W evaluations per
 * triangle in the first pass (edges outside the region of influence are rejected by a box
 * test), the mesh grows by the number of marked edges per pass. MaxPasses bounds the growth;
 * a Tolerance far below the mesh's rounding noise refines up to MaxPasses everywhere W bends.
 */

#ifndef vtkBenderAdaptiveSubdivisionFilter_h
#define vtkBenderAdaptiveSubdivisionFilter_h

#include "vtkBenderFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include "RibbonWarp.h"
#include "WarpBinding.h"
#include "WarpPlan.h"

#include <string>
#include <vector>

class VTKBENDERFILTERS_EXPORT vtkBenderAdaptiveSubdivisionFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkBenderAdaptiveSubdivisionFilter* New();
  vtkTypeMacro(vtkBenderAdaptiveSubdivisionFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The frozen warp. Its `subdivision` member, when present, sets Tolerance and MaxPasses
   * (the plan-file form); when absent they are left as they are. Default: the identity warp
   * (identical straight ribbons (0,0,0)-(1,0,0), R = 1).
   */
  void SetWarp(const bender::WarpSpec& spec);
  const bender::WarpSpec& GetWarp() const { return this->Spec; }
  ///@}

  ///@{
  /** Split threshold delta, model units, > 0. Default 1e-3. */
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /** At most this many passes, [0, 64]; 0 warps without refining. Default 8. */
  vtkSetClampMacro(MaxPasses, int, 0, 64);
  vtkGetMacro(MaxPasses, int);
  ///@}

  ///@{
  /** Blend mode for points with two projections (see vtkBenderWarpFilter). Default normative. */
  void SetBlendMode(bender::BlendMode mode);
  bender::BlendMode GetBlendMode() const { return this->Blend; }
  ///@}

  ///@{
  /** Screw evaluation, Exact (default, normative) or Table (see vtkBenderWarpFilter). */
  void SetPrecision(bender::WarpPrecision precision);
  bender::WarpPrecision GetPrecision() const { return this->Precision; }
  ///@}

  ///@{
  /** Add the point array "InitialPosition" (pre-warp positions). Default off. */
  vtkSetMacro(KeepInitialPositions, bool);
  vtkGetMacro(KeepInitialPositions, bool);
  vtkBooleanMacro(KeepInitialPositions, bool);
  ///@}

  /** Name of the pre-warp position array written with KeepInitialPositions. */
  static const char* InitialPositionArrayName() { return "InitialPosition"; }

  /** The message of the last failure, empty after a successful update. */
  const std::string& GetLastError() const { return this->LastError; }
  /** Passes that split at least one edge in the last update. */
  int GetNumberOfPassesRun() const { return static_cast<int>(this->SplitsPerPass.size()); }
  /** Edges split in each pass of the last update (the triangle count grows by their sum,
   * counted once per incident triangle). */
  const std::vector<vtkIdType>& GetSplitsPerPass() const { return this->SplitsPerPass; }
  /** True when the last update stopped because nothing was marked (not at MaxPasses). */
  bool GetConverged() const { return this->Converged; }
  /** Largest edge deviation among the edges tested in the last pass that tested any. */
  double GetLastMaximumDeviation() const { return this->LastMaximumDeviation; }

protected:
  vtkBenderAdaptiveSubdivisionFilter();
  ~vtkBenderAdaptiveSubdivisionFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkBenderAdaptiveSubdivisionFilter(const vtkBenderAdaptiveSubdivisionFilter&) = delete;
  void operator=(const vtkBenderAdaptiveSubdivisionFilter&) = delete;

  bender::WarpSpec Spec;
  double Tolerance = 1e-3;
  int MaxPasses = 8;
  bender::BlendMode Blend = bender::BlendMode::TwoProjections;
  bender::WarpPrecision Precision = bender::WarpPrecision::Exact;
  bool KeepInitialPositions = false;
  std::string LastError;
  std::vector<vtkIdType> SplitsPerPass;
  bool Converged = false;
  double LastMaximumDeviation = 0.0;
};

#endif
