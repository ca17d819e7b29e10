#include "CfdDictionaries.h"

#include "CfdPatches.h"

#include <cmath>
#include <functional>
#include <iomanip>
#include <locale>
#include <sstream>

namespace bender
{

std::string CfdNumber(double v)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::setprecision(10) << v;
  return s.str();
}

std::string CfdShort(double v, int digits)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::setprecision(digits) << v;
  return s.str();
}

namespace
{

std::string Vec(const std::array<double, 3>& v)
{
  return "(" + CfdNumber(v[0]) + " " + CfdNumber(v[1]) + " " + CfdNumber(v[2]) + ")";
}

std::string FoamHeader(const std::string& cls,
  const std::string& location,
  const std::string& object)
{
  std::string h =
    "/*--------------------------------*- C++ -*----------------------------------*\\\n"
    "  Written by Bender (bender-cli cfd-case) for OpenFOAM v1912 or later.\n"
    "\\*---------------------------------------------------------------------------*/\n"
    "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " +
    cls + ";\n";
  if (!location.empty())
  {
    h += "    location    \"" + location + "\";\n";
  }
  h += "    object      " + object + ";\n}\n\n";
  return h;
}

/// Subdomains per axis, product `processors`: each prime factor (largest first) goes to the
/// axis whose pieces are longest.
std::array<int, 3> SplitAxes(int processors, const std::array<double, 3>& extent)
{
  std::vector<int> factors;
  for (int n = processors, f = 2; n > 1;)
  {
    if (n % f == 0)
    {
      factors.push_back(f);
      n /= f;
    }
    else
    {
      f = f * f > n ? n : f + 1;
    }
  }
  std::array<int, 3> split{ 1, 1, 1 };
  for (auto f = factors.rbegin(); f != factors.rend(); ++f)
  {
    std::size_t axis = 0;
    for (std::size_t k = 1; k < 3; ++k)
    {
      if (extent[k] / split[k] > extent[axis] / split[axis])
      {
        axis = k;
      }
    }
    split[axis] *= *f;
  }
  return split;
}

// A field of 0/: the header, `head` (dimensions, internal field), then each patch's boundary
// condition as `condition` writes it.
std::string InitialField(const std::string& cls,
  const std::string& object,
  const std::string& head,
  const std::vector<CfdPatch>& patches,
  const std::function<std::string(const CfdPatch&)>& condition)
{
  std::string s = FoamHeader(cls, "0", object) + head + "boundaryField\n{\n";
  for (const auto& p : patches)
  {
    s += "    " + p.name + "\n    {\n" + condition(p) + "    }\n";
  }
  return s + "}\n";
}

} // namespace

std::string BlockMeshDict(const std::array<double, 3>& origin,
  double h,
  const std::array<int, 3>& n)
{
  std::array<double, 3> hi{};
  for (std::size_t k = 0; k < 3; ++k)
  {
    hi[k] = origin[k] + h * n[k];
  }
  std::ostringstream s;
  s << FoamHeader("dictionary", "system", "blockMeshDict");
  s << "// The background box: the surface's bounds plus a margin, cubes of " << CfdNumber(h)
    << " m.\nconvertToMeters 1;\n\nvertices\n(\n";
  const double xs[2] = { origin[0], hi[0] };
  const double ys[2] = { origin[1], hi[1] };
  const double zs[2] = { origin[2], hi[2] };
  const int order[8][3] = { { 0, 0, 0 },
    { 1, 0, 0 },
    { 1, 1, 0 },
    { 0, 1, 0 },
    { 0, 0, 1 },
    { 1, 0, 1 },
    { 1, 1, 1 },
    { 0, 1, 1 } };
  for (const auto& o : order)
  {
    s << "    (" << CfdNumber(xs[o[0]]) << " " << CfdNumber(ys[o[1]]) << " " << CfdNumber(zs[o[2]])
      << ")\n";
  }
  s << ");\n\nblocks\n(\n    hex (0 1 2 3 4 5 6 7) (" << n[0] << " " << n[1] << " " << n[2]
    << ") simpleGrading (1 1 1)\n);\n\nedges\n(\n);\n\n"
       "boundary\n(\n    background\n    {\n        type patch;\n        faces\n        (\n"
       "            (0 3 2 1) (4 5 6 7) (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)\n"
       "        );\n    }\n);\n\nmergePatchPairs\n(\n);\n";
  return s.str();
}

