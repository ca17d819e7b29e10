#ifndef bender_CfdFlowResults_h
#define bender_CfdFlowResults_h

// The flow results of a case that has run (issue 23, "Results back on the vessel"): the case's
// last time read with VTK's vtkOpenFOAMReader and mapped onto the CFD-ready surface, and the
// figures a surgeon and a CFD engineer compare.
//
// MapCfdResults writes, all or nothing (a temporary sibling folder renamed into place; the
// previous CASE/results kept when anything fails):
//  - CASE/results/surface.vtp: the case's labelled surface (LPS, mm; CellEntityIds and the
//    patch names kept) with point data
//      "Pressure" (Pa, relative to the area-weighted mean pressure of the outlets),
//      "WallShearStress" (3-vector, Pa: OpenFOAM's kinematic wallShearStress x density;
//        OpenFOAM's sign, the stress on the fluid, opposite to the near-wall flow; zero on
//        the ends),
//      "WallShearStressMagnitude" (Pa);
//  - CASE/results/volume.vtu: the mesh's cells, points in mm (LPS), point and cell data "U"
//    (m/s) and "Pressure" (Pa, as above), for streamlines;
//  - CASE/results/flow.json: CfdFlowResultsToJson (format "bender-flow-results", version 1).

#include "PatchLabels.h"

#include <string>
#include <utility>
#include <vector>

class vtkPolyData;

namespace bender
{

/// The file names inside CASE/results.
inline constexpr const char* kCfdResultsFolder = "results";
inline constexpr const char* kCfdSurfaceResults = "surface.vtp";
inline constexpr const char* kCfdVolumeResults = "volume.vtu";
inline constexpr const char* kCfdFlowJson = "flow.json";

/// Point data names of surface.vtp (and volume.vtu's "U").
inline constexpr const char* kPressureArrayName = "Pressure";
inline constexpr const char* kWallShearStressArrayName = "WallShearStress";
inline constexpr const char* kWallShearStressMagnitudeArrayName = "WallShearStressMagnitude";
inline constexpr const char* kVelocityArrayName = "U";

/// The WSS thresholds of the low / high areas, Pa (low: < 0.4, atherosclerosis-prone;
/// high: > 15, endothelial damage).
inline constexpr double kLowWallShearStressPa = 0.4;
inline constexpr double kHighWallShearStressPa = 15.0;

/// The run of simpleFoam.
struct CfdRunSummary
{
  int iterations = 0;     ///< the last iteration
  int iterationLimit = 0; ///< controlDict's endTime
  /// True only when simpleFoam met the residual control ("SIMPLE solution converged").
  bool converged = false;
  /// Initial residuals of the last iteration: {"Ux", 1e-4}, {"p", ...}.
  std::vector<std::pair<std::string, double>> residuals;
  /// CfdRunStatus: "converged in N iterations; initial residuals ..." or "stopped at N
  /// iterations, residuals Ux 2e-3 ... (not converged: ...)".
  std::string status;
};

/// One end of the vessel.
struct CfdEndFlow
{
  std::string name;                  ///< the patch name ("inlet", "outlet_1")
  PatchType role = PatchType::Inlet; ///< Inlet or Outlet
  double flowRateMlPerMin = 0.0;     ///< through the end, positive along the flow (in at the
                                     ///< inlet, out at the outlets)
  double splitPercent = 0.0;         ///< outlets: flow / inlet flow x 100; the inlet: 100
  double meanPressurePa = 0.0;       ///< area-weighted, relative to the outlets' mean
  double pressureDropPa = 0.0;       ///< the inlet's mean pressure - this end's (inlet: 0)
};

/// Wall shear stress statistics over the wall (the surface's wall patch, triangles weighted
/// by area; a triangle's value is the mean of its corners' WallShearStressMagnitude).
struct CfdWallShearStats
{
  double meanPa = 0.0;         ///< area-weighted mean
  double maxPa = 0.0;          ///< the largest value at a wall point
  double percentile99Pa = 0.0; ///< 99 % of the wall area has a lower value
  double lowAreaMm2 = 0.0;     ///< wall area with WSS < kLowWallShearStressPa
  double highAreaMm2 = 0.0;    ///< wall area with WSS > kHighWallShearStressPa
  double wallAreaMm2 = 0.0;    ///< the whole wall
};

/// The settings of the case (from bender-case.json), SI with the unit named.
struct CfdFlowSettings
{
  double densityKgPerM3 = 0.0;
  double viscosityM2PerS = 0.0;
  double inletFlowRateMlPerMin = 0.0; ///< as prescribed
  double inletVelocityMPerS = 0.0;    ///< mean, as prescribed
  double reynolds = 0.0;
  double cellSizeMm = 0.0; ///< at the wall
  int processors = 1;
};

/// Everything flow.json holds.
struct CfdFlowResults
{
  std::string caseDirectory; ///< as given to MapCfdResults (not written to flow.json)
  double time = 0.0;         ///< the OpenFOAM time mapped (the last one written)
  CfdRunSummary run;
  std::vector<CfdEndFlow> ends; ///< the inlet first, then the outlets in label order
  double inletFlowRateMlPerMin = 0.0;
  double massImbalancePercent = 0.0; ///< |sum of the flow through the ends| / inlet flow x 100
  CfdWallShearStats wallShearStress;
  long long meshCells = 0;
  CfdFlowSettings settings;
};

/// Reads the case's last time with vtkOpenFOAMReader, maps it onto the case's labelled
/// surface (constant/triSurface/<name>.vtp) and writes CASE/results (surface.vtp, volume.vtu,
/// flow.json) all or nothing; returns what flow.json holds. Throws InputError naming the file
/// or patch (no labelled surface in the case, a patch of the surface missing from the mesh:
/// "results do not match the surface"), Error when a field holds NaN or infinity ("the
/// solution diverged: p is not finite at time N"), when no time was written, or when the
/// results cannot be written; CASE/results is then left as it was.
CfdFlowResults MapCfdResults(const std::string& caseDirectory);

/// Reads CASE/results/flow.json back. Throws InputError (one line naming the file) when it is
/// missing, not JSON, of another format or version, or lacks a field.
CfdFlowResults ReadCfdFlowResults(const std::string& caseDirectory);

/// The results as flow.json's JSON text (format "bender-flow-results", version 1; every number
/// with its unit in its key or in "units").
std::string CfdFlowResultsToJson(const CfdFlowResults& results);

/// The figures as lines of text for bender-cli (the run's status, each end, the WSS).
std::string FormatCfdFlowResults(const CfdFlowResults& results);
/// The WSS statistics and where the results are, as lines of text (the part of
/// FormatCfdFlowResults that FormatCfdRun adds to the flow split and the mesh).
std::string FormatCfdWallShearStress(const CfdFlowResults& results);

/// The WSS statistics of a labelled surface in mm carrying point data
/// WallShearStressMagnitude (Pa), over its wall triangles (CellEntityIds == 1; the whole
/// surface when it has no labels). Throws InputError when the array is missing.
CfdWallShearStats ComputeWallShearStats(vtkPolyData* surface);

/// The area-weighted percentile (0-100) of values with weights (the smallest value v such
/// that the weights of the values <= v reach percent of the total). Empty: 0.
double WeightedPercentile(std::vector<std::pair<double, double>> valueWeights, double percent);

} // namespace bender

#endif
