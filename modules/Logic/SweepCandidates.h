#ifndef bender_SweepCandidates_h
#define bender_SweepCandidates_h

// The candidates of a what-if sweep (issue 24): a plan's warps taken to a fraction of their
// motion, or given another radius of influence, or several plans side by side. Each candidate
// is a plan of warps only; the sweep prepares each for CFD in the same way (SweepPrepare.h).
// Lengths in the plan's unit (mm).

#include "WarpPlan.h"

#include <string>
#include <vector>

namespace bender
{

/// What a sweep varies.
enum class SweepParameter
{
  Fraction, ///< the fraction of each warp's motion (0: the original, 1: the plan)
  Radius,   ///< every warp's radius of influence R, mm
  Plan      ///< one candidate per plan file (--plans)
};

/// "fraction", "radius", "plan".
std::string SweepParameterName(SweepParameter parameter);

/// `--vary NAME=FROM:TO:COUNT`: COUNT values evenly spaced from FROM to TO (both included).
struct SweepVary
{
  SweepParameter parameter = SweepParameter::Fraction;
  double from = 0.0;
  double to = 1.0;
  int count = 2; ///< [1, 1000]; 1: FROM alone
};

/// Parses "fraction=0:1.5:7" or "radius=8:16:5". Throws InputError naming the text and the
/// problem: an unknown name, not three numbers, COUNT outside [1, 1000], FROM != TO with COUNT
/// 1, a fraction outside [-2, 4], a radius not > 0.
SweepVary ParseSweepVary(const std::string& text);

/// The values of `vary`, FROM first; exact at both ends.
std::vector<double> SweepValues(const SweepVary& vary);

/// One end of the final ribbon at `fraction` of the rigid motion carrying the initial end's
/// frame onto the final end's (the minimal screw, Screw.h): 0 gives the initial end, 1 the
/// final end (both exactly as given), 1.5 half as far again along the same screw. Tangent and
/// normal come out unit and orthogonal (the geometry core's own normalisation of each).
RibbonEnd EndAtFraction(const RibbonEnd& initial, const RibbonEnd& final, double fraction);

/// `warp` with its final ribbon's two end frames at `fraction` (EndAtFraction); the initial
/// ribbon, radius, decay, twist turns and subdivision unchanged.
WarpSpec WarpAtFraction(const WarpSpec& warp, double fraction);

/// One candidate of a sweep.
struct SweepCandidate
{
  std::string id; ///< folder name in the sweep: "c03", "original"
  SweepParameter parameter = SweepParameter::Fraction;
  double value = 0.0;    ///< the fraction, the radius (mm), or the plan's index
  std::string planName;  ///< the plan file (base name) it comes from
  WarpPlan plan;         ///< its warps only (no Prepare for CFD step)
  bool original = false; ///< the surface as it is (no warp)
};

/// The candidates of a varied plan: one per value, ids c00, c01, ... in value order; a
/// fraction sweep's 0 is the original itself; a radius sweep gets an "original" candidate
/// first. Throws InputError naming the plan when it has no warp.
std::vector<SweepCandidate> MakeSweepCandidates(const WarpPlan& plan,
  const std::string& planName,
  const SweepVary& vary);

/// The candidates of several plans: "original" first, then one per plan (c00, c01, ... in the
/// order given, value = its index). Throws InputError naming a plan without a warp.
std::vector<SweepCandidate> MakePlanCandidates(const std::vector<WarpPlan>& plans,
  const std::vector<std::string>& planNames);

} // namespace bender

#endif
