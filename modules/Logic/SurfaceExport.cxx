#include "SurfaceExport.h"

#include <vtkPolyData.h>

namespace bender
{

std::string ExportHeader(const ExportOptions& options)
{
  return "bender: frame " + options.frame + ", unit " + options.unit;
}

MeshCheckReport CheckForExport(vtkPolyData* surface, vtkPolyData* before)
{
  MeshCheckOptions checkOptions;
  checkOptions.requireClosed = false;
  checkOptions.selfIntersections = true;
  const bool sameTopology = before && surface &&
    before->GetNumberOfPoints() == surface->GetNumberOfPoints() &&
    before->GetNumberOfCells() == surface->GetNumberOfCells();
  return CheckMesh(surface, sameTopology ? before : nullptr, checkOptions);
}

void ExportSurface(vtkPolyData* surface, const std::string& path, const ExportOptions& options)
{
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    throw MeshIOError(path + ": there is no surface to export");
  }
  MeshWriteOptions writeOptions;
  writeOptions.stlEncoding = options.stlEncoding;
  writeOptions.header = ExportHeader(options);
  WriteMesh(surface, path, writeOptions);
}

} // namespace bender
