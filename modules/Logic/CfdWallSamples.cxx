#include "CfdWallSamples.h"

#include "BenderErrors.h"
#include "CfdFlowResults.h"
#include "MeshIO.h"
#include "PatchLabels.h"

#include <vtkCell.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>

namespace bender
{

std::vector<CfdWallSample> CfdWallSamplesOf(vtkPolyData* surface, const std::string& name)
{
  vtkDataArray* pressure = surface->GetPointData()->GetArray(kPressureArrayName);
  vtkDataArray* shear = surface->GetPointData()->GetArray(kWallShearStressMagnitudeArrayName);
  if (!pressure || !shear)
  {
    throw InputError(name +
      ": no Pressure and WallShearStressMagnitude point data (map the "
      "results of a run first)");
  }
  const std::vector<int> ids = CellPatchIds(surface);
  std::vector<CfdWallSample> samples;
  for (vtkIdType i = 0; i < surface->GetNumberOfCells(); ++i)
  {
    if (ids[static_cast<std::size_t>(i)] != kWallEntityId)
    {
      continue;
    }
    vtkCell* cell = surface->GetCell(i);
    if (cell->GetNumberOfPoints() != 3)
    {
      continue;
    }
    Vec3 p[3];
    CfdWallSample s;
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType id = cell->GetPointId(k);
      double x[3];
      surface->GetPoint(id, x);
      p[k] = { x[0], x[1], x[2] };
      s.centroid += p[k] / 3.0;
      s.pressure += pressure->GetComponent(id, 0) / 3.0;
      s.shear += shear->GetComponent(id, 0) / 3.0;
    }
    s.area = 0.5 * Norm(Cross(p[1] - p[0], p[2] - p[0]));
    samples.push_back(s);
  }
  if (samples.empty())
  {
    throw InputError(name + ": no wall triangle (CellEntityIds 1)");
  }
  return samples;
}

std::vector<CfdWallSample> ReadCfdWallSamples(const std::string& path)
{
  return CfdWallSamplesOf(ReadMesh(path), path);
}

double MeanWallShear(const std::vector<CfdWallSample>& samples, const CfdWallFilter& keep)
{
  double area = 0.0, sum = 0.0;
  for (const CfdWallSample& s : samples)
  {
    if (keep(s))
    {
      area += s.area;
      sum += s.area * s.shear;
    }
  }
  if (!(area > 0.0))
  {
    throw InputError("no wall triangle in the range to average");
  }
  return sum / area;
}

double WallPressureSlope(const std::vector<CfdWallSample>& samples,
  const std::function<double(const CfdWallSample&)>& abscissa,
  const CfdWallFilter& keep)
{
  double w = 0.0, ws = 0.0, wp = 0.0;
  for (const CfdWallSample& s : samples)
  {
    if (keep(s))
    {
      w += s.area;
      ws += s.area * abscissa(s);
      wp += s.area * s.pressure;
    }
  }
  if (!(w > 0.0))
  {
    throw InputError("no wall triangle in the range to fit");
  }
  const double meanS = ws / w, meanP = wp / w;
  double sxx = 0.0, sxp = 0.0;
  for (const CfdWallSample& s : samples)
  {
    if (keep(s))
    {
      const double ds = abscissa(s) - meanS;
      sxx += s.area * ds * ds;
      sxp += s.area * ds * (s.pressure - meanP);
    }
  }
  if (!(sxx > 0.0))
  {
    throw InputError("the wall triangles in the range span no length to fit");
  }
  return sxp / sxx;
}

} // namespace bender
