#include "CheckSurface.h"

#include "MeshIO.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace bender
{

MeshCheckReport CheckSurface(const CheckSurfaceOptions& options)
{
  CheckSurfaceOptions meshOnly = options;
  meshOnly.lumen.enabled = false;
  return CheckSurfaceAndLumen(meshOnly).report;
}

SurfaceCheck CheckSurfaceAndLumen(const CheckSurfaceOptions& options)
{
  // ReadMesh's MeshIOError is an InputError already.
  const vtkSmartPointer<vtkPolyData> mesh = ReadMesh(options.input);
  const vtkSmartPointer<vtkPolyData> before =
    options.before.empty() ? nullptr : ReadMesh(options.before);
  SurfaceCheck check;
  check.report = CheckMesh(mesh, before, options.check);
  if (before && options.lumen.enabled)
  {
    check.lumen = CheckLumen(before, mesh, options.lumen);
  }
  return check;
}

} // namespace bender
