#ifndef bender_CfdDictionaries_h
#define bender_CfdDictionaries_h

// The text of every file of an OpenFOAM case written by WriteOpenFoamCase (CfdCase.h): the
// system/ dictionaries, the constant/ properties, the 0/ fields and the Allrun. SI units,
// numbers in the classic locale.

#include "CfdCase.h"

#include <array>
#include <string>
#include <vector>

namespace bender
{

/// v with 10 significant digits, classic locale (every number of the dictionaries).
std::string CfdNumber(double v);
/// v with `digits` significant digits, classic locale (messages and reports).
std::string CfdShort(double v, int digits = 3);

/// The background box from `origin` (m), cubes of h, n cells per axis.
std::string BlockMeshDict(const std::array<double, 3>& origin,
  double h,
  const std::array<int, 3>& n);
/// The feature edges of constant/triSurface/`stl` (the rims of the ends).
std::string SurfaceFeatureExtractDict(const std::string& stl);
/// snappyHexMesh on surface `surfaceName` (one region per patch), refined once at the wall
/// to cellSize (m), the mesh kept on the side of `inside` (m).
std::string SnappyHexMeshDict(const std::string& surfaceName,
  const std::vector<CfdPatch>& patches,
  const std::array<double, 3>& inside,
  double cellSize);
/// simpleFoam for `iterations`, with the flow and pressure of every end and the residuals
/// written by function objects.
std::string ControlDict(const std::vector<CfdPatch>& patches, int iterations);
std::string FvSchemes();
std::string FvSolution();
/// `processors` subdomains by `method`; the hierarchical split follows `extent` (any unit).
std::string DecomposeParDict(int processors,
  const std::string& method,
  const std::array<double, 3>& extent);
/// Newtonian, kinematic viscosity nu (m^2/s).
std::string TransportProperties(double nu);
std::string TurbulenceProperties();
/// 0/U: no slip on the wall, the inlet's flow rate or velocity, inletOutlet at the outlets.
std::string VelocityField(const std::vector<CfdPatch>& patches, const CfdCaseOptions& options);
/// 0/p: 0 at the outlets, zero gradient elsewhere.
std::string PressureField(const std::vector<CfdPatch>& patches);
/// The Allrun script (mesh, solve; mpirun when processors > 1).
std::string Allrun(int processors);

} // namespace bender

#endif
