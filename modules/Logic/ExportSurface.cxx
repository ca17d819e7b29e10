#include "ExportSurface.h"

#include "BenderErrors.h"
#include "vtkBenderCapFilter.h"

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cctype>
#include <exception>

namespace bender
{

std::string ExportHeader(StlFrame frame, const std::string& unit)
{
  return std::string("bender export: frame ") + (frame == StlFrame::RAS ? "RAS" : "LPS") +
    ", unit " + unit;
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

namespace
{
bool HasExtension(const std::string& path, const std::string& ext)
{
  if (path.size() < ext.size())
  {
    return false;
  }
  std::string tail = path.substr(path.size() - ext.size());
  std::transform(tail.begin(),
    tail.end(),
    tail.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return tail == ext;
}
} // namespace

ExportSurfaceResult ExportSurface(vtkPolyData* surface, const ExportSurfaceOptions& options)
{
  const std::string& path = options.output;
  if (path.empty())
  {
    throw InputError("export: no output file given");
  }
  const std::string source = options.sourceName.empty() ? "the surface" : options.sourceName;
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    throw InputError(source + ": there is no surface to export (no points)");
  }
  if (surface->GetNumberOfPolys() + surface->GetNumberOfStrips() == 0)
  {
    throw InputError(source + ": the surface has no triangles (nothing to export)");
  }
  if (!options.protectedPath.empty() && SameFile(path, options.protectedPath))
  {
    throw InputError(path + ": refusing to overwrite the input file; choose another output");
  }
  if (!(options.planarity >= 0.0 && options.planarity <= 1.0))
  {
    throw InputError(path + ": the cap planarity must be in [0, 1]");
  }
  const bool stl = HasExtension(path, ".stl");
  if (!stl && options.patches != StlPatchMode::Single)
  {
    throw InputError(path +
      ": patches (solids, files) are written as .stl only; .vtp keeps "
      "them as the PatchId cell labels");
  }

  ExportSurfaceResult result;
  vtkSmartPointer<vtkPolyData> mesh = surface;
  if (options.cap)
  {
    vtkNew<vtkBenderCapFilter> caps;
    caps->SetInputData(surface);
    caps->SetPlanarity(options.planarity);
    caps->Update();
    if (!caps->GetLastError().empty())
    {
      throw InputError(path + ": capping failed: " + caps->GetLastError());
    }
    mesh = caps->GetOutput();
    result.caps = caps->GetNumberOfCaps();
    result.skippedLoops = caps->GetNumberOfSkippedLoops();
  }
  result.triangles = static_cast<long long>(mesh->GetNumberOfPolys());
  result.surface = mesh;

  try
  {
    if (stl)
    {
      StlExportOptions stlOptions;
      stlOptions.patches = options.patches;
      stlOptions.frame = options.frame;
      stlOptions.unit = options.unit;
      if (options.patches == StlPatchMode::Single && options.stlEncoding == StlEncoding::Ascii)
      {
        stlOptions.patches = StlPatchMode::Solids; // ASCII of the whole surface: named solids
      }
      if (!options.protectedPath.empty())
      {
        // With one file per patch the names derive from the output: none may be the input.
        for (const std::string& planned : PlannedStlPaths(mesh, path, stlOptions))
        {
          if (SameFile(planned, options.protectedPath))
          {
            throw InputError(
              planned + ": refusing to overwrite the input file; choose another output");
          }
        }
      }
      result.written = ExportStl(mesh, path, stlOptions);
      return result;
    }
    if (options.frame == StlFrame::RAS)
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
    writeOptions.header = ExportHeader(options.frame, options.unit);
    WriteMesh(mesh, path, writeOptions);
    result.written = { path };
  }
  catch (const InputError&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    // MeshIOError, StlExportError: one line naming the file already.
    throw InputError(e.what());
  }
  return result;
}

} // namespace bender
