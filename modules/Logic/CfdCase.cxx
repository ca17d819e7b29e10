#include "CfdCase.h"

#include "AtomicFile.h"
#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "ExportSurface.h"

#include <vtkCellType.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSelectEnclosedPoints.h>
#include <vtkStaticCellLocator.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <locale>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace bender
{
namespace
{

constexpr double kPi = 3.14159265358979323846;
constexpr const char* kCaseJson = "bender-case.json";

std::string Num(double v)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::setprecision(10) << v;
  return s.str();
}

std::string Short(double v, int digits = 3)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::setprecision(digits) << v;
  return s.str();
}

std::string Vec(const std::array<double, 3>& v)
{
  return "(" + Num(v[0]) + " " + Num(v[1]) + " " + Num(v[2]) + ")";
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

std::string SurfaceName(const CfdCaseOptions& options)
{
  return options.sourceName.empty() ? std::string("the surface") : options.sourceName;
}

bool IsEnd(PatchType type)
{
  return type != PatchType::Wall;
}

/// Per-patch sums over the triangles of the surface (in its unit, mm).
struct PatchSums
{
  long long triangles = 0;
  double area = 0.0;
  std::array<double, 3> vectorArea{};
  std::array<double, 3> weightedCentre{};
};

void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/// Adds triangle (a, b, c) of patch index `patch` to the sums and to the signed volume.
void AddTriangle(vtkPoints* points,
  vtkIdType a,
  vtkIdType b,
  vtkIdType c,
  PatchSums& sums,
  double& volume)
{
  double p0[3], p1[3], p2[3];
  points->GetPoint(a, p0);
  points->GetPoint(b, p1);
  points->GetPoint(c, p2);
  const double e1[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  const double e2[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
  double n[3];
  Cross(e1, e2, n);
  const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  ++sums.triangles;
  sums.area += area;
  for (int k = 0; k < 3; ++k)
  {
    sums.vectorArea[k] += 0.5 * n[k];
    sums.weightedCentre[k] += area * (p0[k] + p1[k] + p2[k]) / 3.0;
  }
  double p1xp2[3];
  Cross(p1, p2, p1xp2);
  volume += (p0[0] * p1xp2[0] + p0[1] * p1xp2[1] + p0[2] * p1xp2[2]) / 6.0;
}

/// The patches of the surface with their areas, centres and outward normals, in metres.
std::vector<CfdPatch> MeasurePatches(vtkPolyData* surface,
  const std::vector<PatchLabel>& labels,
  const std::string& name)
{
  const std::vector<int> ids = CellPatchIds(surface);
  int maxId = 0;
  for (const auto& l : labels)
  {
    maxId = std::max(maxId, l.id);
  }
  std::vector<PatchSums> sums(static_cast<std::size_t>(maxId) + 1);
  double volume = 0.0;
  vtkPoints* points = surface->GetPoints();
  vtkNew<vtkIdList> cell;
  for (vtkIdType i = 0; i < surface->GetNumberOfCells(); ++i)
  {
    const int type = surface->GetCellType(i);
    if (type != VTK_TRIANGLE && type != VTK_POLYGON && type != VTK_QUAD &&
      type != VTK_TRIANGLE_STRIP)
    {
      continue;
    }
    surface->GetCellPoints(i, cell);
    const vtkIdType n = cell->GetNumberOfIds();
    const int id = ids[static_cast<std::size_t>(i)];
    if (id < 0 || id > maxId)
    {
      continue;
    }
    PatchSums& s = sums[static_cast<std::size_t>(id)];
    if (type == VTK_TRIANGLE_STRIP)
    {
      for (vtkIdType k = 0; k + 2 < n; ++k)
      {
        if (k % 2 == 0)
        {
          AddTriangle(points, cell->GetId(k), cell->GetId(k + 1), cell->GetId(k + 2), s, volume);
        }
        else
        {
          AddTriangle(points, cell->GetId(k + 1), cell->GetId(k), cell->GetId(k + 2), s, volume);
        }
      }
    }
    else
    {
      for (vtkIdType k = 1; k + 1 < n; ++k)
      {
        AddTriangle(points, cell->GetId(0), cell->GetId(k), cell->GetId(k + 1), s, volume);
      }
    }
  }
  if (!(std::abs(volume) > 0.0) || !std::isfinite(volume))
  {
    throw InputError(name + ": the surface encloses no volume");
  }
  const double outward = volume > 0.0 ? 1.0 : -1.0;
  std::vector<CfdPatch> patches;
  for (const auto& l : labels)
  {
    const PatchSums& s = sums[static_cast<std::size_t>(l.id)];
    CfdPatch p;
    p.name = l.name;
    p.type = l.type;
    p.triangles = s.triangles;
    p.area = s.area * 1e-6;
    if (s.area > 0.0)
    {
      for (int k = 0; k < 3; ++k)
      {
        p.centre[static_cast<std::size_t>(k)] =
          1e-3 * s.weightedCentre[static_cast<std::size_t>(k)] / s.area;
      }
    }
    const double norm = std::sqrt(s.vectorArea[0] * s.vectorArea[0] +
      s.vectorArea[1] * s.vectorArea[1] + s.vectorArea[2] * s.vectorArea[2]);
    if (norm > 0.0)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        p.normal[k] = outward * s.vectorArea[k] / norm;
      }
    }
    p.diameter = 2.0 * std::sqrt(p.area / kPi);
    patches.push_back(p);
  }
  return patches;
}

/// A point well inside the lumen (metres): on the inward normal of an end (the inlet first),
/// the candidate farthest from the wall.
std::array<double, 3> InsidePoint(vtkPolyData* surface,
  const std::vector<CfdPatch>& patches,
  std::size_t inlet,
  double cellSize,
  const std::string& name)
{
  vtkNew<vtkSelectEnclosedPoints> enclosed;
  enclosed->SetTolerance(1e-6);
  enclosed->Initialize(surface);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(surface);
  locator->BuildLocator();
  std::vector<std::size_t> order{ inlet };
  for (std::size_t i = 0; i < patches.size(); ++i)
  {
    if (i != inlet && IsEnd(patches[i].type))
    {
      order.push_back(i);
    }
  }
  std::array<double, 3> best{};
  double bestDistance = -1.0;
  for (const std::size_t i : order)
  {
    const CfdPatch& p = patches[i];
    const double radius = 0.5 * p.diameter;
    for (const double depth : { 0.75, 1.0, 1.5, 0.5, 2.0, 3.0, 0.25 })
    {
      // mm, nudged off the background grid's planes.
      double x[3];
      for (std::size_t k = 0; k < 3; ++k)
      {
        const double nudge = (0.0173 + 0.0119 * static_cast<double>(k)) * cellSize;
        x[k] = 1e3 * (p.centre[k] - depth * radius * p.normal[k] + nudge);
      }
      if (!enclosed->IsInsideSurface(x))
      {
        continue;
      }
      double closest[3], d2 = 0.0;
      vtkIdType cellId = -1;
      int subId = 0;
      locator->FindClosestPoint(x, closest, cellId, subId, d2);
      const double d = 1e-3 * std::sqrt(d2);
      if (d > bestDistance)
      {
        bestDistance = d;
        best = { 1e-3 * x[0], 1e-3 * x[1], 1e-3 * x[2] };
      }
    }
    if (bestDistance >= 1.5 * cellSize)
    {
      break;
    }
  }
  enclosed->Complete();
  if (bestDistance < 0.0)
  {
    throw InputError(name +
      ": no point inside the lumen was found behind its ends (is the "
      "surface oriented consistently and closed?)");
  }
  return best;
}

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
  s << "// The background box: the surface's bounds plus a margin, cubes of " << Num(h)
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
    s << "    (" << Num(xs[o[0]]) << " " << Num(ys[o[1]]) << " " << Num(zs[o[2]]) << ")\n";
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
    << Num(cellSize) << " m at the wall.\n    refinementSurfaces\n    {\n        " << surfaceName
    << "\n        {\n            level (1 1);\n            patchInfo { type wall; }\n"
       "            regions\n            {\n";
  for (const auto& p : patches)
  {
    s << "                " << p.name << " { level (1 1); patchInfo { type "
      << (IsEnd(p.type) ? "patch" : "wall") << "; } }\n";
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
    << Num(std::pow(0.01 * cellSize, 3))
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
    if (!IsEnd(p.type))
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
       "        fields          (U p);\n        writeResidualFields no;\n    }\n}\n";
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
    Num(nu) + ";\n";
}

std::string TurbulenceProperties()
{
  return FoamHeader("dictionary", "constant", "turbulenceProperties") +
    "simulationType  laminar;\n";
}

std::string VelocityField(const std::vector<CfdPatch>& patches, const CfdCaseOptions& options)
{
  std::ostringstream s;
  s << FoamHeader("volVectorField", "0", "U");
  s << "dimensions      [0 1 -1 0 0 0 0];\n\ninternalField   uniform (0 0 0);\n\n"
       "boundaryField\n{\n";
  for (const auto& p : patches)
  {
    s << "    " << p.name << "\n    {\n";
    if (p.type == PatchType::Wall)
    {
      s << "        type            noSlip;\n";
    }
    else if (p.type == PatchType::Inlet)
    {
      if (options.flowRate > 0.0)
      {
        s << "        type            flowRateInletVelocity;\n"
             "        volumetricFlowRate constant "
          << Num(options.flowRate)
          << ";  // m^3/s\n        extrapolateProfile no;\n        value           uniform (0 0 "
             "0);\n";
      }
      else
      {
        s << "        // Uniform, normal to the inlet, into the domain (m/s).\n"
             "        type            surfaceNormalFixedValue;\n        refValue        uniform "
          << Num(-options.velocity) << ";\n        value           uniform (0 0 0);\n";
      }
    }
    else
    {
      s << "        type            inletOutlet;\n        inletValue      uniform (0 0 0);\n"
           "        value           uniform (0 0 0);\n";
    }
    s << "    }\n";
  }
  s << "}\n";
  return s.str();
}

std::string PressureField(const std::vector<CfdPatch>& patches)
{
  std::ostringstream s;
  s << FoamHeader("volScalarField", "0", "p");
  s << "// Kinematic pressure p / rho (m^2/s^2).\ndimensions      [0 2 -2 0 0 0 0];\n\n"
       "internalField   uniform 0;\n\nboundaryField\n{\n";
  for (const auto& p : patches)
  {
    s << "    " << p.name << "\n    {\n";
    if (p.type == PatchType::Outlet)
    {
      s << "        type            fixedValue;\n        value           uniform 0;\n";
    }
    else
    {
      s << "        type            zeroGradient;\n";
    }
    s << "    }\n";
  }
  s << "}\n";
  return s.str();
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
       "if [ \"$what\" = all ] || [ \"$what\" = mesh ]; then\n"
       "    rm -rf constant/polyMesh constant/extendedFeatureEdgeMesh postProcessing processor*\n"
       "    step blockMesh blockMesh\n"
       "    step surfaceFeatureExtract surfaceFeatureExtract\n"
       "    step snappyHexMesh snappyHexMesh -overwrite\n"
       "    step checkMesh checkMesh\n"
       "    if ! grep -q \"Mesh OK\" log.checkMesh; then\n"
       "        echo \"bender Allrun: checkMesh found problems, see log.checkMesh\" >&2\n"
       "        exit 1\n    fi\nfi\n\n"
       "if [ \"$what\" = all ] || [ \"$what\" = solve ]; then\n"
       "    rm -rf postProcessing processor*\n"
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

void WriteText(const fs::path& path, const std::string& text)
{
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  std::string problem;
  if (ec || !AtomicWriteText(path.string(), text, problem))
  {
    throw InputError(path.string() + ": " + (ec ? ec.message() : problem));
  }
}

/// A fresh sibling of target: "<parent>/.<name>.<tag>-XXXXXX".
fs::path TemporarySibling(const fs::path& target, const char* tag)
{
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::string pattern =
    (parent / ("." + target.filename().string() + "." + tag + "-XXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (!mkdtemp(buffer.data()))
  {
    throw InputError(
      target.string() + ": cannot create a folder beside it (" + std::strerror(errno) + ")");
  }
  return fs::path(buffer.data());
}

nlohmann::ordered_json PatchJson(const CfdPatch& p)
{
  nlohmann::ordered_json j;
  j["name"] = p.name;
  j["type"] = PatchTypeName(p.type);
  j["triangles"] = p.triangles;
  j["area"] = p.area;
  j["diameter"] = p.diameter;
  j["centre"] = p.centre;
  j["normal"] = p.normal;
  return j;
}

nlohmann::ordered_json CaseJson(const CfdCaseResult& r, const CfdCaseOptions& options)
{
  nlohmann::ordered_json j;
  j["format"] = "bender-cfd-case";
  j["unit"] = "m";
  j["frame"] = "LPS";
  j["surface"] = "constant/triSurface/" + options.surfaceName + ".stl";
  j["inlet"] = r.inlet;
  if (options.flowRate > 0.0)
  {
    j["flowRate"] = options.flowRate;
  }
  else
  {
    j["velocity"] = options.velocity;
  }
  j["inletFlowRate"] = r.inletFlowRate;
  j["inletVelocity"] = r.inletVelocity;
  j["reynolds"] = r.reynolds;
  j["viscosity"] = options.viscosity;
  j["density"] = options.density;
  j["iterations"] = options.iterations;
  j["processors"] = options.processors;
  j["cellSize"] = r.cellSize;
  j["backgroundCellSize"] = r.backgroundCellSize;
  j["backgroundCells"] = r.backgroundCells;
  j["insidePoint"] = r.insidePoint;
  j["patches"] = nlohmann::ordered_json::array();
  for (const auto& p : r.patches)
  {
    j["patches"].push_back(PatchJson(p));
  }
  return j;
}

void CheckOption(bool ok, const std::string& what)
{
  if (!ok)
  {
    throw InputError(what);
  }
}

} // namespace

CfdCaseResult WriteOpenFoamCase(vtkPolyData* surface, const CfdCaseOptions& options)
{
  const std::string name = SurfaceName(options);
  CheckOption(!options.caseDirectory.empty(), "give the case folder");
  CheckOption(std::isfinite(options.flowRate) && options.flowRate >= 0.0 && options.flowRate < 1.0,
    "--flow-rate " + Num(options.flowRate) + ": give a flow rate in m^3/s, > 0 and < 1");
  CheckOption(options.flowRate > 0.0 ||
      (std::isfinite(options.velocity) && options.velocity > 0.0 && options.velocity < 100.0),
    "--velocity " + Num(options.velocity) + ": give a velocity in m/s, > 0 and < 100");
  CheckOption(std::isfinite(options.cellSize) && options.cellSize >= 0.0 && options.cellSize < 1.0,
    "--cell-size " + Num(options.cellSize) + ": give a cell size in m, > 0 and < 1");
  CheckOption(
    std::isfinite(options.viscosity) && options.viscosity > 0.0 && options.viscosity < 1.0,
    "--viscosity " + Num(options.viscosity) + ": give a kinematic viscosity in m^2/s, > 0");
  CheckOption(std::isfinite(options.density) && options.density > 0.0,
    "density " + Num(options.density) + ": must be > 0");
  CheckOption(options.iterations >= 1 && options.iterations <= 1000000,
    "--iterations " + std::to_string(options.iterations) + ": give 1 to 1000000");
  CheckOption(options.processors >= 1 && options.processors <= 4096,
    "--processors " + std::to_string(options.processors) + ": give 1 to 4096");
  CheckOption(options.decomposition == "hierarchical" || options.decomposition == "scotch" ||
      options.decomposition == "simple",
    "--decomposition " + options.decomposition + ": give hierarchical, scotch or simple");
  CheckOption(IsValidPatchName(options.surfaceName),
    "surface name '" + options.surfaceName + "': use letters, digits and _");
  if (!surface || surface->GetNumberOfPolys() + surface->GetNumberOfStrips() == 0)
  {
    throw InputError(name + ": no triangles");
  }

  // The folder: new, or empty, or replaced with force.
  const fs::path target = fs::path(options.caseDirectory);
  std::error_code ec;
  const bool exists = fs::exists(target, ec);
  if (exists)
  {
    if (!fs::is_directory(target, ec))
    {
      throw InputError(options.caseDirectory + ": exists and is not a folder");
    }
    if (!fs::is_empty(target, ec) && !options.force)
    {
      throw InputError(
        options.caseDirectory + ": the folder is not empty (use --force to replace it)");
    }
  }
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(parent, ec))
  {
    throw InputError(options.caseDirectory + ": folder " + parent.string() + " does not exist");
  }

  // The surface: closed, consistently oriented, labelled with an inlet and an outlet.
  MeshCheckOptions checkOptions;
  checkOptions.selfIntersections = false;
  const MeshCheckReport report = CheckMesh(surface, nullptr, checkOptions);
  if (!report.closed)
  {
    throw InputError(name + ": the surface is not closed (" + std::to_string(report.boundaryEdges) +
      " boundary edges in " + std::to_string(report.boundaryLoops.size()) + " open loops, " +
      std::to_string(report.nonManifoldEdges) +
      " non-manifold edges): clip and cap its ends first (bender-cli clip)");
  }
  if (report.inconsistentEdges > 0)
  {
    throw InputError(name + ": the triangles are not consistently oriented (" +
      std::to_string(report.inconsistentEdges) + " edges)");
  }
  const std::vector<PatchLabel> labels = ReadPatchLabels(surface);
  std::vector<CfdPatch> patches = MeasurePatches(surface, labels, name);
  std::string names;
  std::vector<std::size_t> ends;
  for (std::size_t i = 0; i < patches.size(); ++i)
  {
    if (IsEnd(patches[i].type))
    {
      ends.push_back(i);
      names += (names.empty() ? "" : ", ") + patches[i].name;
    }
  }
  if (ends.size() < 2)
  {
    throw InputError(name +
      ": a flow case needs an inlet and at least one outlet, the surface has " +
      std::to_string(ends.size()) +
      " labelled end(s) (cap or clip its ends: bender-cli clip, export --cap)");
  }
  std::size_t inlet = patches.size();
  if (!options.inlet.empty())
  {
    for (std::size_t i = 0; i < patches.size(); ++i)
    {
      if (patches[i].name == options.inlet)
      {
        inlet = i;
      }
    }
    if (inlet == patches.size())
    {
      throw InputError(
        "--inlet " + options.inlet + ": " + name + " has no such end (ends: " + names + ")");
    }
    if (!IsEnd(patches[inlet].type))
    {
      throw InputError(
        "--inlet " + options.inlet + ": is the wall, not an end (ends: " + names + ")");
    }
  }
  else
  {
    std::string inlets;
    for (const std::size_t i : ends)
    {
      if (patches[i].type == PatchType::Inlet)
      {
        inlets += (inlets.empty() ? "" : ", ") + patches[i].name;
        if (inlet != patches.size())
        {
          throw InputError(name + ": several inlets (" + inlets + "...): choose one with --inlet");
        }
        inlet = i;
      }
    }
    if (inlet == patches.size())
    {
      throw InputError(
        name + ": no end is labelled inlet: name it with --inlet (ends: " + names + ")");
    }
  }
  for (const std::size_t i : ends)
  {
    patches[i].type = i == inlet ? PatchType::Inlet : PatchType::Outlet;
  }

  // Sizes (metres).
  double smallest = 0.0;
  for (const std::size_t i : ends)
  {
    if (smallest == 0.0 || patches[i].diameter < smallest)
    {
      smallest = patches[i].diameter;
    }
  }
  CfdCaseResult result;
  result.caseDirectory = options.caseDirectory;
  result.inlet = patches[inlet].name;
  result.cellSize = options.cellSize > 0.0 ? options.cellSize : smallest / 8.0;
  if (!(result.cellSize > 0.0))
  {
    throw InputError(name + ": its ends have no area");
  }
  result.backgroundCellSize = 2.0 * result.cellSize;
  const double hb = result.backgroundCellSize;
  double bounds[6];
  surface->GetBounds(bounds);
  std::array<double, 3> origin{};
  double cells = 1.0;
  for (std::size_t k = 0; k < 3; ++k)
  {
    // Two cells of margin, shifted off the surface's bounds by a fraction of a cell.
    const double lo = 1e-3 * bounds[2 * k], hi = 1e-3 * bounds[2 * k + 1];
    origin[k] = lo - 2.137 * hb;
    const double n = std::ceil((hi - origin[k]) / hb + 2.0);
    if (!(n < 1e6))
    {
      throw InputError("--cell-size " + Num(result.cellSize) + ": far too small for " + name);
    }
    result.backgroundCells[k] = static_cast<int>(n);
    cells *= n;
  }
  if (cells > 2e7)
  {
    throw InputError("--cell-size " + Num(result.cellSize) + " m: the background mesh of " + name +
      " would have " + Short(cells) + " cells; give a larger cell size");
  }
  result.insidePoint = InsidePoint(surface, patches, inlet, result.cellSize, name);
  result.patches = patches;
  const CfdPatch& in = patches[inlet];
  result.inletFlowRate = options.flowRate > 0.0 ? options.flowRate : options.velocity * in.area;
  result.inletVelocity = in.area > 0.0 ? result.inletFlowRate / in.area : 0.0;
  result.reynolds = result.inletVelocity * in.diameter / options.viscosity;

  // Everything into a temporary sibling, renamed into place when complete.
  const fs::path temp = TemporarySibling(target, "bender-new");
  try
  {
    fs::permissions(temp,
      fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
        fs::perms::others_read | fs::perms::others_exec);
    const std::string stl = options.surfaceName + ".stl";
    fs::create_directories(temp / "constant" / "triSurface");
    ExportSurfaceOptions exportOptions;
    exportOptions.output = (temp / "constant" / "triSurface" / stl).string();
    exportOptions.unit = "m";
    exportOptions.stlEncoding = StlEncoding::Ascii;
    exportOptions.patches = StlPatchMode::Solids;
    exportOptions.sourceName = options.sourceName;
    ExportSurface(surface, exportOptions);
    result.written.push_back("constant/triSurface/" + stl);
    const std::vector<std::pair<std::string, std::string>> files = {
      { "system/blockMeshDict", BlockMeshDict(origin, hb, result.backgroundCells) },
      { "system/surfaceFeatureExtractDict", SurfaceFeatureExtractDict(stl) },
      { "system/snappyHexMeshDict",
        SnappyHexMeshDict(options.surfaceName, patches, result.insidePoint, result.cellSize) },
      { "system/controlDict", ControlDict(patches, options.iterations) },
      { "system/fvSchemes", FvSchemes() },
      { "system/fvSolution", FvSolution() },
      { "system/decomposeParDict",
        DecomposeParDict(options.processors,
          options.decomposition,
          { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] }) },
      { "constant/transportProperties", TransportProperties(options.viscosity) },
      { "constant/turbulenceProperties", TurbulenceProperties() },
      { "0/U", VelocityField(patches, options) },
      { "0/p", PressureField(patches) },
      { "Allrun", Allrun(options.processors) },
      { kCaseJson, CaseJson(result, options).dump(2) + "\n" },
    };
    for (const auto& [path, text] : files)
    {
      WriteText(temp / path, text);
      result.written.push_back(path);
    }
    fs::permissions(temp / "Allrun",
      fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
      fs::perm_options::add);
  }
  catch (...)
  {
    fs::remove_all(temp, ec);
    throw;
  }

  // Into place: over an empty folder directly; a non-empty one (force) is moved aside first
  // and removed once the new case is there.
  fs::path old;
  if (fs::exists(target, ec) && !fs::is_empty(target, ec))
  {
    old = TemporarySibling(target, "bender-old");
    fs::remove(old, ec);
    fs::rename(target, old, ec);
    if (ec)
    {
      fs::remove_all(temp, ec);
      throw InputError(options.caseDirectory + ": cannot be replaced (" + ec.message() + ")");
    }
  }
  fs::rename(temp, target, ec);
  if (ec)
  {
    const std::string problem = ec.message();
    if (!old.empty())
    {
      fs::rename(old, target, ec);
    }
    fs::remove_all(temp, ec);
    throw InputError(options.caseDirectory + ": cannot be written (" + problem + ")");
  }
  if (!old.empty())
  {
    fs::remove_all(old, ec);
  }
  return result;
}

namespace
{

/// The data lines of a postProcessing .dat file of the latest start time, as words.
std::vector<std::vector<std::string>> ReadDat(const fs::path& caseDir,
  const std::string& object,
  const std::string& file,
  std::vector<std::string>* header = nullptr)
{
  const fs::path folder = caseDir / "postProcessing" / object;
  std::error_code ec;
  fs::path latest;
  double latestTime = -1.0;
  if (fs::is_directory(folder, ec))
  {
    for (const auto& entry : fs::directory_iterator(folder, ec))
    {
      char* end = nullptr;
      const std::string t = entry.path().filename().string();
      const double time = std::strtod(t.c_str(), &end);
      if (end && *end == '\0' && time > latestTime && fs::exists(entry.path() / file, ec))
      {
        latestTime = time;
        latest = entry.path() / file;
      }
    }
  }
  if (latest.empty())
  {
    throw InputError((folder / "0" / file).string() + ": missing (has the case run?)");
  }
  std::ifstream in(latest);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::vector<std::string> row;
    std::string w;
    while (words >> w)
    {
      row.push_back(w);
    }
    if (row.empty())
    {
      continue;
    }
    if (row[0] == "#")
    {
      if (header && row.size() > 1 && row[1] == "Time")
      {
        header->assign(row.begin() + 1, row.end());
      }
      continue;
    }
    rows.push_back(row);
  }
  if (rows.empty())
  {
    throw InputError(latest.string() + ": no data");
  }
  return rows;
}

double ParseNumber(const std::string& word, const std::string& where)
{
  char* end = nullptr;
  const double v = std::strtod(word.c_str(), &end);
  if (!end || *end != '\0' || !std::isfinite(v))
  {
    throw InputError(where + ": '" + word + "' is not a number");
  }
  return v;
}

/// The last value of a surfaceFieldValue file, and its iteration.
double LastValue(const fs::path& caseDir, const std::string& object, int& iteration)
{
  const auto rows = ReadDat(caseDir, object, "surfaceFieldValue.dat");
  const auto& last = rows.back();
  const std::string where = (caseDir / "postProcessing" / object).string();
  if (last.size() < 2)
  {
    throw InputError(where + ": a line without a value");
  }
  iteration = static_cast<int>(ParseNumber(last[0], where));
  return ParseNumber(last[1], where);
}

std::string ReadWhole(const fs::path& path)
{
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

} // namespace

bool IsOnPath(const std::string& program)
{
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
  {
    if (!dir.empty() && access((fs::path(dir) / program).c_str(), X_OK) == 0)
    {
      return true;
    }
  }
  return false;
}

std::string FindOpenFoamProblem(int processors)
{
  for (const char* program :
    { "blockMesh", "surfaceFeatureExtract", "snappyHexMesh", "checkMesh", "simpleFoam" })
  {
    if (!IsOnPath(program))
    {
      return std::string("OpenFOAM is not installed: ") + program +
        " is not on PATH (Debian: apt-get install openfoam; elsewhere source OpenFOAM's "
        "etc/bashrc)";
    }
  }
  if (processors > 1)
  {
    for (const char* program : { "decomposePar", "reconstructPar", "mpirun" })
    {
      if (!IsOnPath(program))
      {
        return std::string("a parallel run needs ") + program + ", which is not on PATH";
      }
    }
  }
  const char* project = std::getenv("WM_PROJECT_DIR");
  std::error_code ec;
  if ((!project || !fs::exists(fs::path(project) / "etc" / "controlDict", ec)) &&
    !fs::exists("/usr/share/openfoam/etc/controlDict", ec))
  {
    return "OpenFOAM's etc/controlDict is not found (set WM_PROJECT_DIR or source OpenFOAM's "
           "etc/bashrc)";
  }
  return "";
}

CfdRunResult ReadCfdResults(const std::string& caseDirectory)
{
  const fs::path dir(caseDirectory);
  const fs::path jsonPath = dir / kCaseJson;
  nlohmann::json j;
  try
  {
    std::ifstream in(jsonPath);
    if (!in)
    {
      throw InputError(jsonPath.string() + ": missing (not a case written by bender-cli cfd-case)");
    }
    in >> j;
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(jsonPath.string() + ": not valid JSON (" + e.what() + ")");
  }
  CfdRunResult run;
  double density = 1060.0;
  int limit = 0;
  std::vector<CfdPatchFlow> flows;
  try
  {
    density = j.at("density").get<double>();
    limit = j.at("iterations").get<int>();
    for (const auto& p : j.at("patches"))
    {
      CfdPatchFlow f;
      f.name = p.at("name").get<std::string>();
      f.type = PatchTypeFromName(p.at("type").get<std::string>());
      if (IsEnd(f.type) && IsValidPatchName(f.name))
      {
        flows.push_back(f);
      }
    }
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(jsonPath.string() + ": " + e.what());
  }
  double inletPressure = 0.0, total = 0.0;
  for (auto& f : flows)
  {
    int iteration = 0;
    f.flowRate = LastValue(dir, "flow_" + f.name, iteration);
    f.pressure = density * LastValue(dir, "pressure_" + f.name, iteration);
    run.iterations = std::max(run.iterations, iteration);
    total += f.flowRate;
    if (f.type == PatchType::Inlet)
    {
      run.inletFlowRate += -f.flowRate;
      inletPressure = f.pressure;
    }
  }
  if (!(run.inletFlowRate > 0.0))
  {
    throw InputError(caseDirectory + ": no flow into the inlet in the results");
  }
  run.massImbalance = std::abs(total) / run.inletFlowRate;
  for (auto& f : flows)
  {
    f.percentOfInlet = 100.0 * f.flowRate / run.inletFlowRate;
    f.pressureDrop = inletPressure - f.pressure;
  }
  run.patches = flows;
  std::vector<std::string> header;
  const auto rows = ReadDat(dir, "solverInfo", "solverInfo.dat", &header);
  const auto& last = rows.back();
  for (std::size_t c = 0; c < header.size() && c < last.size(); ++c)
  {
    const std::string& h = header[c];
    const std::string suffix = "_initial";
    if (h.size() > suffix.size() && h.compare(h.size() - suffix.size(), suffix.size(), suffix) == 0)
    {
      run.residuals.emplace_back(h.substr(0, h.size() - suffix.size()),
        ParseNumber(last[c], (dir / "postProcessing/solverInfo").string()));
    }
  }
  const std::string log = ReadWhole(dir / "log.simpleFoam");
  run.converged =
    log.find("solution converged in") != std::string::npos || (limit > 0 && run.iterations < limit);
  return run;
}

std::vector<std::pair<std::string, long long>> ReadMeshPatches(const std::string& caseDirectory)
{
  const fs::path path = fs::path(caseDirectory) / "constant" / "polyMesh" / "boundary";
  std::ifstream in(path);
  if (!in)
  {
    throw InputError(path.string() + ": missing (has the case been meshed?)");
  }
  // After the FoamFile header: N ( name { type ...; nFaces N; startFace N; } ... ).
  std::vector<std::string> words;
  std::string w;
  while (in >> w)
  {
    words.push_back(w);
  }
  std::vector<std::pair<std::string, long long>> patches;
  std::size_t i = 0;
  for (; i < words.size() && words[i] != "FoamFile"; ++i)
  {
  }
  int depth = 0;
  std::string current;
  bool inList = false;
  for (; i < words.size(); ++i)
  {
    const std::string& t = words[i];
    if (t == "{")
    {
      ++depth;
      if (inList && depth == 1 && i > 0)
      {
        current = words[i - 1];
        patches.emplace_back(current, -1);
      }
    }
    else if (t == "}")
    {
      --depth;
    }
    else if (t == "(" && depth == 0)
    {
      inList = true;
    }
    else if (t == "nFaces" && depth == 1 && !patches.empty() && i + 1 < words.size())
    {
      std::string n = words[i + 1];
      if (!n.empty() && n.back() == ';')
      {
        n.pop_back();
      }
      patches.back().second = static_cast<long long>(ParseNumber(n, path.string()));
    }
  }
  if (patches.empty())
  {
    throw InputError(path.string() + ": no patches");
  }
  return patches;
}

namespace
{
/// Runs `sh ./Allrun what` in dir, its output to log.Allrun (appended when append) and to
/// options.onLine. Throws Error naming the failed step.
void RunAllrun(const fs::path& dir,
  const std::string& caseDirectory,
  const std::string& what,
  const CfdRunOptions& options,
  bool append)
{
  int pipeFds[2];
  if (pipe(pipeFds) != 0)
  {
    throw Error(std::string("cannot run Allrun: ") + std::strerror(errno));
  }
  const pid_t pid = fork();
  if (pid < 0)
  {
    close(pipeFds[0]);
    close(pipeFds[1]);
    throw Error(std::string("cannot run Allrun: ") + std::strerror(errno));
  }
  if (pid == 0)
  {
    dup2(pipeFds[1], STDOUT_FILENO);
    dup2(pipeFds[1], STDERR_FILENO);
    close(pipeFds[0]);
    close(pipeFds[1]);
    const int devNull = open("/dev/null", O_RDONLY);
    if (devNull >= 0)
    {
      dup2(devNull, STDIN_FILENO);
    }
    if (chdir(dir.c_str()) != 0)
    {
      _exit(126);
    }
    execl("/bin/sh", "sh", "./Allrun", what.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipeFds[1]);
  std::ofstream log(dir / "log.Allrun", append ? std::ios::app : std::ios::trunc);
  std::string pending, lastLines;
  char buffer[4096];
  for (;;)
  {
    const ssize_t n = read(pipeFds[0], buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      break;
    }
    log.write(buffer, n);
    pending.append(buffer, static_cast<std::size_t>(n));
    std::size_t eol;
    while ((eol = pending.find('\n')) != std::string::npos)
    {
      const std::string line = pending.substr(0, eol);
      pending.erase(0, eol + 1);
      lastLines = line;
      if (options.onLine)
      {
        options.onLine(line);
      }
    }
  }
  close(pipeFds[0]);
  log.close();
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
  {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    // Allrun's own message names the failed step and its log.
    const std::string text = ReadWhole(dir / "log.Allrun");
    std::string failed;
    const std::size_t at = text.find("bender Allrun: ");
    std::size_t pos = text.rfind(" failed, see ");
    if (pos == std::string::npos)
    {
      pos = text.rfind("checkMesh found problems");
    }
    if (pos != std::string::npos && at != std::string::npos)
    {
      const std::size_t start = text.rfind("bender Allrun: ", pos);
      const std::size_t end = text.find('\n', pos);
      failed =
        text.substr(start + 15, end == std::string::npos ? std::string::npos : end - start - 15);
    }
    throw Error(caseDirectory + ": " + (failed.empty() ? "Allrun failed" : failed) +
      " (all output in log.Allrun)");
  }
}

/// Every end of the case (bender-case.json) must be a non-empty patch of the mesh.
void CheckMeshPatches(const std::string& caseDirectory)
{
  const auto meshPatches = ReadMeshPatches(caseDirectory);
  std::ifstream in(fs::path(caseDirectory) / kCaseJson);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.contains("patches"))
  {
    throw InputError(caseDirectory + ": " + kCaseJson + " is unreadable");
  }
  for (const auto& p : j["patches"])
  {
    const std::string name = p.value("name", "");
    const auto it = std::find_if(
      meshPatches.begin(), meshPatches.end(), [&](const auto& m) { return m.first == name; });
    if (it == meshPatches.end() || it->second <= 0)
    {
      throw Error(caseDirectory + ": snappyHexMesh left patch " + name +
        " without faces (give a smaller --cell-size)");
    }
  }
}
} // namespace

CfdRunResult RunOpenFoamCase(const std::string& caseDirectory, const CfdRunOptions& options)
{
  const fs::path dir(caseDirectory);
  std::error_code ec;
  if (!fs::exists(dir / "Allrun", ec) || !fs::exists(dir / kCaseJson, ec))
  {
    throw InputError(caseDirectory + ": not a case written by bender-cli cfd-case (no Allrun)");
  }
  int processors = 1;
  try
  {
    std::ifstream in(dir / kCaseJson);
    processors = nlohmann::json::parse(in).at("processors").get<int>();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError((dir / kCaseJson).string() + ": " + e.what());
  }
  if (const std::string problem = FindOpenFoamProblem(processors); !problem.empty())
  {
    throw EnvironmentError(problem);
  }
  using Steps = CfdRunOptions::Steps;
  if (options.steps != Steps::Solve)
  {
    RunAllrun(dir, caseDirectory, "mesh", options, false);
    CheckMeshPatches(caseDirectory);
  }
  if (options.steps != Steps::Mesh)
  {
    RunAllrun(dir, caseDirectory, "solve", options, options.steps == Steps::All);
  }
  if (options.steps == CfdRunOptions::Steps::Mesh)
  {
    return CfdRunResult{};
  }
  return ReadCfdResults(caseDirectory);
}

std::string CfdToJson(const CfdCaseResult& written, const CfdRunResult* run)
{
  nlohmann::ordered_json j;
  j["case"] = written.caseDirectory;
  j["inlet"] = written.inlet;
  j["inletFlowRate"] = written.inletFlowRate;
  j["inletVelocity"] = written.inletVelocity;
  j["reynolds"] = written.reynolds;
  j["cellSize"] = written.cellSize;
  j["backgroundCells"] = written.backgroundCells;
  j["insidePoint"] = written.insidePoint;
  j["patches"] = nlohmann::ordered_json::array();
  for (const auto& p : written.patches)
  {
    j["patches"].push_back(PatchJson(p));
  }
  j["files"] = written.written;
  if (run)
  {
    nlohmann::ordered_json r;
    r["iterations"] = run->iterations;
    r["converged"] = run->converged;
    r["inletFlowRate"] = run->inletFlowRate;
    r["massImbalance"] = run->massImbalance;
    r["patches"] = nlohmann::ordered_json::array();
    for (const auto& f : run->patches)
    {
      nlohmann::ordered_json o;
      o["name"] = f.name;
      o["type"] = PatchTypeName(f.type);
      o["flowRate"] = f.flowRate;
      o["percentOfInlet"] = f.percentOfInlet;
      o["pressure"] = f.pressure;
      o["pressureDrop"] = f.pressureDrop;
      r["patches"].push_back(o);
    }
    r["residuals"] = nlohmann::ordered_json::object();
    for (const auto& [field, value] : run->residuals)
    {
      r["residuals"][field] = value;
    }
    j["run"] = r;
  }
  return j.dump(2);
}

std::string FormatCfdCase(const CfdCaseResult& r)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "OpenFOAM case " << r.caseDirectory << " (" << r.written.size() << " files, metres):\n";
  for (const auto& p : r.patches)
  {
    s << "  " << p.name << " (" << PatchTypeName(p.type) << "): " << p.triangles
      << " triangles, area " << Short(p.area * 1e6) << " mm^2";
    if (IsEnd(p.type))
    {
      s << ", diameter " << Short(p.diameter * 1e3) << " mm";
    }
    s << "\n";
  }
  s << "  inlet " << r.inlet << ": " << Short(r.inletFlowRate * 6e7) << " ml/min ("
    << Short(r.inletFlowRate) << " m^3/s), mean velocity " << Short(r.inletVelocity)
    << " m/s, Reynolds " << Short(r.reynolds) << "\n";
  s << "  mesh: cells of " << Short(r.cellSize * 1e3) << " mm at the wall, background "
    << r.backgroundCells[0] << " x " << r.backgroundCells[1] << " x " << r.backgroundCells[2]
    << " cells of " << Short(r.backgroundCellSize * 1e3) << " mm\n";
  s << "  run it: " << r.caseDirectory << "/Allrun\n";
  return s.str();
}

std::string FormatCfdRun(const CfdRunResult& run)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "simpleFoam: " << run.iterations << " iterations, "
    << (run.converged ? "converged" : "not converged (iteration limit)") << "; initial residuals";
  for (const auto& [field, value] : run.residuals)
  {
    s << " " << field << " " << Short(value, 2);
  }
  s << "\n";
  for (const auto& f : run.patches)
  {
    if (f.type == PatchType::Inlet)
    {
      s << "  " << f.name << " (inlet): " << Short(-f.flowRate * 6e7) << " ml/min, pressure "
        << Short(f.pressure) << " Pa\n";
    }
  }
  for (const auto& f : run.patches)
  {
    if (f.type == PatchType::Outlet)
    {
      s << "  " << f.name << ": " << Short(f.percentOfInlet) << " % of the inlet flow ("
        << Short(f.flowRate * 6e7) << " ml/min), pressure drop from the inlet "
        << Short(f.pressureDrop) << " Pa\n";
    }
  }
  s << "  mass imbalance " << Short(100.0 * run.massImbalance, 2) << " % of the inlet flow\n";
  return s.str();
}

} // namespace bender
