#include "CfdDictionaries.h"

#include "CfdPatches.h"

#include <cmath>
#include <iomanip>
#include <locale>
#include <sstream>
#include <utility>

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

std::string CfdVector(const std::array<double, 3>& v)
{
  return "(" + CfdNumber(v[0]) + " " + CfdNumber(v[1]) + " " + CfdNumber(v[2]) + ")";
}

std::string CfdFoamHeader(const std::string& cls,
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

namespace
{

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

} // namespace

std::string ControlDict(const std::vector<CfdPatch>& patches, int iterations)
{
  std::ostringstream s;
  s << CfdFoamHeader("dictionary", "system", "controlDict");
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
  return CfdFoamHeader("dictionary", "system", "fvSchemes") +
    "ddtSchemes\n{\n    default         steadyState;\n}\n\n"
    // grad(U) is not limited: on the demo vessel a cell-limited gradient put the default mesh's
    // pressure drop 2.6 % higher and held U's residual above its control (docs/cfd.md).
    "gradSchemes\n{\n    default         Gauss linear;\n}\n\n"
    "divSchemes\n{\n    default         none;\n"
    "    div(phi,U)      bounded Gauss linearUpwind grad(U);\n"
    "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n\n"
    "laplacianSchemes\n{\n    default         Gauss linear limited corrected 0.33;\n}\n\n"
    "interpolationSchemes\n{\n    default         linear;\n}\n\n"
    "snGradSchemes\n{\n    default         limited corrected 0.33;\n}\n";
}

std::string FvSolution()
{
  return CfdFoamHeader("dictionary", "system", "fvSolution") +
    "solvers\n{\n"
    "    p\n    {\n        solver          GAMG;\n        smoother        GaussSeidel;\n"
    "        tolerance       1e-07;\n        relTol          0.01;\n    }\n\n"
    "    U\n    {\n        solver          smoothSolver;\n        smoother        "
    "symGaussSeidel;\n        tolerance       1e-08;\n        relTol          0.1;\n    }\n}\n\n"
    "SIMPLE\n{\n    nNonOrthogonalCorrectors 1;\n    consistent      yes;\n\n"
    "    // Stop when the initial residuals fall below these.\n"
    "    residualControl\n    {\n        p               1e-4;\n        U               1e-5;\n"
    "    }\n}\n\n"
    // SIMPLEC (consistent) needs no relaxation of p; U at 0.9 (docs/cfd.md, "Speed").
    "relaxationFactors\n{\n    fields\n    {\n        p               1;\n    }\n"
    "    equations\n    {\n        U               0.9;\n    }\n}\n";
}

std::string DecomposeParDict(int processors,
  const std::string& method,
  const std::array<double, 3>& extent)
{
  const std::array<int, 3> n = SplitAxes(processors, extent);
  const std::string coefficients =
    "(" + std::to_string(n[0]) + " " + std::to_string(n[1]) + " " + std::to_string(n[2]) + ")";
  return CfdFoamHeader("dictionary", "system", "decomposeParDict") + "numberOfSubdomains " +
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
  return CfdFoamHeader("dictionary", "constant", "transportProperties") +
    "// Newtonian blood by default (3.5e-6 m^2/s = 3.7 mPa s / 1060 kg/m^3).\n"
    "transportModel  Newtonian;\n\nnu              [0 2 -1 0 0 0 0] " +
    CfdNumber(nu) + ";\n";
}

std::string TurbulenceProperties()
{
  return CfdFoamHeader("dictionary", "constant", "turbulenceProperties") +
    "simulationType  laminar;\n";
}

std::string InletFlowDict(const std::string& inlet)
{
  std::string s = CfdFoamHeader("dictionary", "system", "inletFlow") +
    "// Read by the Allrun's mesh step (postProcess -dict system/inletFlow -time 0): the flow\n"
    "// through the meshed inlet and its mean velocity, as the mapped profile gives them.\n"
    "functions\n{\n";
  const std::pair<const char*, const char*> measures[] = { { "inletFlux", "areaNormalIntegrate" },
    { "inletMean", "areaAverage" } };
  for (const auto& [name, op] : measures)
  {
    s += std::string("    ") + name +
      "\n    {\n        type            surfaceFieldValue;\n"
      "        libs            (\"libfieldFunctionObjects.so\");\n"
      "        writeControl    timeStep;\n        log             false;\n"
      "        writeFields     false;\n        regionType      patch;\n        name            " +
      inlet + ";\n        operation       " + op + ";\n        fields          (U);\n    }\n";
  }
  return s + "}\n";
}

std::string Allrun(int processors, const std::string& poiseuilleInlet, double flowRate)
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
       "        # checkMesh marks each failed check with ***: name them on the one line.\n"
       "        failed=$(grep '\\*\\*\\*' log.checkMesh | sed 's/^ *\\*\\*\\*//' | tr '\\n' ';' "
       "| sed 's/;$//')\n"
       "        echo \"bender Allrun: checkMesh found problems ($failed), see log.checkMesh\" >&2\n"
       "        exit 1\n    fi\n"
    << (poiseuilleInlet.empty()
           ? std::string()
           : "    # The inlet's mapped profile carries the flow exactly on the meshed faces: its\n"
             "    # flow and mean measured there, the mean scaled to the flow held by setAverage.\n"
             "    step postProcess postProcess -dict system/inletFlow -time 0 -fields '(U)'\n"
             "    flux=$(tail -n 1 postProcessing/inletFlux/0/surfaceFieldValue.dat | awk '{ print "
             "$2 }')\n"
             "    mean=$(tail -n 1 postProcessing/inletMean/0/surfaceFieldValue.dat | tr -d '()' | "
             "awk '{ print $2, $3, $4 }')\n"
             "    average=$(awk -v q=" +
             CfdNumber(flowRate) +
             " -v f=\"$flux\" -v m=\"$mean\" 'BEGIN { split(m, v, \" \"); if (f < 0) f = -f;\n"
             "        if (!(f > 0)) exit 1; s = q / f;\n"
             "        printf \"(%.10g %.10g %.10g)\", v[1] * s, v[2] * s, v[3] * s }') || {\n"
             "        echo \"bender Allrun: postProcess failed, see log.postProcess: the meshed "
             "inlet carries no flow\" >&2\n"
             "        exit 1\n    }\n"
             "    values=constant/boundaryData/" +
             poiseuilleInlet +
             "/0/U\n"
             "    sed -i '\\%^" +
             std::string(kCfdInletAverageMarker).substr(0, 20) +
             "%,$d' \"$values\"\n"
             "    printf '%s\\n%s\\n' '" +
             kCfdInletAverageMarker +
             "' \"$average\" >> \"$values\"\n"
             "    sed -i 's/setAverage      false;/setAverage      true;/' 0/U\n")
    << "fi\n\n"
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
