#ifndef bender_VesselSession_h
#define bender_VesselSession_h

// The vessel side of the application without Qt: the centerlines of the session's committed
// surface (computed as a job off the GUI thread after a load, a segmentation, a release, an
// undo), the ribbon placed on them from two picks, the branch held under the ribbon measured
// live during a bend (its centerline samples and their wall points warped with the live warp,
// cheap: no centerline is recomputed per frame) and the before/after comparison of the whole
// plan (original surface against the committed one, branches matched by their outlets).
// Model coordinates (LPS mm), angles in degrees.

#include "CenterlineRibbonPlacement.h"
#include "Progress.h"
#include "VesselCenterlines.h"
#include "VesselMeasures.h"
#include "WarpPlan.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{
class BenderSession;

/// The measures of the centerline stretch between the held ribbon's ends (extended by one local
/// radius beyond each end, so that the end tangents are those of the vessel, not of one sample),
/// by MeasureStretch: the same rule as the plan's table (the end-window rule of
/// VesselMeasures.h). The radius at a sample is its distance to the nearest of the wall points
/// held with it (carried by the live warp), so minRadius is the narrowest the bend makes it.
struct HeldBranchMeasures : BranchMeasures
{
  bool valid = false;
  int samples = 0;
};

/// Centerlines of one surface state, computed by a job: Begin on the session's thread (inputs
/// copied), Run on any thread, VesselSession::Finish on the session's thread.
class CenterlineJob
{
public:
  /// Computes; never throws (the problem is kept for Finish). Cancellation: bender::Cancelled
  /// between the stages, kept as a problem.
  void Run(const ProgressReporter& progress);
  bool Succeeded() const { return this->Ok; }
  const std::string& GetProblem() const { return this->Problem; }

private:
  friend class VesselSession;
  vtkSmartPointer<vtkPolyData> Original; // the surface before the warps
  vtkSmartPointer<vtkPolyData> Current;  // the committed surface (null: the original itself)
  std::optional<CenterlineResult> OriginalResult; // known already: not recomputed
  const void* Key = nullptr;
  vtkMTimeType KeyTime = 0;
  const void* OriginalKey = nullptr;
  vtkMTimeType OriginalTime = 0;
  // Results
  bool Ok = false;
  std::string Problem;
  CenterlineResult Before;
  std::optional<CenterlineResult> After;
  std::optional<VesselComparison> Comparison;
};

class VesselSession
{
public:
  ///@{ Centerlines
  /// True when the centerlines shown are those of `session`'s committed surface (or a job for
  /// it was begun and not finished, or it failed for that surface).
  bool IsUpToDate(const BenderSession& session) const;
  /// A job for the committed surface; null when up to date or without a surface. When the
  /// committed surface is warped, the job also computes the original's centerlines (once),
  /// seeds the committed one's with the original's endpoints carried along (MatchedSeeds) and
  /// compares them (CompareVessels).
  std::shared_ptr<CenterlineJob> BeginCenterlines(const BenderSession& session);
  /// Takes a job's result in (unless another job was begun since); `message` gets one line
  /// (the problem, or a summary). Returns whether centerlines are now shown.
  bool Finish(CenterlineJob& job, std::string& message);
  bool HasCenterlines() const { return this->Shown.has_value(); }
  /// The polylines (one per outlet, from the inlet) and branches of the committed surface.
  vtkPolyData* GetPaths() const;
  vtkPolyData* GetBranches() const;
  const VesselMeasurements& GetMeasures() const { return this->Measures; }
  /// Original against committed, after at least one warp.
  const std::optional<VesselComparison>& GetComparison() const { return this->Comparison; }
  void Clear();
  ///@}

  /// The ribbon on the centerline between two picks (PlaceRibbonOnCenterline); throws
  /// RibbonPlacementError (no centerline, a pick on the sac, ...).
  RibbonPlacement PlaceRibbon(const Vec3& first,
    const Vec3& second,
    const CenterlineRibbonOptions& options = {}) const;

  /// Whether `point` (a pick on the wall) belongs to a vessel: its distance to the nearest
  /// centerline sample is at most `factor` x the inscribed radius there (the rule of
  /// PlaceRibbonOnCenterline; a pick on an aneurysm's sac is not). False without centerlines.
  bool IsOnVessel(const Vec3& point, double factor = 1.5) const;

  ///@{ The branch held under the ribbon
  /// Takes the centerline stretch under `ribbon` (the path nearest to both its ends) and the
  /// wall points of `surface` around it; false when there is no centerline or the ribbon's ends
  /// are farther than twice the local radius from every path.
  bool HoldBranch(const RibbonSpec& ribbon, vtkPolyData* surface);
  bool IsHolding() const { return !this->Held.empty(); }
  void DropBranch();
  /// The held stretch as it is (before the bend).
  HeldBranchMeasures MeasureHeld() const;
  /// The held stretch warped by `warp` (the live warp: initial and final ribbons, R, decay):
  /// its samples and wall points moved with RibbonWarp's exact evaluation.
  HeldBranchMeasures MeasureHeld(const WarpSpec& warp) const;
  /// The held stretch (as it is, or warped by `warp`) as one polyline with point data
  /// MaximumInscribedSphereRadius (the radii MeasureHeld uses): MeasureBranches of it gives
  /// MeasureHeld's values, as the plan's table measures its branches. Null when nothing is held
  /// or for an invalid warp.
  vtkSmartPointer<vtkPolyData> HeldStretch() const;
  vtkSmartPointer<vtkPolyData> HeldStretch(const WarpSpec& warp) const;
  ///@}

  /// The shown paths carried by `warp` (same lines and point data, points moved with
  /// RibbonWarp's exact evaluation): the centerline drawn during a bend, cheap (no centerline
  /// computed). Null without centerlines or for an invalid warp.
  vtkSmartPointer<vtkPolyData> WarpedPaths(const WarpSpec& warp) const;

private:
  struct HeldSample
  {
    Vec3 position;
    double radius = 0;
    std::vector<Vec3> wall; // surface points whose nearest sample this is (a few at most)
  };
  // The held samples carried by `warp` (none: as they are) and their radii; false when nothing
  // is held or the warp is invalid.
  bool HeldSamples(const WarpSpec* warp,
    std::vector<Point3>& points,
    std::vector<double>& radii) const;
  HeldBranchMeasures MeasureBy(const WarpSpec* warp) const;
  vtkSmartPointer<vtkPolyData> StretchBy(const WarpSpec* warp) const;

  std::optional<CenterlineResult> Shown;
  std::optional<CenterlineResult> OriginalResult;
  VesselMeasurements Measures;
  std::optional<VesselComparison> Comparison;
  const void* Key = nullptr;
  vtkMTimeType KeyTime = 0;
  const void* OriginalKey = nullptr;
  vtkMTimeType OriginalTime = 0;
  std::shared_ptr<CenterlineJob> Pending;
  std::vector<HeldSample> Held; // from the ribbon's start to its end
};

/// The live warp of a grabbed session as a WarpSpec (its initial and final ribbons, R, decay,
/// screws): what BenderSession applies to the display surface.
WarpSpec LiveWarpOf(const BenderSession& session);

} // namespace bender

#endif
