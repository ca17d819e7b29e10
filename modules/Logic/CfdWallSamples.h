#ifndef bender_CfdWallSamples_h
#define bender_CfdWallSamples_h

// The wall of a mapped CFD result (CASE/results/surface.vtp, CfdFlowResults.h) as one sample
// per wall triangle: centroid (LPS mm), area (mm^2), and the triangle's mean of the point data
// Pressure (Pa) and WallShearStressMagnitude (Pa). What the verification cases average and fit.

#include "Vec3.h"

#include <functional>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

struct CfdWallSample
{
  Vec3 centroid;     ///< LPS mm
  double area = 0.0; ///< mm^2
  double pressure = 0.0;
  double shear = 0.0;
};

using CfdWallFilter = std::function<bool(const CfdWallSample&)>;

/// The wall triangles (CellEntityIds 1) of a mapped surface. Throws InputError naming `name`
/// when the surface has no Pressure or WallShearStressMagnitude point data or no wall triangle.
std::vector<CfdWallSample> CfdWallSamplesOf(vtkPolyData* surface, const std::string& name);
/// CfdWallSamplesOf the surface read from `path` (ReadMesh).
std::vector<CfdWallSample> ReadCfdWallSamples(const std::string& path);

/// The area-weighted mean wall shear stress of the samples `keep` accepts (Pa). Throws
/// InputError when it accepts none.
double MeanWallShear(const std::vector<CfdWallSample>& samples, const CfdWallFilter& keep);

/// The slope dp/ds of the area-weighted least-squares line of pressure against the abscissa
/// s(sample) over the samples `keep` accepts (Pa per unit of s). Throws InputError when they
/// span no abscissa.
double WallPressureSlope(const std::vector<CfdWallSample>& samples,
  const std::function<double(const CfdWallSample&)>& abscissa,
  const CfdWallFilter& keep);

} // namespace bender

#endif