std::string SurfaceFeatureExtractDict(const std::string& stl)
{
  return FoamHeader("dictionary", "system", "surfaceFeatureExtractDict") + stl +
    "\n{\n"
    "    extractionMethod    extractFromSurface;\n"
    "    extractFromSurfaceCoeffs\n    {\n"
    "        // Edges between faces meeting at more than 180 - includedAngle degrees: the rims\n"
    "        // where the ends meet the wall.\n"
    "        includedAngle   150;\n    }\n"
    "    subsetFeatures\n    {\n        nonManifoldEdges    no;\n        openEdges   yes;\n    }\n"
    "    writeObj            no;\n"
    "}\n";
}

std::string SnappyHexMeshDict(const std::string& surfaceName,
  const std::vector<CfdPatch>& patches,
  const std::array<double, 3>& inside,
  double cellSize)
{
  std::ostringstream s;
  s << FoamHeader("dictionary", "system", "snappyHexMeshDict");
  s << "castellatedMesh true;\nsnap            true;\naddLayers       false;\n\n";
  s << "geometry\n{\n    " << surfaceName << ".stl\n    {\n        type triSurfaceMesh;\n"
    << "        name " << surfaceName << ";\n        regions\n        {\n";
  for (const auto& p : patches)
  {
    s << "            " << p.name << " { name " << p.name << "; }\n";
  }
  s << "        }\n    }\n}\n\n";
  s << "castellatedMeshControls\n{\n"
       "    maxLocalCells       2000000;\n    maxGlobalCells      8000000;\n"
       "    minRefinementCells  0;\n    maxLoadUnbalance    0.10;\n"
       "    nCellsBetweenLevels 3;\n\n"
       "    features\n    (\n        { file \""
    << surfaceName
    << ".eMesh\"; level 1; }\n    );\n\n"
       "    // One level of refinement at the surface: cells of "
    << CfdNumber(cellSize) << " m at the wall.\n    refinementSurfaces\n    {\n        "
    << surfaceName
    << "\n        {\n            level (1 1);\n            patchInfo { type wall; }\n"
       "            regions\n            {\n";
  for (const auto& p : patches)
  {
    s << "                " << p.name << " { level (1 1); patchInfo { type "
      << (IsEndPatch(p.type) ? "patch" : "wall") << "; } }\n";
  }
  s << "            }\n        }\n    }\n\n"
       "    resolveFeatureAngle 30;\n    refinementRegions\n    {\n    }\n\n"
       "    // A point inside the lumen, behind the inlet.\n"
       "    locationInMesh "
    << Vec(inside)
    << ";\n    allowFreeStandingZoneFaces true;\n}\n\n"
       "snapControls\n{\n"
       "    nSmoothPatch        3;\n    tolerance           2.0;\n    nSolveIter          100;\n"
       "    nRelaxIter          5;\n    nFeatureSnapIter    10;\n"
       "    implicitFeatureSnap false;\n    explicitFeatureSnap true;\n"
       "    multiRegionFeatureSnap true;\n}\n\n"
       "addLayersControls\n{\n"
       "    relativeSizes       true;\n    layers\n    {\n    }\n"
       "    expansionRatio      1.2;\n    finalLayerThickness 0.5;\n    minThickness        0.1;\n"
       "    nGrow               0;\n    featureAngle        60;\n    slipFeatureAngle    30;\n"
       "    nRelaxIter          3;\n    nSmoothSurfaceNormals 1;\n    nSmoothNormals      3;\n"
       "    nSmoothThickness    10;\n    maxFaceThicknessRatio 0.5;\n"
       "    maxThicknessToMedialRatio 0.3;\n    minMedialAxisAngle  90;\n"
       "    nBufferCellsNoExtrude 0;\n    nLayerIter          50;\n}\n\n"
       "meshQualityControls\n{\n"
       "    maxNonOrtho         65;\n    maxBoundarySkewness 20;\n    maxInternalSkewness 4;\n"
       "    maxConcave          80;\n    minVol              "
    << CfdNumber(std::pow(0.01 * cellSize, 3))
    << ";\n    minTetQuality       1e-15;\n    minArea             -1;\n"
       "    minTwist            0.02;\n    minDeterminant      0.001;\n"
       "    minFaceWeight       0.05;\n    minVolRatio         0.01;\n"
       "    minTriangleTwist    -1;\n    nSmoothScale        4;\n    errorReduction      0.75;\n"
       "    relaxed\n    {\n        maxNonOrtho     75;\n    }\n}\n\n"
       "mergeTolerance 1e-6;\n";
  return s.str();
}

