#include "CfdCase.h"

#include "AtomicFile.h"
#include "AtomicFileRecovery.h"
#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "CfdBoundaryConditions.h"
#include "CfdCaseFile.h"
#include "CfdDictionaries.h"
#include "CfdMeshGrading.h"
#include "CfdMeshing.h"
#include "CfdPatches.h"
#include "CfdWallEnds.h"
#include "ExportSurface.h"
#include "FaultInjection.h"
#include "StringUtil.h"

#include <vtkAbstractArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace bender
{
namespace
{
/// A copy of `array`'s values and name without its vtkInformation (the ranges VTK caches
/// there once asked): the XML writer closes an array with information differently, so the same
/// surface would write different bytes depending on what was asked of it before.
vtkSmartPointer<vtkAbstractArray> WithoutInformation(vtkAbstractArray* array)
{
  vtkSmartPointer<vtkAbstractArray> fresh =
    vtkSmartPointer<vtkAbstractArray>::Take(array->NewInstance());
  fresh->SetName(array->GetName());
  fresh->SetNumberOfComponents(array->GetNumberOfComponents());
  fresh->InsertTuples(0, array->GetNumberOfTuples(), 0, array);
  return fresh;
}

/// The labelled surface as written into the case: the same bytes for the same surface (the
/// flow cache keys cases by their files), the caller's surface untouched.
vtkSmartPointer<vtkPolyData> AsWritten(vtkPolyData* surface)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(surface);
  vtkNew<vtkFieldData> fieldData;
  copy->SetFieldData(fieldData);
  for (int i = 0; i < surface->GetFieldData()->GetNumberOfArrays(); ++i)
  {
    fieldData->AddArray(WithoutInformation(surface->GetFieldData()->GetAbstractArray(i)));
  }
  for (vtkDataSetAttributes* data : { static_cast<vtkDataSetAttributes*>(copy->GetPointData()),
         static_cast<vtkDataSetAttributes*>(copy->GetCellData()) })
  {
    for (int i = 0; i < data->GetNumberOfArrays(); ++i)
    {
      // AddArray replaces the array of the same name in place (an unnamed one is kept).
      if (data->GetAbstractArray(i)->GetName())
      {
        data->AddArray(WithoutInformation(data->GetAbstractArray(i)));
      }
    }
  }
  if (surface->GetPoints())
  {
    vtkNew<vtkPoints> points;
    points->SetData(
      vtkDataArray::SafeDownCast(WithoutInformation(surface->GetPoints()->GetData())));
    copy->SetPoints(points);
  }
  return copy;
}

std::string SurfaceName(const CfdCaseOptions& options)
{
  return options.sourceName.empty() ? std::string("the surface") : options.sourceName;
}

void WriteText(const fs::path& path, const std::string& text)
{
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  std::string problem;
  if (ec || !AtomicWriteText(path.string(), text, problem))
  {
    throw InputError(path.string() + ": " + (ec ? ec.message() : problem));
  }
}

nlohmann::ordered_json CaseJson(const CfdCaseResult& r, const CfdCaseOptions& options)
{
  nlohmann::ordered_json j;
  j["format"] = "bender-cfd-case";
  j["unit"] = "m";
  j["frame"] = "LPS";
  j["surface"] = "constant/triSurface/" + options.surfaceName + ".stl";
  // The surface as labelled, LPS mm: MapCfdResults maps the results onto it.
  j["labelledSurface"] = "constant/triSurface/" + options.surfaceName + ".vtp";
  j["inlet"] = r.inlet;
  if (options.velocity > 0.0)
  {
    j["velocity"] = options.velocity;
  }
  else
  {
    j["flowRate"] = options.flowRate;
  }
  j["inletFlowRate"] = r.inletFlowRate;
  j["inletVelocity"] = r.inletVelocity;
  j["reynolds"] = r.reynolds;
  j["inletProfile"] = CfdInletProfileName(r.inletProfile);
  j["inletPeakToMean"] = r.inletPeakToMean;
  j["outletCondition"] = CfdOutletConditionName(r.outletCondition);
  nlohmann::ordered_json outlets = nlohmann::ordered_json::array();
  for (const CfdOutletSetting& o : r.outlets)
  {
    nlohmann::ordered_json outlet = { { "name", o.name },
      { "pressureReference", o.pressureReference } };
    if (r.outletCondition == CfdOutletCondition::Split ||
      r.outletCondition == CfdOutletCondition::Murray)
    {
      outlet["percentOfInlet"] = o.percent;
      outlet["flowRate_m3_per_s"] = o.flowRate;
    }
    if (r.outletCondition == CfdOutletCondition::Resistance)
    {
      outlet["resistance_Pa_s_per_m3"] = o.resistance;
    }
    outlets.push_back(outlet);
  }
  j["outlets"] = outlets;
  j["layers"] = r.layers;
  j["viscosity"] = options.viscosity;
  j["density"] = options.density;
  j["iterations"] = options.iterations;
  j["processors"] = options.processors;
  j["cellSize"] = r.cellSize;
  j["grading"] = CfdMeshGradingJson(r.grading);
  j["backgroundCellSize"] = r.backgroundCellSize;
  j["backgroundCells"] = r.backgroundCells;
  j["insidePoint"] = r.insidePoint;
  j["patches"] = CfdPatchesJson(r.patches);
  return j;
}

/// Refuses a vessel whose size no vessel has, naming the likely unit mistake: the largest end
/// narrower than 50 um (a surface in metres read as millimetres: 1000 x too small) or wider
/// than 300 mm, or the vessel longer than 3 m (micrometres: 1000 x too large).
void CheckScale(vtkPolyData* surface, double largestEnd, const std::string& name)
{
  double bounds[6];
  surface->GetBounds(bounds);
  const double extent =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  const std::string measured = ": its widest end is " + CfdShort(1e3 * largestEnd) +
    " mm across and it spans " + CfdShort(extent) + " mm";
  if (largestEnd < 50e-6)
  {
    throw InputError(name + measured +
      ": the vessel looks 1000x too small; was it written in metres? (Bender reads "
      "millimetres: scale it by 1000)");
  }
  if (largestEnd > 0.3 || extent > 3000.0)
  {
    throw InputError(name + measured +
      ": the vessel looks 1000x too large; was it written in micrometres? (Bender reads "
      "millimetres: scale it by 0.001)");
  }
}

/// The cell size on the inlet (the faces its profile is sampled on).
double InletCellSize(const CfdCaseResult& r)
{
  for (const CfdEndCells& e : r.grading.ends)
  {
    if (e.name == r.inlet)
    {
      return e.cellSize;
    }
  }
  return r.cellSize;
}

void CheckOption(bool ok, const std::string& what)
{
  if (!ok)
  {
    throw InputError(what);
  }
}

// WriteOpenFoamCase with the patch table of `surface` when already read (null: read here).
CfdCaseResult WriteCase(vtkPolyData* surface,
  const std::vector<PatchLabel>* known,
  const CfdCaseOptions& options)
{
  const std::string name = SurfaceName(options);
  CheckOption(!options.caseDirectory.empty(), "give the case folder");
  CheckOption(
    std::isfinite(options.velocity) && options.velocity >= 0.0 && options.velocity < 100.0,
    "--velocity " + CfdNumber(options.velocity) + ": give a velocity in m/s, > 0 and < 100");
  CheckOption(options.velocity > 0.0 ||
      (std::isfinite(options.flowRate) && options.flowRate > 0.0 && options.flowRate < 1.0),
    "--flow-rate " + CfdNumber(options.flowRate) + ": give a flow rate in m^3/s, > 0 and < 1");
  CheckOption(options.layers >= 0 && options.layers <= 10,
    "--layers " + std::to_string(options.layers) + ": give 0 to 10");
  CheckOption(std::isfinite(options.cellSize) && options.cellSize >= 0.0 && options.cellSize < 1.0,
    "--cell-size " + CfdNumber(options.cellSize) + ": give a cell size in m, > 0 and < 1");
  CheckOption(std::isfinite(options.cellsAcross) &&
      (options.cellsAcross == 0.0 || (options.cellsAcross >= 2.0 && options.cellsAcross <= 200.0)),
    "--cells-across " + CfdNumber(options.cellsAcross) + ": give 2 to 200");
  CheckOption(
    std::isfinite(options.viscosity) && options.viscosity > 0.0 && options.viscosity < 1.0,
    "--viscosity " + CfdNumber(options.viscosity) + ": give a kinematic viscosity in m^2/s, > 0");
  CheckOption(std::isfinite(options.density) && options.density > 0.0,
    "density " + CfdNumber(options.density) + ": must be > 0");
  CheckOption(options.iterations >= 1 && options.iterations <= 1000000,
    "--iterations " + std::to_string(options.iterations) + ": give 1 to 1000000");
  CheckOption(options.processors >= 1 && options.processors <= 4096,
    "--processors " + std::to_string(options.processors) + ": give 1 to 4096");
  CheckOption(options.decomposition == "hierarchical" || options.decomposition == "scotch" ||
      options.decomposition == "simple",
    "--decomposition " + options.decomposition + ": give hierarchical, scotch or simple");
  CheckOption(IsValidPatchName(options.surfaceName),
    "surface name '" + options.surfaceName + "': use letters, digits and _");
  if (!surface || surface->GetNumberOfPolys() + surface->GetNumberOfStrips() == 0)
  {
    throw InputError(name + ": no triangles");
  }

  // The folder: new, or empty, or replaced with force.
  const fs::path target = fs::path(options.caseDirectory);
  std::error_code ec;
  const bool exists = fs::exists(target, ec);
  if (exists)
  {
    if (!fs::is_directory(target, ec))
    {
      throw InputError(options.caseDirectory + ": exists and is not a folder");
    }
    if (!fs::is_empty(target, ec) && !options.force)
    {
      throw InputError(
        options.caseDirectory + ": the folder is not empty (use --force to replace it)");
    }
  }
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(parent, ec))
  {
    throw InputError(options.caseDirectory + ": folder " + parent.string() + " does not exist");
  }

  // The surface: closed, consistently oriented, labelled with an inlet and an outlet.
  MeshCheckOptions checkOptions;
  checkOptions.selfIntersections = false;
  const MeshCheckReport report = CheckMesh(surface, nullptr, checkOptions);
  if (!report.closed)
  {
    throw InputError(name + ": the surface is not closed (" + std::to_string(report.boundaryEdges) +
      " boundary edges in " + std::to_string(report.boundaryLoops.size()) + " open loops, " +
      std::to_string(report.nonManifoldEdges) +
      " non-manifold edges): clip and cap its ends first (bender-cli clip)");
  }
  if (report.inconsistentEdges > 0)
  {
    throw InputError(name + ": the triangles are not consistently oriented (" +
      std::to_string(report.inconsistentEdges) + " edges)");
  }
  LabelledSurface labelled =
    known ? LabelledSurface{ surface, *known } : ReadLabelledSurface(surface);
  // The patches and the point inside the lumen, measured once (LPS millimetres); its one-line
  // problems (non-finite coordinates, a bad cell array) get the surface's name.
  PatchSidecar measured;
  try
  {
    measured = ComputePatchSidecar(labelled, ExportTransform(StlFrame::LPS, "mm"));
  }
  catch (const StlExportError& e)
  {
    throw InputError(name + ": " + e.what());
  }
  std::vector<CfdPatch> patches = CfdPatchesOf(measured, name);
  const std::vector<std::size_t> ends = EndPatches(patches);
  if (ends.size() < 2)
  {
    throw InputError(name +
      ": a flow case needs an inlet and at least one outlet, the surface has " +
      std::to_string(ends.size()) +
      " labelled end(s) (cap or clip its ends: bender-cli clip, export --cap)");
  }
  // The inlet, and names that say the roles in the case, its STL and bender-case.json.
  const std::size_t inlet = ChooseInlet(patches, labelled, options.inlet, name);

  // Sizes (metres).
  double smallest = 0.0, largest = 0.0;
  for (const std::size_t i : ends)
  {
    if (smallest == 0.0 || patches[i].diameter < smallest)
    {
      smallest = patches[i].diameter;
    }
    largest = std::max(largest, patches[i].diameter);
  }
  CheckScale(surface, largest, name);
  CheckNoWallEnd(labelled, 1e3 * smallest, name);
  CfdCaseResult result;
  result.caseDirectory = options.caseDirectory;
  result.inlet = patches[inlet].name;
  // The grading: the cells across every end, the base cell from the largest end unless given.
  const double across = options.cellsAcross > 0.0 ? options.cellsAcross
    : options.cellSize > 0.0                      ? smallest / options.cellSize
                                                  : kCfdDefaultCellsAcross;
  result.cellSize = options.cellSize > 0.0 ? options.cellSize : largest / across;
  if (!(result.cellSize > 0.0) || !(smallest > 0.0))
  {
    throw InputError(name + ": its ends have no area");
  }
  CfdGradedMesh graded = GradeCfdMesh(labelled, patches, result.cellSize, across);
  result.grading = graded.grading;
  result.backgroundCellSize = 2.0 * result.cellSize;
  const double hb = result.backgroundCellSize;
  double bounds[6];
  surface->GetBounds(bounds);
  std::array<double, 3> origin{};
  double cells = 1.0;
  for (std::size_t k = 0; k < 3; ++k)
  {
    // Two cells of margin, shifted off the surface's bounds by a fraction of a cell.
    const double lo = 1e-3 * bounds[2 * k], hi = 1e-3 * bounds[2 * k + 1];
    origin[k] = lo - 2.137 * hb;
    const double n = std::ceil((hi - origin[k]) / hb + 2.0);
    if (!(n < 1e6))
    {
      throw InputError("--cell-size " + CfdNumber(result.cellSize) + ": far too small for " + name);
    }
    result.backgroundCells[k] = static_cast<int>(n);
    cells *= n;
  }
  if (cells > 2e7)
  {
    throw InputError("--cell-size " + CfdNumber(result.cellSize) + " m: the background mesh of " +
      name + " would have " + CfdShort(cells) + " cells; give a larger cell size");
  }
  result.insidePoint = InsidePoint(measured, result.cellSize, name);
  result.patches = patches;
  const CfdPatch& in = patches[inlet];
  result.inletFlowRate = options.velocity > 0.0 ? options.velocity * in.area : options.flowRate;
  result.inletVelocity = in.area > 0.0 ? result.inletFlowRate / in.area : 0.0;
  result.reynolds = result.inletVelocity * in.diameter / options.viscosity;
  result.outletCondition = options.outlets;
  result.outlets = CfdOutletSettings(patches, options, result.inletFlowRate);
  result.layers = options.layers;
  result.inletProfile = options.inletProfile;
  CfdInletProfileData profile;
  if (options.inletProfile == CfdInletProfile::Poiseuille)
  {
    CfdInletFlow inlet;
    for (const PatchLabel& l : labelled.patches)
    {
      inlet.id = l.name == in.name ? l.id : inlet.id;
    }
    inlet.outwardNormal = in.normal;
    inlet.flowRate = result.inletFlowRate;
    inlet.faceSize = InletCellSize(result);
    profile = PoiseuilleInletProfile(labelled.surface, CellPatchIds(labelled.surface), inlet, name);
    result.inletPeakToMean = profile.peakToMean;
  }

  // Everything into a temporary sibling, put in place in one step when complete
  // (AtomicFileRecovery.h): a crash leaves the previous case or none, never half of one.
  fs::path temp;
  try
  {
    temp = TemporaryFolderBeside(target.string());
  }
  catch (const fs::filesystem_error& e)
  {
    throw InputError(
      options.caseDirectory + ": cannot create a folder beside it (" + e.code().message() + ")");
  }
  try
  {
    fs::permissions(temp,
      fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
        fs::perms::others_read | fs::perms::others_exec);
    const std::string stl = options.surfaceName + ".stl";
    fs::create_directories(temp / "constant" / "triSurface");
    ExportSurfaceOptions exportOptions;
    exportOptions.output = (temp / "constant" / "triSurface" / stl).string();
    exportOptions.unit = "m";
    exportOptions.stlEncoding = StlEncoding::Ascii;
    exportOptions.patches = StlPatchMode::Solids;
    exportOptions.sourceName = options.sourceName;
    ExportSurface(labelled, exportOptions);
    result.written.push_back("constant/triSurface/" + stl);
    for (std::size_t i = 0; i < graded.regionSurfaces.size(); ++i)
    {
      // The wall triangles of each refinement region, in metres (snappyHexMesh's distances).
      const std::string region = "constant/triSurface/" + result.grading.regions[i].name + ".stl";
      ExportSurfaceOptions regionOptions;
      regionOptions.output = (temp / region).string();
      regionOptions.unit = "m";
      regionOptions.stlEncoding = StlEncoding::Ascii;
      regionOptions.sourceName = result.grading.regions[i].name;
      ExportSurface(graded.regionSurfaces[i], regionOptions);
      result.written.push_back(region);
    }
    const std::string vtp = options.surfaceName + ".vtp";
    WriteMesh(AsWritten(labelled.surface), (temp / "constant" / "triSurface" / vtp).string());
    result.written.push_back("constant/triSurface/" + vtp);
    std::vector<std::pair<std::string, std::string>> files = {
      { "system/blockMeshDict", BlockMeshDict(origin, hb, result.backgroundCells) },
      { "system/surfaceFeatureExtractDict", SurfaceFeatureExtractDict(stl) },
      { "system/snappyHexMeshDict",
        SnappyHexMeshDict(options.surfaceName,
          patches,
          result.insidePoint,
          result.cellSize,
          options.layers,
          result.grading) },
      { "system/controlDict", ControlDict(patches, options.iterations) },
      { "system/fvSchemes", FvSchemes() },
      { "system/fvSolution", FvSolution() },
      { "system/decomposeParDict",
        DecomposeParDict(options.processors,
          options.decomposition,
          { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] }) },
      { "constant/transportProperties", TransportProperties(options.viscosity) },
      { "constant/turbulenceProperties", TurbulenceProperties() },
      { "0/U", VelocityField(result, options) },
      { "0/p", PressureField(result) },
      { "Allrun",
        Allrun(options.processors,
          options.inletProfile == CfdInletProfile::Poiseuille ? in.name : std::string(),
          result.inletFlowRate) },
    };
    if (options.inletProfile == CfdInletProfile::Poiseuille)
    {
      files.emplace_back("system/inletFlow", InletFlowDict(in.name));
      const std::string data = "constant/boundaryData/" + in.name + "/";
      files.emplace_back(data + "points", BoundaryDataPoints(profile));
      files.emplace_back(data + "0/U", BoundaryDataVelocity(profile));
    }
    for (const CfdOutletSetting& o : result.outlets)
    {
      if (o.resistance > 0.0)
      {
        files.emplace_back("constant/resistance/" + o.name,
          ResistanceCurve(o, options.density, result.inletFlowRate));
      }
    }
    files.emplace_back(kCfdCaseJson, CaseJson(result, options).dump(2) + "\n");
    for (const auto& [path, text] : files)
    {
      WriteText(temp / path, text);
      result.written.push_back(path);
      FaultPoint("cfd-case");
    }
    fs::permissions(temp / "Allrun",
      fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
      fs::perm_options::add);
  }
  catch (const InputError& e)
  {
    // A write that failed (a full disk): the case named, never its temporary sibling.
    fs::remove_all(temp, ec);
    std::string what = e.what();
    for (std::size_t at = what.find(temp.string()); at != std::string::npos;
         at = what.find(temp.string()))
    {
      what.replace(at, temp.string().size(), target.string());
    }
    throw InputError(
      StartsWith(what, options.caseDirectory) ? what : options.caseDirectory + ": " + what);
  }
  catch (...)
  {
    fs::remove_all(temp, ec);
    throw;
  }

  std::string problem;
  if (!AtomicReplaceFolder(temp.string(), target.string(), problem))
  {
    fs::remove_all(temp, ec);
    throw InputError(options.caseDirectory + ": " + problem);
  }
  return result;
}
} // namespace

CfdCaseResult WriteOpenFoamCase(vtkPolyData* surface, const CfdCaseOptions& options)
{
  return WriteCase(surface, nullptr, options);
}

CfdCaseResult WriteOpenFoamCase(const LabelledSurface& surface, const CfdCaseOptions& options)
{
  return WriteCase(surface.surface, &surface.patches, options);
}

} // namespace bender
