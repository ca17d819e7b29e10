#include "ExportSurface.h"

#include "BenderErrors.h"
#include "MeshFormats.h"
#include "vtkBenderCapFilter.h"

#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <exception>
#include <optional>
#include <utility>

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
// A producer writing mesh through WriteMesh to the temporary file of an atomic set.
FileProducer MeshProducer(vtkSmartPointer<vtkPolyData> mesh, MeshWriteOptions writeOptions)
{
  return [mesh, writeOptions](const std::string& temp, std::string& problem)
  {
    try
    {
      WriteMesh(mesh, temp, writeOptions);
    }
    catch (const std::exception& e) // MeshIOError, and std's: AtomicWriteAll takes a problem
    {
      problem = e.what();
      return false;
    }
    return true;
  };
}

bool HasEndPatches(const std::vector<PatchLabel>& labels)
{
  for (const PatchLabel& label : labels)
  {
    if (label.id != kWallEntityId)
    {
      return true;
    }
  }
  return false;
}
// ExportSurface with the patch table of `surface` when already read (null: read here).
ExportSurfaceResult ExportSurfaceWith(vtkPolyData* surface,
  const std::vector<PatchLabel>* known,
  const ExportSurfaceOptions& options)
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
  if (!IsExportUnit(options.unit))
  {
    throw InputError(path + ": unknown unit '" + options.unit + "' (expected mm or m)");
  }
  // An unknown extension takes the WriteMesh path, which names the problem.
  const MeshFormat format = FindMeshFormat(path).value_or(MeshFormat{});
  MeshExportRequest request;
  request.encoding = options.stlEncoding;
  request.patches = options.patches;
  request.sidecar = options.patchesJson ? SidecarChoice::On : SidecarChoice::Off;
  const MeshExportRules rules = ResolveMeshExport(format, request);
  if (!rules.problem.empty())
  {
    throw InputError(path + ": " + rules.problem);
  }
  const std::string sidecarPath = PatchSidecarPath(path);
  if (rules.sidecar && !options.protectedPath.empty() &&
    SameFile(sidecarPath, options.protectedPath))
  {
    throw InputError(sidecarPath + ": refusing to overwrite the input file; choose another output");
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
      throw InputError(source + ": capping failed: " + caps->GetLastError());
    }
    bool labelledEnds = false;
    try
    {
      labelledEnds = HasEndPatches(known ? *known : ReadPatchLabels(surface));
    }
    catch (const InputError& e)
    {
      throw InputError(source + ": " + e.what());
    }
    result.caps = caps->GetNumberOfCaps();
    result.skippedLoops = caps->GetNumberOfSkippedLoops();
    // A surface already closed with labelled ends (capped, clipped) is kept as it is: capping
    // it again would find nothing and relabel it all wall.
    if (!(labelledEnds && result.caps == 0))
    {
      mesh = caps->GetOutput();
    }
    if (result.caps == 0 && !labelledEnds)
    {
      // A capped export without an inlet or outlet cannot set up a flow problem: say so
      // rather than write one solid "wall".
      throw InputError(result.skippedLoops == 0
          ? source +
            ": nothing to cap: the surface has no open end (it is closed; clip its vessel ends "
            "open first, e.g. bender-cli clip)"
          : source + ": nothing to cap: none of its " + std::to_string(result.skippedLoops) +
            " open boundary loops is planar enough (raise the planarity, now " +
            std::to_string(options.planarity) + ")");
    }
  }
  result.triangles = static_cast<long long>(mesh->GetNumberOfPolys());
  result.surface = mesh;

  // The patch table of the surface written, read once for every file below.
  const LabelledSurface labelled =
    known && mesh.Get() == surface ? LabelledSurface{ mesh, *known } : ReadLabelledSurface(mesh);
  result.patches = labelled.patches;
  const ExportTransform transform(options.frame, options.unit);
  std::vector<AtomicFile> files;
  if (rules.measure)
  {
    AtomicFile sidecar = PatchSidecarFile(labelled, sidecarPath, transform, &result.sidecar);
    result.measured = true;
    if (rules.sidecar)
    {
      files.push_back(std::move(sidecar));
    }
  }
  TetgenFormat tetgen = TetgenFormat::Smesh;
  if (format.namedPatches)
  {
    StlExportOptions stlOptions;
    stlOptions.patches = rules.patches;
    stlOptions.frame = options.frame;
    stlOptions.unit = options.unit;
    if (!options.protectedPath.empty())
    {
      // With one file per patch the names derive from the output: none may be the input.
      for (const std::string& planned : PlannedStlPaths(labelled, path, stlOptions))
      {
        if (SameFile(planned, options.protectedPath))
        {
          throw InputError(
            planned + ": refusing to overwrite the input file; choose another output");
        }
      }
    }
    std::vector<AtomicFile> stlFiles = StlFiles(labelled, path, stlOptions);
    files.insert(files.begin(), stlFiles.begin(), stlFiles.end());
  }
  else if (format.regionPoint && TetgenFormatForPath(path, tetgen))
  {
    files.insert(files.begin(),
      TetgenFile(labelled,
        path,
        tetgen,
        transform,
        result.sidecar.hasInsidePoint ? result.sidecar.insidePoint.data() : nullptr));
  }
  else
  {
    vtkSmartPointer<vtkPolyData> written = mesh;
    if (options.frame == StlFrame::RAS || options.unit != "mm" || format.patchLabels)
    {
      // RAS negates x and y (a half turn about z: orientation and volume are kept); metres
      // divide by 1000.
      written = vtkSmartPointer<vtkPolyData>::New();
      written->DeepCopy(mesh);
      vtkPoints* pts = written->GetPoints();
      for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
      {
        double p[3], q[3];
        pts->GetPoint(i, p);
        transform.Apply(p, q);
        pts->SetPoint(i, q);
      }
    }
    if (format.patchLabels)
    {
      // The VTK form states its frame and unit in field data beside the patch names.
      for (const auto& [name, value] :
        { std::pair<const char*, std::string>{ "Unit", options.unit },
          std::pair<const char*, std::string>{ "Frame", StlFrameName(options.frame) } })
      {
        vtkNew<vtkStringArray> array;
        array->SetName(name);
        array->InsertNextValue(value);
        written->GetFieldData()->RemoveArray(name);
        written->GetFieldData()->AddArray(array);
      }
    }
    MeshWriteOptions writeOptions;
    writeOptions.stlEncoding = rules.encoding;
    writeOptions.header = ExportHeader(options.frame, options.unit);
    files.insert(files.begin(), AtomicFile{ path, MeshProducer(written, writeOptions) });
  }
  std::string problem;
  if (!AtomicWriteAll(files, problem))
  {
    throw InputError(problem);
  }
  for (const AtomicFile& file : files)
  {
    result.written.push_back(file.path);
  }
  return result;
}
} // namespace

ExportSurfaceResult ExportSurface(vtkPolyData* surface, const ExportSurfaceOptions& options)
{
  return ExportSurfaceWith(surface, nullptr, options);
}

ExportSurfaceResult ExportSurface(const LabelledSurface& surface,
  const ExportSurfaceOptions& options)
{
  return ExportSurfaceWith(surface.surface, &surface.patches, options);
}

} // namespace bender