std::string ControlDict(const std::vector<CfdPatch>& patches, int iterations)
{
  std::ostringstream s;
  s << FoamHeader("dictionary", "system", "controlDict");
  s << "application     simpleFoam;\nstartFrom       startTime;\nstartTime       0;\n"
       "stopAt          endTime;\n// The iteration limit; the residual control of fvSolution "
       "stops earlier when converged.\nendTime         "
    << iterations << ";\ndeltaT          1;\nwriteControl    timeStep;\nwriteInterval   "
    << iterations
    << ";\npurgeWrite      0;\nwriteFormat     ascii;\nwritePrecision  8;\n"
       "writeCompression off;\ntimeFormat      general;\ntimePrecision   6;\n"
       "runTimeModifiable true;\n\n"
       "// Per end: the volumetric flow out of the domain (sum of phi, m^3/s; negative = in) and\n"
       "// the area-averaged kinematic pressure (p / rho, m^2/s^2), every iteration, in\n"
       "// postProcessing/<name>/0/surfaceFieldValue.dat; the solver residuals in\n"
       "// postProcessing/solverInfo/0/solverInfo.dat.\nfunctions\n{\n";
  for (const auto& p : patches)
  {
    if (!IsEndPatch(p.type))
    {
      continue;
    }
    for (const bool flow : { true, false })
    {
      s << "    " << (flow ? "flow_" : "pressure_") << p.name
        << "\n    {\n        type            surfaceFieldValue;\n"
           "        libs            (\"libfieldFunctionObjects.so\");\n"
           "        writeControl    timeStep;\n        writeInterval   1;\n"
           "        log             false;\n        writeFields     false;\n"
           "        regionType      patch;\n        name            "
        << p.name << ";\n        operation       " << (flow ? "sum" : "areaAverage")
        << ";\n        fields          (" << (flow ? "phi" : "p") << ");\n    }\n";
    }
  }
  s << "    solverInfo\n    {\n        type            solverInfo;\n"
       "        libs            (\"libutilityFunctionObjects.so\");\n"
       "        writeControl    timeStep;\n        writeInterval   1;\n"
       "        fields          (U p);\n        writeResidualFields no;\n    }\n"
       "    // The wall shear stress (kinematic, m^2/s^2) on every wall patch, written with the\n"
       "    // fields: MapCfdResults maps it onto the surface (x density: Pa).\n"
       "    wallShearStress\n    {\n        type            wallShearStress;\n"
       "        libs            (\"libfieldFunctionObjects.so\");\n"
       "        writeControl    writeTime;\n        log             false;\n    }\n}\n";
  return s.str();
}

std::string FvSchemes()
{
  return FoamHeader("dictionary", "system", "fvSchemes") +
    "ddtSchemes\n{\n    default         steadyState;\n}\n\n"
    "gradSchemes\n{\n    default         Gauss linear;\n    grad(U)         cellLimited Gauss "
    "linear 1;\n}\n\n"
    "divSchemes\n{\n    default         none;\n"
    "    div(phi,U)      bounded Gauss linearUpwind grad(U);\n"
    "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n\n"
    "laplacianSchemes\n{\n    default         Gauss linear limited corrected 0.33;\n}\n\n"
    "interpolationSchemes\n{\n    default         linear;\n}\n\n"
    "snGradSchemes\n{\n    default         limited corrected 0.33;\n}\n";
}

