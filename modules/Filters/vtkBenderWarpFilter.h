/**
 * @class   vtkBenderWarpFilter
 * @brief   deform a surface with the ribbon warp of the Bender paper
 *
 * vtkBenderWarpFilter moves the points of its input (port 0, a vtkPolyData) by the space warp
 * defined by two ribbons: the *initial* ribbon, captured when the user grabbed, and the
 * *final* ribbon, where the user's hands are now (or were at release). Points within Radius of
 * the initial wire follow the screw motions carrying the initial ribbon's frames to the final
 * ribbon's, weighted by the decay (bell or plateau); points farther away do not move. The
 * mathematics is modules/Geometry (spec: ribbon-warp-spec.md); this class adds the VTK
 * pipeline, the per-grab binding cache and vtkSMPTools parallelism.
 *
 * The warp is set as a whole with SetWarp (a bender::WarpSpec, as stored in a plan file), or
 * piecewise with SetInitialRibbon / SetFinalRibbon / SetRadius / SetDecay / SetReverseScrews.
 * Coordinates are those of the input mesh (LPS millimetres for segmented vessels).
 *
 * Binding: the projections of the input points onto the initial wire are computed once and
 * kept while the input points, the initial ribbon, the radius, the decay and the blend mode
 * are unchanged. Moving only the final ribbon then re-runs the evaluation alone, which is what
 * an interactive drag does (see GetBindingCount).
 *
 * Interactive use (a drag): the caller validates each move by building the bender::RibbonWarp
 * once and hands it over with SetPreparedWarp (shared, not rebuilt here). The output points
 * are kept between updates while nobody else holds them, so that a move writes only the
 * points inside the region of influence; the input is never copied per move (see
 * GetPointsCopyCount and GetWarpBuildCount). With PassThrough on (nothing grabbed), the output
 * shares the input's points and arrays.
 *
 * Output: same topology, point and cell data passed; point and cell normals removed (stale
 * after a warp: recompute downstream). Float points stay float, double stay double.
 *
 * Errors (vtkErrorMacro, RequestData returns 0, output empty, GetLastError() says why): an
 * invalid ribbon or warp (spec convention 11), a non-finite input coordinate. An empty input
 * is not an error. A warp never writes NaN or infinity.
 *
 * @warning Binding costs about 0.1 us per input point (parallel), evaluation about 0.05 us per
 * point inside the region of influence with Precision Table, a few times more with Exact.
 * With Radius >= the smallest arc radius of either wire, space may invert (paper 3.8):
 * GetSpaceInversionRisk() reports it; the filter still warps.
 */

#ifndef vtkBenderWarpFilter_h
#define vtkBenderWarpFilter_h

#include "vtkBenderFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h"

#include "RibbonWarp.h"
#include "WarpBinding.h"
#include "WarpPlan.h"

