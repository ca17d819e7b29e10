#include "SurfaceExport.h"

#include "vtkBenderCapFilter.h"

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

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

std::vector<std::string> ExportSurface(
  vtkPolyData* surface, const std::string& path, const ExportOptions& options)
{
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    throw MeshIOError(path + ": there is no surface to export");
  }
  if (options.frame != "LPS" && options.frame != "RAS")
  {
    throw MeshIOError(path + ": unknown frame '" + options.frame + "' (LPS or RAS)");
  }
  vtkSmartPointer<vtkPolyData> mesh = surface;
  if (options.cap)
  {
    vtkNew<vtkBenderCapFilter> caps;
    caps->SetInputData(surface);
    caps->Update();
    if (!caps->GetLastError().empty())
    {
      throw std::runtime_error(path + ": capping failed: " + caps->GetLastError());
    }
    mesh = caps->GetOutput();
  }
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool stl = lower.size() > 4 && lower.compare(lower.size() - 4, 4, ".stl") == 0;
  if (stl && (options.patches != StlPatchMode::Single || options.frame == "RAS" ||
               mesh->GetCellData()->GetArray("PatchId")))
  {
    StlExportOptions stlOptions;
    stlOptions.patches = options.patches;
    stlOptions.frame = options.frame == "RAS" ? StlFrame::RAS : StlFrame::LPS;
    stlOptions.unit = options.unit;
    if (options.patches == StlPatchMode::Single && options.stlEncoding == StlEncoding::Ascii)
    {
      stlOptions.patches = StlPatchMode::Solids; // ASCII of the whole surface: named solids
    }
    if (!options.protectedPath.empty())
    {
      for (const std::string& planned : PlannedStlPaths(mesh, path, stlOptions))
      {
        if (SameFile(planned, options.protectedPath))
        {
          throw MeshIOError(planned + ": refusing to overwrite the input surface");
        }
      }
    }
    return ExportStl(mesh, path, stlOptions);
  }
  if (options.frame == "RAS")
  {
    // LPS -> RAS negates x and y (a half turn about z: orientation and volume are kept).
    auto ras = vtkSmartPointer<vtkPolyData>::New();
    ras->DeepCopy(mesh);
    vtkPoints* pts = ras->GetPoints();
    for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
    {
      double p[3];
      pts->GetPoint(i, p);
      pts->SetPoint(i, -p[0], -p[1], p[2]);
    }
    mesh = ras;
  }
  MeshWriteOptions writeOptions;
  writeOptions.stlEncoding = options.stlEncoding;
  writeOptions.header = ExportHeader(options);
  WriteMesh(mesh, path, writeOptions);
  return { path };
}

} // namespace bender
