#ifndef bender_CfdCase_h
#define bender_CfdCase_h

// An OpenFOAM case of a labelled vessel surface (issue 11): a steady laminar simpleFoam case
// meshed by blockMesh + snappyHexMesh, written complete into a new folder, with an Allrun; and
// running it and reading the flow split, pressure drops and residuals back from the function
// objects' postProcessing files.
//
// The surface is Bender's: LPS millimetres, closed, labelled by PatchLabels.h (wall, inlet,
// outlets). The case is in metres (the STL is written by ExportSurface with unit "m"), SI
// throughout; OpenFOAM's p is kinematic (p / rho), reported here in Pa with rho.

#include "CfdFlowResults.h"
#include "CfdStageTimes.h"
#include "LabelledSurface.h"
#include "PatchLabels.h"
#include "Progress.h"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// The inlet's velocity profile: developed (Poiseuille on the inlet's shape) or uniform.
enum class CfdInletProfile
{
  Poiseuille,
  Plug
};

/// What holds the outlets: p = 0 at each (the split then follows from the geometry alone), a
/// prescribed split of the inlet's flow (given per outlet, or Murray's law Q ~ r^3 from the
/// outlets' equivalent radii), or a resistance each (steady Windkessel p = R Q).
enum class CfdOutletCondition
{
  ZeroPressure,
  Split,
  Murray,
  Resistance
};

/// One outlet's given value: a percentage of the inlet's flow (Split) or a resistance in
/// Pa s/m^3 (Resistance).
struct CfdOutletValue
{
  std::string name;
  double value = 0.0;
};

/// Options of WriteOpenFoamCase. Lengths in metres, SI units.
struct CfdCaseOptions
{
  std::string caseDirectory; ///< created; must not exist, or be empty, unless force
  /// Replace a non-empty existing caseDirectory (the old one is removed only once the new
  /// one is complete).
  bool force = false;
  /// What messages call the surface ("aneurysm.stl"); empty: "the surface".
  std::string sourceName;
  /// The inlet patch; empty: the one patch of type inlet.
  std::string inlet;
  /// Volumetric flow rate at the inlet, m^3/s (1e-5 = 600 ml/min): the same flow whatever
  /// the inlet's area, so that compared shapes carry the same flow.
  double flowRate = 1e-5;
  /// > 0: the inlet's mean velocity instead, m/s (the flow is velocity x the inlet's area).
  double velocity = 0.0;
  /// The inlet's profile: Poiseuille (timeVaryingMappedFixedValue, constant/boundaryData) or
  /// plug (flowRateInletVelocity, or surfaceNormalFixedValue with a velocity).
  CfdInletProfile inletProfile = CfdInletProfile::Poiseuille;
  /// The outlets' condition; outletValues gives each outlet's share (Split, percent) or
  /// resistance (Resistance, Pa s/m^3), every outlet once.
  CfdOutletCondition outlets = CfdOutletCondition::ZeroPressure;
  std::vector<CfdOutletValue> outletValues;
  /// Prism layers on the wall (snappyHexMesh addLayers); 0: none.
  int layers = 3;
  /// The wall's base cell size H, m (the background mesh is twice as coarse, refined once at
  /// the surface; ends and narrower stretches of the lumen are refined further, CfdMeshGrading.h);
  /// 0: the largest end's equivalent diameter / cellsAcross.
  double cellSize = 0.0;
  /// The wall cells across every end (and, within kCfdWallCellsMargin, across the lumen
  /// everywhere on the wall) that the grading gives; 0: 8 (kCfdDefaultCellsAcross), or with a
  /// cellSize, the smallest end's diameter / cellSize (that size everywhere the lumen is as
  /// wide as the smallest end, narrower places refined). The levels follow from cellsAcross x
  /// cellSize: a convergence study's finer meshes, H / r with r x the cells across, keep
  /// mesh-1's levels in the same places.
  double cellsAcross = 0.0;
  /// Kinematic viscosity, m^2/s (blood: 3.5e-6).
  double viscosity = 3.5e-6;
  /// Density used to report pressures in Pa, kg/m^3 (blood: 1060).
  double density = 1060.0;
  /// simpleFoam's iteration limit (endTime); the residual control may stop it earlier.
  int iterations = 1000;
  /// Processors of decomposeParDict; > 1: Allrun runs simpleFoam with mpirun.
  int processors = 1;
  /// decomposeParDict's method: "hierarchical" (default: boxes split along the longest axes,
  /// needs no library; Debian's openfoam 1912 is built without scotch), "scotch" (better
  /// balance where OpenFOAM has it: clusters) or "simple".
  std::string decomposition = "hierarchical";
  /// Base name of the surface in constant/triSurface.
  std::string surfaceName = "vessel";
};

/// One patch of the case.
struct CfdPatch
{
  std::string name;
  PatchType type = PatchType::Wall;
  long long triangles = 0;
  double area = 0.0;              ///< m^2
  std::array<double, 3> centre{}; ///< m, LPS
  std::array<double, 3> normal{}; ///< outward unit normal (ends only)
  double diameter = 0.0;          ///< equivalent diameter 2 sqrt(area / pi), m
};

