#include "CheckSurface.h"

#include "MeshIO.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace bender
{

MeshCheckReport CheckSurface(const CheckSurfaceOptions& options)
{
  // ReadMesh's MeshIOError is an InputError already.
  const vtkSmartPointer<vtkPolyData> mesh = ReadMesh(options.input);
  const vtkSmartPointer<vtkPolyData> before =
    options.before.empty() ? nullptr : ReadMesh(options.before);
  return CheckMesh(mesh, before, options.check);
}

} // namespace bender