class vtkPoints;

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class VTKBENDERFILTERS_EXPORT vtkBenderWarpFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkBenderWarpFilter* New();
  vtkTypeMacro(vtkBenderWarpFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The whole warp: both ribbons, radius, decay, reverseScrews (subdivision is ignored here;
   * see the subdivision filter). Default: identical straight ribbons from (0,0,0) to (1,0,0),
   * R = 1, bell, which leaves every point in place.
   */
  void SetWarp(const bender::WarpSpec& spec);
  const bender::WarpSpec& GetWarp() const { return this->Spec; }
  ///@}

  ///@{
  /**
   * A warp already built and validated by the caller (its spec becomes the filter's). The
   * filter uses it as is instead of building its own; any later change of a ribbon, the
   * radius, the decay or the screws drops it. Used when it was built with the filter's
   * blend mode, else the filter builds its own.
   */
  void SetPreparedWarp(std::shared_ptr<const bender::RibbonWarp> warp);
  const std::shared_ptr<const bender::RibbonWarp>& GetPreparedWarp() const
  {
    return this->Prepared;
  }
  ///@}

  ///@{
  /**
   * Pass the input through unchanged (shared points, no warp, no binding). For a live
   * pipeline whose warp is off while nothing is grabbed. Default off.
   */
  void SetPassThrough(bool passThrough)
  {
    if (this->PassThrough != passThrough)
    {
      this->PassThrough = passThrough;
      this->Modified();
    }
  }
  bool GetPassThrough() const { return this->PassThrough; }
  vtkBooleanMacro(PassThrough, bool);
  ///@}

  ///@{
  /** The ribbon at grab (initial) and now/at release (final). */
  void SetInitialRibbon(const bender::RibbonSpec& ribbon);
  void SetFinalRibbon(const bender::RibbonSpec& ribbon);
  ///@}

  ///@{
  /** Radius R of the region of influence around the initial wire, > 0, model units. */
  void SetRadius(double r);
  double GetRadius() const { return this->Spec.radius; }
  ///@}

  ///@{
  /** Decay: bell (default) or plateau with width p in [0, 0.95] (fraction of R). */
  void SetDecay(const bender::DecaySpec& decay);
  ///@}

  ///@{
  /** Start the screws from the non-minimal twin (paper 3.8 toggle). Default false. */
  void SetReverseScrews(bool reverse);
  bool GetReverseScrews() const { return this->Spec.reverseScrews; }
  ///@}

  ///@{
  /**
   * Blend mode for points with two projections. Default TwoProjections (normative);
   * SingleProjection tears space and exists only for comparison (paper Fig. 8).
   */
  void SetBlendMode(bender::BlendMode mode);
  bender::BlendMode GetBlendMode() const { return this->Blend; }
  ///@}

  ///@{
  /**
   * Exact (default): screws evaluated at each point's exact s, the normative result, for
   * commits and batch work. Table: screws interpolated from the lifted table, about 3 times
   * faster, within 1e-5 of the model size; for interactive drags.
   */
  void SetPrecision(bender::WarpPrecision precision);
  bender::WarpPrecision GetPrecision() const { return this->Precision; }
  ///@}

  /** The message of the last failure, empty after a successful update. */
  const std::string& GetLastError() const { return this->LastError; }
  /** Space-inversion warning of the last successful update (empty when R < r_min). */
  const std::string& GetLastWarning() const { return this->LastWarning; }
  /** True when the last update's R >= r_min of the initial or final wire. */
  bool GetSpaceInversionRisk() const { return this->SpaceInversionRisk; }
  /** True when the lift chose the non-minimal screw somewhere (the paper's Fig. 10 case). */
  bool GetFlipOccurred() const { return this->FlipOccurred; }
  /** r_min of the initial wire of the last update (infinite for straight wires). */
  double GetInitialMinimumRadius() const { return this->InitialMinimumRadius; }
  /** Number of points inside the region of influence in the current binding. */
  vtkIdType GetNumberOfBoundPoints() const;
  /** The input's point ids inside the region of influence in the current binding (the points
   * a move can change); sorted, empty before the first update. */
  const std::vector<std::int64_t>& GetBoundPointIds() const;
  /** How many times the binding was (re)computed: for tests and benchmarks. */
  vtkIdType GetBindingCount() const { return this->BindingCount; }
  /** How many times the filter built a RibbonWarp itself (not counting prepared ones). */
  vtkIdType GetWarpBuildCount() const { return this->WarpBuildCount; }
  /** How many times all input points were copied into the output points (after a (re)bind or a
   * new output array; not per move). */
  vtkIdType GetPointsCopyCount() const { return this->PointsCopyCount; }

protected:
  vtkBenderWarpFilter();
  ~vtkBenderWarpFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkBenderWarpFilter(const vtkBenderWarpFilter&) = delete;
  void operator=(const vtkBenderWarpFilter&) = delete;

  struct BindingCache;

  bender::WarpSpec Spec;
  std::shared_ptr<const bender::RibbonWarp> Prepared;
  bool PassThrough = false;
  vtkSmartPointer<vtkPoints> OutputPoints;
  vtkIdType FilledForBinding = -1;
  vtkIdType WarpBuildCount = 0;
  vtkIdType PointsCopyCount = 0;
  bender::BlendMode Blend = bender::BlendMode::TwoProjections;
  bender::WarpPrecision Precision = bender::WarpPrecision::Exact;
  std::unique_ptr<BindingCache> Cache;
  std::string LastError;
  std::string LastWarning;
  bool SpaceInversionRisk = false;
  bool FlipOccurred = false;
  double InitialMinimumRadius = 0.0;
  vtkIdType BindingCount = 0;
};

#endif