/// How one outlet is held (CfdOutletSettings, CfdBoundaryConditions.h).
struct CfdOutletSetting
{
  std::string name;
  double percent = 0.0;          ///< Split, Murray: the prescribed share of the inlet's flow
  double flowRate = 0.0;         ///< Split, Murray: that share, m^3/s
  double resistance = 0.0;       ///< Resistance: R, Pa s/m^3 (p = R Q)
  bool pressureReference = true; ///< held at p = 0 (ZeroPressure; the largest share of a split)
};

/// The wall cells across one end: its equivalent diameter over its cell size.
struct CfdEndCells
{
  std::string name;
  int level = 1;         ///< snappyHexMesh's level on the end (1: the wall's base)
  double cellSize = 0.0; ///< m
  double cellsAcross = 0.0;
};

/// A stretch of the lumen refined beyond the wall's base: the wall triangles too narrow for
/// the level below, and the lumen within `distance` of them (snappyHexMesh's distance mode).
struct CfdRefinementRegion
{
  std::string name; ///< its surface: constant/triSurface/<name>.stl
  int level = 2;
  double cellSize = 0.0; ///< m
  double distance = 0.0; ///< m: the largest local radius among its triangles
  long long triangles = 0;
};

/// How the mesh is graded by the local width of the lumen (CfdMeshGrading.h).
struct CfdMeshGrading
{
  double cellsAcross = 0.0;                 ///< asked for at every end
  std::vector<CfdEndCells> ends;            ///< in patch order
  std::vector<CfdRefinementRegion> regions; ///< levels above the base, coarsest first
  double wallCellsAcross = 0.0;             ///< the fewest across the lumen on the wall
  double narrowestDiameter = 0.0;           ///< the lumen's narrowest on the wall, m
  std::array<double, 3> narrowestAt{};      ///< where: that wall triangle's centre, m (LPS)
  double narrowestCellsAcross = 0.0;        ///< the cells across it there
};

/// What WriteOpenFoamCase wrote.
struct CfdCaseResult
{
  std::string caseDirectory;
  std::vector<CfdPatch> patches; ///< in label order; the inlet has type Inlet, other ends Outlet
  std::string inlet;
  double cellSize = 0.0;                ///< the wall's base cell size H, m
  CfdMeshGrading grading;               ///< the cells across each end and the lumen
  double backgroundCellSize = 0.0;      ///< blockMesh's, m
  std::array<int, 3> backgroundCells{}; ///< blockMesh's cells per axis
  std::array<double, 3> insidePoint{};  ///< locationInMesh, m
  double inletFlowRate = 0.0;           ///< m^3/s (velocity x inlet area with a velocity)
  double inletVelocity = 0.0;           ///< mean inlet velocity, m/s
  double reynolds = 0.0;                ///< mean inlet velocity x inlet diameter / nu
  CfdInletProfile inletProfile = CfdInletProfile::Poiseuille;
  double inletPeakToMean = 1.0; ///< u_max / u_mean of the inlet's profile as written
  CfdOutletCondition outletCondition = CfdOutletCondition::ZeroPressure;
  std::vector<CfdOutletSetting> outlets; ///< in patch order
  int layers = 0;                        ///< prism layers asked for on the wall
  std::vector<std::string> written;      ///< files, relative to the case folder
};

/// Writes the case: constant/triSurface/<name>.stl (multi-solid ASCII in metres, one solid per
/// patch, through ExportSurface), system/{blockMeshDict, surfaceFeatureExtractDict,
/// snappyHexMeshDict, controlDict, fvSchemes, fvSolution, decomposeParDict},
/// constant/{transportProperties, turbulenceProperties}, 0/{U, p}, Allrun (executable),
/// bender-case.json (the patches and settings, read back by ReadCfdResults). All or nothing:
/// the case is assembled in a temporary sibling folder and renamed into place.
/// Throws InputError naming the surface or option: no triangles, not closed, fewer than two
/// ends, no inlet (or an unknown --inlet), options out of range, an existing non-empty
/// folder without force, an unwritable folder.
CfdCaseResult WriteOpenFoamCase(vtkPolyData* surface, const CfdCaseOptions& options);
/// WriteOpenFoamCase with the patch table already read (ReadLabelledSurface, after the clip):
/// the same case, the labels parsed once for the checks, the measures and the export.
CfdCaseResult WriteOpenFoamCase(const LabelledSurface& surface, const CfdCaseOptions& options);

/// Where OpenFOAM is: empty when simpleFoam, blockMesh, surfaceFeatureExtract, snappyHexMesh
/// and checkMesh are on PATH (and mpirun when processors > 1); else what is missing, one line.
std::string FindOpenFoamProblem(int processors = 1);

