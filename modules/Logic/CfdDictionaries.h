#ifndef bender_CfdDictionaries_h
#define bender_CfdDictionaries_h

// The text of the files of an OpenFOAM case written by WriteOpenFoamCase (CfdCase.h): the
// solver's system/ dictionaries, the constant/ properties and the Allrun (the mesh's
// dictionaries are in CfdMeshing.h, the boundary conditions in CfdBoundaryConditions.h). SI
// units, numbers in the classic locale.

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

/// v as an OpenFOAM vector "(x y z)", CfdNumber's digits.
std::string CfdVector(const std::array<double, 3>& v);
/// The FoamFile header of a dictionary or field of class `cls` in `location` ("" for none).
std::string CfdFoamHeader(const std::string& cls,
  const std::string& location,
  const std::string& object);

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
/// The Allrun script (mesh, solve; mpirun when processors > 1).
/// The line after which constant/boundaryData/<inlet>/0/U gives the inlet's average velocity.
inline constexpr const char* kCfdInletAverageMarker =
  "// The mean velocity on the inlet (m/s), held with setAverage:";

/// The Allrun. With `poiseuilleInlet` (the inlet's patch name; empty: none), its mesh step
/// then holds the mapped profile's average so that the meshed inlet carries `flowRate` (m^3/s)
/// exactly: postProcess measures the mapped flow and mean on the meshed faces
/// (system/inletFlow), and the mean scaled to the flow is written after
/// kCfdInletAverageMarker in constant/boundaryData/<inlet>/0/U, with 0/U's setAverage on.
std::string Allrun(int processors, const std::string& poiseuilleInlet = "", double flowRate = 0.0);

/// system/inletFlow: the flow through and the mean velocity on `inlet` (postProcess -dict).
std::string InletFlowDict(const std::string& inlet);

} // namespace bender

#endif
