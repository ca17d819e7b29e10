#include "CheckSurface.h"

#include "BenderErrors.h"
#include "MeshIO.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <exception>

namespace bender
{

MeshCheckReport CheckSurface(const CheckSurfaceOptions& options)
{
  vtkSmartPointer<vtkPolyData> mesh, before;
  try
  {
    mesh = ReadMesh(options.input);
    if (!options.before.empty())
    {
      before = ReadMesh(options.before);
    }
  }
  catch (const std::exception& e)
  {
    throw InputError(e.what());
  }
  return CheckMesh(mesh, before, options.check);
}

} // namespace bender