std::string FvSolution()
{
  return FoamHeader("dictionary", "system", "fvSolution") +
    "solvers\n{\n"
    "    p\n    {\n        solver          GAMG;\n        smoother        GaussSeidel;\n"
    "        tolerance       1e-07;\n        relTol          0.01;\n    }\n\n"
    "    U\n    {\n        solver          smoothSolver;\n        smoother        "
    "symGaussSeidel;\n        tolerance       1e-08;\n        relTol          0.1;\n    }\n}\n\n"
    "SIMPLE\n{\n    nNonOrthogonalCorrectors 1;\n    consistent      yes;\n\n"
    "    // Stop when the initial residuals fall below these.\n"
    "    residualControl\n    {\n        p               1e-4;\n        U               1e-5;\n"
    "    }\n}\n\n"
    "relaxationFactors\n{\n    fields\n    {\n        p               0.5;\n    }\n"
    "    equations\n    {\n        U               0.7;\n    }\n}\n";
}

std::string DecomposeParDict(int processors,
  const std::string& method,
  const std::array<double, 3>& extent)
{
  const std::array<int, 3> n = SplitAxes(processors, extent);
  const std::string coefficients =
    "(" + std::to_string(n[0]) + " " + std::to_string(n[1]) + " " + std::to_string(n[2]) + ")";
  return FoamHeader("dictionary", "system", "decomposeParDict") + "numberOfSubdomains " +
    std::to_string(processors) +
    ";\n\n// hierarchical needs no library; scotch balances better where OpenFOAM was built\n"
    "// with it (Debian's openfoam 1912 was not: its scotchDecomp is a stub).\n"
    "method          " +
    method +
    ";\n\n"
    "hierarchicalCoeffs\n{\n    n               " +
    coefficients +
    ";\n    order           xyz;\n}\n\n"
    "simpleCoeffs\n{\n    n               " +
    coefficients + ";\n}\n";
}

std::string TransportProperties(double nu)
{
  return FoamHeader("dictionary", "constant", "transportProperties") +
    "// Newtonian blood by default (3.5e-6 m^2/s = 3.7 mPa s / 1060 kg/m^3).\n"
    "transportModel  Newtonian;\n\nnu              [0 2 -1 0 0 0 0] " +
    CfdNumber(nu) + ";\n";
}

std::string TurbulenceProperties()
{
  return FoamHeader("dictionary", "constant", "turbulenceProperties") +
    "simulationType  laminar;\n";
}

std::string VelocityField(const std::vector<CfdPatch>& patches, const CfdCaseOptions& options)
{
  return InitialField("volVectorField",
    "U",
    "dimensions      [0 1 -1 0 0 0 0];\n\ninternalField   uniform (0 0 0);\n\n",
    patches,
    [&options](const CfdPatch& p) -> std::string
    {
      if (p.type == PatchType::Wall)
      {
        return "        type            noSlip;\n";
      }
      if (p.type == PatchType::Inlet && options.flowRate > 0.0)
      {
        return "        type            flowRateInletVelocity;\n"
               "        volumetricFlowRate constant " +
          CfdNumber(options.flowRate) +
          ";  // m^3/s\n        extrapolateProfile no;\n        value           uniform (0 0 "
          "0);\n";
      }
      if (p.type == PatchType::Inlet)
      {
        return "        // Uniform, normal to the inlet, into the domain (m/s).\n"
               "        type            surfaceNormalFixedValue;\n        refValue        "
               "uniform " +
          CfdNumber(-options.velocity) + ";\n        value           uniform (0 0 0);\n";
      }
      return "        type            inletOutlet;\n        inletValue      uniform (0 0 0);\n"
             "        value           uniform (0 0 0);\n";
    });
}

