#ifndef bender_CfdConvergenceStudy_h
#define bender_CfdConvergenceStudy_h

// Mesh convergence of a vessel's OpenFOAM case, measured (issue 23, bender-cli cfd-case
// --convergence): the same case written and run on three meshes, wall cell sizes H, H / r and
// H / r^2 (r >= 1.3; H the case's cell size, by default its default), in DIR/mesh-1 (the
// coarsest, the case as it would be run alone), DIR/mesh-2 and DIR/mesh-3; then, for the
// pressure drop to each outlet, the flow split of each outlet (with two outlets or more) and
// the mean wall shear stress, the three values, the Richardson-extrapolated value, the apparent
// order and the fine-mesh GCI (MeshConvergence.h), and how far mesh-1 lies from the
// extrapolated value.

#include "CfdCase.h"
#include "CfdFlowResults.h"
#include "MeshConvergence.h"
#include "Progress.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

struct CfdConvergenceOptions
{
  /// The case as for WriteOpenFoamCase; caseDirectory is the study's folder (new or empty, or
  /// replaced with force), cellSize H (0: the case's default).
  CfdCaseOptions caseOptions;
  /// Refinement ratio between consecutive meshes, >= MinimumRefinementRatio (1.3).
  double ratio = 1.3;
  /// The three runs at once at most this many (each serial; the finest first); 1: one after
  /// the other. bender-cli gives the machine's cores (at most 3).
  int jobs = 1;
  /// Allrun's progress lines, prefixed by "mesh-N: " (one at a time, from the runs' threads).
  std::function<void(const std::string&)> onLine;
  /// Cancel flag (stops OpenFOAM: Cancelled); its callback gets "mesh-N" stages.
  ProgressReporter progress;
};

/// One quantity over the three meshes.
struct CfdConvergenceQuantity
{
  std::string name; ///< "pressure drop to outlet_1", "flow split of outlet_1", "mean WSS"
  std::string unit; ///< "Pa", "%"
  MeshConvergence study;
  /// How far mesh-1 (the default mesh) is from the best estimate, as a fraction of it:
  /// (mesh-1's value - reference) / |reference|, the reference being the extrapolated value
  /// (Monotone) or, where nothing is extrapolated, mesh-3's value (Oscillatory, whose band is
  /// the values' half range, Celik et al.; Unchanged). 0 when Diverging or the reference is 0.
  double coarseDeviation = 0.0;
  /// "extrapolated", "mesh-3", or empty when there is no deviation (Diverging, reference 0).
  std::string deviationReference;
};

struct CfdConvergenceResult
{
  std::string folder;
  double ratio = 0.0;
  std::array<CfdCaseResult, 3> cases;  ///< mesh-1 (H) to mesh-3 (H / r^2)
  std::array<CfdFlowResults, 3> flows; ///< their mapped results
  std::vector<CfdConvergenceQuantity> quantities;
};

/// Writes, runs and maps the three cases and computes the studies. Throws what
/// WriteOpenFoamCase, RunOpenFoamCase and MapCfdResults throw (the folder of the failed mesh
/// named), InputError for a ratio below 1.3 or a folder that is not new or empty without force.
CfdConvergenceResult RunCfdConvergence(vtkPolyData* surface, const CfdConvergenceOptions& options);

/// The three meshes, then a table: each quantity's three values, extrapolated value, order,
/// GCI and mesh-1's deviation; a note under the table for each quantity not extrapolated.
std::string FormatCfdConvergence(const CfdConvergenceResult& result);

/// One JSON object, format "bender-mesh-convergence", version 1 (null where a study gives no
/// order or extrapolation).
std::string CfdConvergenceToJson(const CfdConvergenceResult& result);

} // namespace bender

#endif