/// Flow through one patch after a run.
struct CfdPatchFlow
{
  std::string name;
  PatchType type = PatchType::Wall;
  double flowRate = 0.0;       ///< m^3/s, positive out of the domain
  double percentOfInlet = 0.0; ///< outlets: flowRate / inlet flow x 100
  double pressure = 0.0;       ///< area-averaged, Pa (rho x kinematic p)
  double pressureDrop = 0.0;   ///< inlet pressure - this pressure, Pa
};

/// The prism layers snappyHexMesh added on one patch (its final layer report).
struct CfdPatchLayers
{
  std::string name;
  long long faces = 0;           ///< faces of the patch
  double layers = 0.0;           ///< layers per face, on average
  double coveragePercent = 0.0;  ///< layers / the layers asked for x 100
  double thicknessPercent = 0.0; ///< overall thickness / the thickness asked for x 100
};

/// What the meshers reported (log.snappyHexMesh, log.checkMesh).
struct CfdMeshReport
{
  long long cells = 0;                ///< checkMesh's cell count
  int layersRequested = 0;            ///< prism layers asked for on the wall (bender-case.json)
  std::vector<CfdPatchLayers> layers; ///< the patches that were given layers
  long long facesExtruded = 0;        ///< faces that got layers, of
  long long facesToExtrude = 0;       ///< the faces of the patches asked to get them
  bool meshOk = false;                ///< checkMesh said "Mesh OK."
  std::string failedChecks;           ///< checkMesh's failed checks ("***" lines), "; "-joined
};

/// What a run gave (read from postProcessing).
struct CfdRunResult
{
  int iterations = 0;                ///< last iteration written by the function objects
  bool converged = false;            ///< simpleFoam met the residual control (its log says so)
  double inletFlowRate = 0.0;        ///< m^3/s, into the domain
  double massImbalance = 0.0;        ///< |sum of the flow through every patch| / inlet flow
  std::vector<CfdPatchFlow> patches; ///< inlet and outlets, in label order
  /// Initial residuals of the last iteration: {"Ux", 1e-4}, {"p", ...}.
  std::vector<std::pair<std::string, double>> residuals;
  /// The results mapped onto the surface and written to CASE/results (MapCfdResults), after
  /// a run of the solver by RunOpenFoamCase; empty from ReadCfdResults.
  std::optional<CfdFlowResults> flow;
  /// The mesh's report (ReadCfdMeshReport, CfdMeshing.h) when RunOpenFoamCase meshed it.
  CfdMeshReport mesh;
  /// How long RunOpenFoamCase's stages took (wall clock); zero from ReadCfdResults.
  CfdStageTimes stages;
};

/// Options of RunOpenFoamCase.
struct CfdRunOptions
{
  /// Which part of the Allrun: everything, the mesh (up to checkMesh), or simpleFoam alone on
  /// the mesh already made.
  enum class Steps
  {
    All,
    Mesh,
    Solve
  };
  Steps steps = Steps::All;
  /// Lines of the Allrun's progress ("bender Allrun: snappyHexMesh").
  std::function<void(const std::string&)> onLine;
  /// Its cancel flag stops the Allrun and the programs it started (RunOpenFoamCase throws
  /// Cancelled); its callback is not used.
  ProgressReporter progress;
};

/// Runs the case's Allrun (serial or with mpirun, as written; its output also in log.Allrun),
/// reads the results and maps them onto the surface (MapCfdResults: CASE/results and `flow`;
/// an empty result for Steps::Mesh). Throws EnvironmentError when OpenFOAM is not installed or
/// Allrun cannot be started, Error naming the failed step and its log (a solver that failed or
/// was killed), MapCfdResults' errors (a diverged solution, results that do not match the
/// surface), Cancelled when options.progress was cancelled. CASE/results is replaced only by a
/// complete new one.
CfdRunResult RunOpenFoamCase(const std::string& caseDirectory, const CfdRunOptions& options = {});

/// The patches of the OpenFOAM mesh (constant/polyMesh/boundary) with their face counts, in
/// file order. Throws InputError when the file is missing or unreadable.
std::vector<std::pair<std::string, long long>> ReadMeshPatches(const std::string& caseDirectory);

/// Reads the results of a case already run (postProcessing/flow_*, pressure_*, solverInfo).
/// Throws InputError naming the missing or unreadable file.
CfdRunResult ReadCfdResults(const std::string& caseDirectory);

/// The result as one JSON object (case, patches, run).
std::string CfdToJson(const CfdCaseResult& written, const CfdRunResult* run);

/// "converged in N iterations; initial residuals Ux 1e-05 ..." when simpleFoam met the residual
/// control, else "stopped at N iterations, residuals ... (not converged: the residual control
/// was not met)".
std::string CfdRunStatus(const CfdRunResult& run);

/// The result as lines of text for bender-cli.
std::string FormatCfdCase(const CfdCaseResult& written);
std::string FormatCfdRun(const CfdRunResult& run);

} // namespace bender

#endif