std::string PressureField(const std::vector<CfdPatch>& patches)
{
  return InitialField("volScalarField",
    "p",
    "// Kinematic pressure p / rho (m^2/s^2).\ndimensions      [0 2 -2 0 0 0 0];\n\n"
    "internalField   uniform 0;\n\n",
    patches,
    [](const CfdPatch& p) -> std::string
    {
      return p.type == PatchType::Outlet
        ? "        type            fixedValue;\n        value           uniform 0;\n"
        : "        type            zeroGradient;\n";
    });
}

std::string Allrun(int processors)
{
  std::ostringstream s;
  s << "#!/bin/sh\n"
       "# Written by Bender (bender-cli cfd-case): meshes this case and solves it with OpenFOAM\n"
       "# (v1912 or later; Debian: apt-get install openfoam).\n"
       "#   ./Allrun        blockMesh, surfaceFeatureExtract, snappyHexMesh, checkMesh, "
       "simpleFoam\n"
       "#   ./Allrun mesh   up to checkMesh\n"
       "#   ./Allrun solve  simpleFoam on the mesh already made\n"
       "# Each step logs to log.<step>. Results: postProcessing/flow_*, pressure_*, solverInfo.\n"
       "cd \"$(dirname \"$0\")\" || exit 1\n"
       "# Debian's openfoam has its programs in /usr/bin and needs only WM_PROJECT_DIR.\n"
       "if [ -z \"${WM_PROJECT_DIR:-}\" ] && [ -f /usr/share/openfoam/etc/controlDict ]; then\n"
       "    WM_PROJECT_DIR=/usr/share/openfoam\n    export WM_PROJECT_DIR\nfi\n"
       "processors="
    << processors
    << "\nwhat=\"${1:-all}\"\n\n"
       "step()\n{\n    log=\"log.$1\"\n    shift\n    echo \"bender Allrun: $*\"\n"
       "    if ! \"$@\" > \"$log\" 2>&1; then\n"
       "        echo \"bender Allrun: $1 failed, see $log:\" >&2\n"
       "        tail -n 5 \"$log\" >&2\n        exit 1\n    fi\n}\n\n"
       "# The times of an earlier run (every numeric folder but 0): a re-run starts clean.\n"
       "clean_times()\n{\n    for d in *; do\n        case \"$d\" in\n"
       "            0 | *[!0-9.e+-]*) ;;\n            [0-9]*) rm -rf \"$d\" ;;\n"
       "        esac\n    done\n}\n\n"
       "if [ \"$what\" = all ] || [ \"$what\" = mesh ]; then\n"
       "    rm -rf constant/polyMesh constant/extendedFeatureEdgeMesh postProcessing processor*\n"
       "    clean_times\n"
       "    step blockMesh blockMesh\n"
       "    step surfaceFeatureExtract surfaceFeatureExtract\n"
       "    step snappyHexMesh snappyHexMesh -overwrite\n"
       "    step checkMesh checkMesh\n"
       "    if ! grep -q \"Mesh OK\" log.checkMesh; then\n"
       "        echo \"bender Allrun: checkMesh found problems, see log.checkMesh\" >&2\n"
       "        exit 1\n    fi\nfi\n\n"
       "if [ \"$what\" = all ] || [ \"$what\" = solve ]; then\n"
       "    rm -rf postProcessing processor*\n    clean_times\n"
       "    if [ \"$processors\" -gt 1 ]; then\n"
       "        # Open MPI refuses root unless told (containers run as root).\n"
       "        if [ \"$(id -u)\" = 0 ]; then\n"
       "            OMPI_ALLOW_RUN_AS_ROOT=1\n            OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1\n"
       "            export OMPI_ALLOW_RUN_AS_ROOT OMPI_ALLOW_RUN_AS_ROOT_CONFIRM\n        fi\n"
       "        step decomposePar decomposePar -force\n"
       "        step simpleFoam mpirun -np \"$processors\" simpleFoam -parallel\n"
       "        step reconstructPar reconstructPar -latestTime\n"
       "    else\n        step simpleFoam simpleFoam\n    fi\nfi\n";
  return s.str();
}

} // namespace bender
