#ifndef bender_CfdBoundaryConditions_h
#define bender_CfdBoundaryConditions_h

// The boundary conditions of an OpenFOAM case written by WriteOpenFoamCase (CfdCase.h): the
// inlet's flow and profile (a developed Poiseuille profile on the inlet's own shape, mapped by
// timeVaryingMappedFixedValue from constant/boundaryData, or a plug), the outlets' conditions
// (zero pressure, a prescribed split, Murray's law, resistances p = R Q), and the 0/U and 0/p
// fields that carry them. Only boundary conditions Debian's OpenFOAM 1912 has compiled in (no
// coded ones): flowRateInletVelocity, surfaceNormalFixedValue, timeVaryingMappedFixedValue,
// flowRateOutletVelocity, inletOutlet, fanPressure (its fan curve as the resistance line).

#include "CfdCase.h"

#include <array>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// "poiseuille", "plug"; "zero-pressure", "split", "murray", "resistance" (the CLI's words).
std::string CfdInletProfileName(CfdInletProfile profile);
std::string CfdOutletConditionName(CfdOutletCondition condition);

/// The inlet's developed profile, sampled at the inlet cap's vertices and triangle centroids.
struct CfdInletProfileData
{
  std::vector<std::array<double, 3>> points;     ///< m, the frame of the case (LPS)
  std::vector<std::array<double, 3>> velocities; ///< m/s, into the domain
  double flowRate = 0.0; ///< m^3/s, the samples integrated over the cap's triangles
  /// The samples are the profile of the flow times this: the faces' midpoint rule, 1 + h^2 /
  /// (3 R^2) for a parabola of half-width R on faces of h, then carries the flow.
  double faceCorrection = 1.0;
  double area = 0.0;       ///< m^2, the cap's
  double peakToMean = 0.0; ///< u_max / u_mean (2 for Poiseuille in a circle)
  /// m/s, into the domain: the flow over the cap's area (the Allrun's mesh step replaces it
  /// with the mean that carries the flow on the meshed inlet, held by 0/U's setAverage).
  std::array<double, 3> meanVelocity{ { 0, 0, 0 } };
};

/// The inlet a profile is laid on and the flow it carries.
struct CfdInletFlow
{
  int id = 0;                                         ///< the cap's patch id (CellPatchIds)
  std::array<double, 3> outwardNormal{ { 0, 0, 1 } }; ///< unit, out of the domain
  double flowRate = 0.0;                              ///< m^3/s
  double faceSize = 0.0;                              ///< m, of the mesh's faces; 0: none
};

/// The Poiseuille profile on the inlet's shape: u = u_max (2 s - s^2), s = the distance to the
/// cap's rim over its largest value (for a circle of radius R, s = 1 - r / R and the profile is
/// u_max (1 - r^2 / R^2)); 0 on the rim; directed along -`inlet.outwardNormal`; u_max such that
/// the profile, linear on the thirds of the cap's triangles (two corners and the centroid),
/// carries `inlet.flowRate`, then scaled by faceCorrection for faces of `inlet.faceSize`.
/// `surface` in mm, `cellIds` its CellPatchIds, the cap the cells of `inlet.id`. Throws
/// InputError naming `name` when the cap has no triangle or no rim.
CfdInletProfileData PoiseuilleInletProfile(vtkPolyData* surface,
  const std::vector<int>& cellIds,
  const CfdInletFlow& inlet,
  const std::string& name);

/// constant/boundaryData/<inlet>/points and .../0/U of timeVaryingMappedFixedValue; the
/// velocities are followed by kCfdInletAverageMarker and meanVelocity.
std::string BoundaryDataPoints(const CfdInletProfileData& profile);
std::string BoundaryDataVelocity(const CfdInletProfileData& profile);

/// Each outlet's condition from the options (the inlet's flow `inletFlowRate`, m^3/s), in
/// patch order. Split: every outlet named once with its percentage, summing to 100 (within
/// 0.1); Murray: Q_i proportional to the cube of the equivalent radius; for both, the outlet
/// with the largest share holds p = 0 (it carries the rest, its share by conservation), the
/// others their flow. Resistance: every outlet named once with R > 0 (Pa s/m^3). Throws
/// InputError naming the option and the outlet.
std::vector<CfdOutletSetting> CfdOutletSettings(const std::vector<CfdPatch>& patches,
  const CfdCaseOptions& options,
  double inletFlowRate);

/// "NAME=VALUE" items of --split or --resistance. Throws InputError naming `option` and the item.
std::vector<CfdOutletValue> ParseCfdOutletValues(const std::string& option,
  const std::vector<std::string>& items);

/// 0/U: no slip on the wall; the inlet's profile (mapped Poiseuille, or a plug: the flow rate,
/// or the velocity with options.velocity); at the outlets inletOutlet, or their flow rate.
std::string VelocityField(const CfdCaseResult& written, const CfdCaseOptions& options);
/// 0/p (kinematic): zero gradient at the wall and the inlet; at the outlets p = 0, zero
/// gradient (a prescribed flow) or fanPressure (a resistance).
std::string PressureField(const CfdCaseResult& written);
/// The fan curve of a resistance outlet (constant/resistance/<name>): the pressure rise, as
/// fanPressure reads it (kinematic, negative: p = p0 - curve(Q)), linear up to 10 x the inlet's
/// flow and held beyond.
std::string ResistanceCurve(const CfdOutletSetting& outlet, double density, double inletFlowRate);

/// The inlet's and the outlets' conditions, the wall cells across each end and the layers
/// asked for, as lines of the case's report.
std::string FormatCfdBoundaryConditions(const CfdCaseResult& written);

} // namespace bender

#endif
