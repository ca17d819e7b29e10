#include "IgtlSurfaceFromMesh.h"

#include "BenderErrors.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cstdint>
#include <limits>

namespace bender
{

IgtlSurface MakeIgtlSurface(vtkPolyData* mesh, const std::string& name)
{
  if (!mesh)
  {
    throw InputError(name + ": no surface to send");
  }
  if (mesh->GetNumberOfPoints() > vtkIdType(std::numeric_limits<std::uint32_t>::max()))
  {
    throw InputError(name + ": too many points for OpenIGTLink");
  }
  IgtlSurface surface;
  surface.points.reserve(std::size_t(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    surface.points.push_back({ p[0], p[1], p[2] });
  }
  vtkCellArray* polys = mesh->GetPolys();
  if (polys)
  {
    surface.polygons.reserve(std::size_t(polys->GetNumberOfCells()));
    vtkNew<vtkIdList> ids;
    for (polys->InitTraversal(); polys->GetNextCell(ids);)
    {
      std::vector<std::uint32_t> polygon;
      polygon.reserve(std::size_t(ids->GetNumberOfIds()));
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        polygon.push_back(std::uint32_t(ids->GetId(k)));
      }
      surface.polygons.push_back(std::move(polygon));
    }
  }
  if (surface.polygons.empty())
  {
    throw InputError(name + ": no polygons to send");
  }
  return surface;
}

} // namespace bender
