#include "CoordinateRange.h"

#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <sstream>

namespace bender
{

bool InMeshCoordinateRange(double value)
{
  return std::isfinite(value) && std::fabs(value) <= MaxMeshCoordinate;
}

bool InMeshCoordinateRange(const double p[3])
{
  return InMeshCoordinateRange(p[0]) && InMeshCoordinateRange(p[1]) && InMeshCoordinateRange(p[2]);
}

std::string CoordinateRangeProblem(const double p[3])
{
  for (int a = 0; a < 3; ++a)
  {
    if (InMeshCoordinateRange(p[a]))
    {
      continue;
    }
    std::ostringstream text;
    if (!std::isfinite(p[a]))
    {
      text << "non-finite coordinate (" << p[a] << ")";
    }
    else
    {
      text << "coordinate " << p[a]
           << " is beyond the single-precision range (|x| <= " << MaxMeshCoordinate << ")";
    }
    return text.str();
  }
  return {};
}

std::string MeshCoordinateRangeProblem(vtkPolyData* mesh)
{
  vtkPoints* points = mesh ? mesh->GetPoints() : nullptr;
  const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    if (!InMeshCoordinateRange(p))
    {
      return "point " + std::to_string(i) + ": " + CoordinateRangeProblem(p);
    }
  }
  return {};
}

} // namespace bender
