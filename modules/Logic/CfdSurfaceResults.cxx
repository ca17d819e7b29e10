#include "CfdFlowResults.h"

#include "AtomicFile.h"
#include "AtomicFileRecovery.h"
#include "BenderErrors.h"
#include "CfdCase.h"
#include "CfdCaseFile.h"
#include "CfdDictionaries.h"
#include "FaultInjection.h"
#include "MeshIO.h"
#include "VtkMessageGuard.h"

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCompositeDataIterator.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkGenericCell.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOpenFOAMReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolygon.h>
#include <vtkStaticCellLocator.h>
#include <vtkStringArray.h>
#include <vtkTriangleFilter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

// MapCfdResults: the case's last time, read by vtkOpenFOAMReader, mapped onto the case's
// labelled surface in mm, and CASE/results written whole.

namespace fs = std::filesystem;

namespace bender
{

namespace
{

constexpr double kMetresToMm = 1000.0;

/// What MapCfdResults needs from bender-case.json.
struct CaseRecord
{
  std::string labelledSurface; ///< relative to the case
  CfdFlowSettings settings;
  int iterationLimit = 0;
};

CaseRecord ReadCaseRecord(const fs::path& dir)
{
  const fs::path path = dir / kCfdCaseJson;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!in.is_open() || j.is_discarded() || !j.is_object())
  {
    throw InputError(path.string() + ": missing or not JSON (not a case of bender-cli cfd-case)");
  }
  CaseRecord r;
  try
  {
    if (!j.contains("labelledSurface"))
    {
      throw InputError(path.string() +
        ": names no labelled surface (a case of an older Bender: write it again with "
        "bender-cli cfd-case)");
    }
    r.labelledSurface = j.at("labelledSurface").get<std::string>();
    r.settings.densityKgPerM3 = j.at("density").get<double>();
    r.settings.viscosityM2PerS = j.at("viscosity").get<double>();
    r.settings.inletFlowRateMlPerMin = j.at("inletFlowRate").get<double>() * 6e7;
    r.settings.inletVelocityMPerS = j.at("inletVelocity").get<double>();
    r.settings.reynolds = j.at("reynolds").get<double>();
    r.settings.cellSizeMm = j.at("cellSize").get<double>() * kMetresToMm;
    r.settings.processors = j.at("processors").get<int>();
    r.iterationLimit = j.at("iterations").get<int>();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(path.string() + ": " + e.what());
  }
  return r;
}

/// The number of cells checkMesh reported ("cells: N"); 0 when the log has none.
long long CheckMeshCells(const fs::path& dir)
{
  const std::string log = ReadTextFile(dir / "log.checkMesh");
  const std::size_t at = log.find("    cells:");
  return at == std::string::npos ? 0 : std::atoll(log.c_str() + at + 10);
}

/// The message of a diverged solution: `field` is not finite at `time`.
std::string DivergedMessage(const std::string& caseDirectory,
  const std::string& field,
  const std::string& where,
  double time)
{
  return caseDirectory + ": the solution diverged: " + field + " is not finite" + where +
    " at time " + CfdShort(time, 6) +
    " (see log.simpleFoam; try a finer mesh, a lower velocity or more iterations)";
}

/// The first field of the time folder whose file holds a nan or inf word (OpenFOAM writes
/// them so when a run diverged without a floating-point trap; VTK's reader cannot read them);
/// empty when none.
std::string NonFiniteField(const fs::path& timeFolder)
{
  static const std::regex word(R"((^|[\s(])-?(nan|inf)([\s)]|$))", std::regex::icase);
  for (const char* field : { "p", "U", "wallShearStress", "phi" })
  {
    const std::string text = ReadTextFile(timeFolder / field);
    if (!text.empty() && std::regex_search(text, word))
    {
      return field;
    }
  }
  return "";
}

/// Throws Error when an array of `data` holds NaN or infinity.
void CheckFinite(vtkFieldData* data,
  const std::string& where,
  const std::string& caseDirectory,
  double time)
{
  for (int a = 0; a < data->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = data->GetArray(a);
    if (!array)
    {
      continue;
    }
    const vtkIdType values = array->GetNumberOfValues();
    for (vtkIdType i = 0; i < values; ++i)
    {
      if (!std::isfinite(array->GetComponent(i / array->GetNumberOfComponents(),
            static_cast<int>(i % array->GetNumberOfComponents()))))
      {
        throw Error(DivergedMessage(caseDirectory, array->GetName(), " on " + where, time));
      }
    }
  }
}

/// A patch of the mesh in mm, triangulated, with its point data, and its location.
struct MeshPatch
{
  vtkSmartPointer<vtkPolyData> faces;
  vtkSmartPointer<vtkStaticCellLocator> locator;
  double area = 0.0;         ///< mm^2
  double meanPressure = 0.0; ///< kinematic, area-weighted (m^2/s^2)
};

/// The points of `data` (m) in mm.
vtkSmartPointer<vtkPoints> PointsInMm(vtkDataSet* data)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(data->GetNumberOfPoints());
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double x[3];
    data->GetPoint(i, x);
    points->SetPoint(i, x[0] * kMetresToMm, x[1] * kMetresToMm, x[2] * kMetresToMm);
  }
  return points;
}

MeshPatch MakeMeshPatch(vtkPolyData* patch)
{
  MeshPatch m;
  vtkNew<vtkPolyData> mm;
  mm->DeepCopy(patch);
  mm->SetPoints(PointsInMm(patch));
  // Area-weighted mean of the face pressures, on the faces as OpenFOAM has them.
  vtkDataArray* p = mm->GetCellData()->GetArray("p");
  double weighted = 0.0;
  for (vtkIdType c = 0; c < mm->GetNumberOfCells(); ++c)
  {
    vtkCell* cell = mm->GetCell(c);
    double normal[3];
    const double area = vtkPolygon::ComputeArea(
      mm->GetPoints(), cell->GetNumberOfPoints(), cell->GetPointIds()->GetPointer(0), normal);
    m.area += area;
    weighted += p ? p->GetTuple1(c) * area : 0.0;
  }
  m.meanPressure = m.area > 0.0 ? weighted / m.area : 0.0;
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mm);
  triangles->Update();
  m.faces = triangles->GetOutput();
  m.locator = vtkSmartPointer<vtkStaticCellLocator>::New();
  m.locator->SetDataSet(m.faces);
  m.locator->BuildLocator();
  return m;
}

/// The pressure (kinematic) and wall shear stress (kinematic, zeros where the patch has none)
/// of `patch` interpolated at its point closest to x (mm). `cell` is scratch space.
void Sample(const MeshPatch& patch,
  const double x[3],
  vtkGenericCell* cell,
  double& p,
  double tau[3])
{
  p = 0.0;
  std::fill(tau, tau + 3, 0.0);
  double closest[3], dist2 = 0.0, pcoords[3], weights[3], unused = 0.0;
  vtkIdType cellId = -1;
  int subId = 0;
  patch.locator->FindClosestPoint(x, closest, cell, cellId, subId, dist2);
  if (cellId < 0)
  {
    return;
  }
  cell->EvaluatePosition(closest, nullptr, subId, pcoords, unused, weights);
  vtkPointData* data = patch.faces->GetPointData();
  vtkDataArray* pressure = data->GetArray("p");
  vtkDataArray* wss = data->GetArray("wallShearStress");
  for (vtkIdType k = 0; k < cell->GetNumberOfPoints() && k < 3; ++k)
  {
    const vtkIdType id = cell->GetPointId(k);
    p += pressure ? weights[k] * pressure->GetTuple1(id) : 0.0;
    for (int c = 0; wss && wss->GetNumberOfComponents() == 3 && c < 3; ++c)
    {
      tau[c] += weights[k] * wss->GetComponent(id, c);
    }
  }
}

/// The blocks of the reader's output by name: "internalMesh" and each boundary patch.
void CollectBlocks(vtkMultiBlockDataSet* blocks,
  vtkSmartPointer<vtkUnstructuredGrid>& internal,
  std::map<std::string, vtkPolyData*>& patches)
{
  for (unsigned int b = 0; b < blocks->GetNumberOfBlocks(); ++b)
  {
    vtkDataObject* block = blocks->GetBlock(b);
    const char* name =
      blocks->HasMetaData(b) ? blocks->GetMetaData(b)->Get(vtkCompositeDataSet::NAME()) : nullptr;
    if (auto* grid = vtkUnstructuredGrid::SafeDownCast(block))
    {
      internal = grid;
    }
    else if (auto* poly = vtkPolyData::SafeDownCast(block); poly && name)
    {
      patches[name] = poly;
    }
    else if (auto* child = vtkMultiBlockDataSet::SafeDownCast(block))
    {
      CollectBlocks(child, internal, patches);
    }
  }
}

/// surface.vtp, volume.vtu and flow.json into a new folder, put in place of CASE/results.
void WriteResultsFolder(const fs::path& dir,
  vtkPolyData* surface,
  vtkUnstructuredGrid* volume,
  const CfdFlowResults& results)
{
  const fs::path target = dir / kCfdResultsFolder;
  fs::path temp;
  try
  {
    temp = TemporaryFolderBeside(target.string());
  }
  catch (const fs::filesystem_error& e)
  {
    throw Error(
      target.string() + ": cannot create a folder beside it (" + e.code().message() + ")");
  }
  std::error_code ec;
  try
  {
    // A write that fails (a full disk) names the results folder, not its temporary sibling.
    try
    {
      WriteMesh(surface, (temp / kCfdSurfaceResults).string());
    }
    catch (const MeshIOError& e)
    {
      throw Error(target.string() + ": " + e.what());
    }
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetInputData(volume);
    writer->SetFileName((temp / kCfdVolumeResults).string().c_str());
    writer->SetDataModeToAppended();
    writer->SetCompressorTypeToZLib();
    std::string problem;
    if (!io_detail::RunWriter(writer.Get(), problem))
    {
      throw Error((target / kCfdVolumeResults).string() + ": " + problem);
    }
    FaultPoint("cfd-results");
    if (!AtomicWriteText((temp / kCfdFlowJson).string(), CfdFlowResultsToJson(results), problem))
    {
      throw Error((target / kCfdFlowJson).string() + ": " + problem);
    }
    if (!AtomicReplaceFolder(temp.string(), target.string(), problem))
    {
      throw Error(target.string() + ": " + problem);
    }
  }
  catch (...) // whatever stopped the write: the half-written folder goes, the error goes on
  {
    fs::remove_all(temp, ec);
    throw;
  }
}

CfdRunSummary Summarise(const CfdRunResult& run, int limit)
{
  CfdRunSummary s;
  s.iterations = run.iterations;
  s.iterationLimit = limit;
  s.residuals = run.residuals;
  s.converged = run.converged;
  s.status = CfdRunStatus(run);
  return s;
}

} // namespace

CfdFlowResults MapCfdResults(const std::string& caseDirectory)
{
  const fs::path dir(caseDirectory);
  const CaseRecord record = ReadCaseRecord(dir);
  const fs::path surfacePath = dir / record.labelledSurface;
  std::error_code ec;
  if (!fs::exists(surfacePath, ec))
  {
    throw InputError(surfacePath.string() + ": missing (the case's labelled surface, in mm)");
  }
  vtkSmartPointer<vtkPolyData> surface = ReadMesh(surfacePath.string());
  const std::vector<PatchLabel> labels = ReadPatchLabels(surface);
  const std::vector<int> cellIds = CellPatchIds(surface);
  const CfdRunResult run = ReadCfdResults(caseDirectory);

  // The last time written, every patch, cell-to-point data (VTK's reader, no hand parsing).
  vtkNew<vtkOpenFOAMReader> reader;
  reader->SetFileName(CfdFoamFile(dir).c_str());
  reader->SetCreateCellToPoint(1);
  reader->SetDecomposePolyhedra(1);
  reader->SetReadZones(0);
  reader->SetSkipZeroTime(true);
  reader->UpdateInformation();
  vtkDoubleArray* times = reader->GetTimeValues();
  if (!times || times->GetNumberOfTuples() == 0)
  {
    throw Error(caseDirectory + ": no time was written (has simpleFoam run?)");
  }
  const double time = times->GetValue(times->GetNumberOfTuples() - 1);
  reader->EnableAllPatchArrays();
  reader->DisableAllCellArrays();
  for (const char* field : { "p", "U", "wallShearStress" })
  {
    reader->SetCellArrayStatus(field, 1);
  }
  vtkSmartPointer<vtkUnstructuredGrid> internal;
  std::map<std::string, vtkPolyData*> meshPatches;
  std::string readerMessage;
  {
    io_detail::VtkMessageGuard guard;
    guard.Watch(reader);
    reader->UpdateTimeStep(time);
    if (vtkMultiBlockDataSet* output = reader->GetOutput())
    {
      CollectBlocks(output, internal, meshPatches);
    }
    readerMessage = guard.Message();
  }
  if (!internal || !internal->GetCellData()->GetArray("p") ||
    !internal->GetCellData()->GetArray("U"))
  {
    vtkStringArray* names = reader->GetTimeNames();
    const std::string timeName = names && names->GetNumberOfValues() > 0
      ? names->GetValue(names->GetNumberOfValues() - 1)
      : CfdShort(time, 10);
    if (const std::string field = NonFiniteField(dir / timeName); !field.empty())
    {
      throw Error(DivergedMessage(caseDirectory, field, "", time));
    }
    throw Error(caseDirectory + ": time " + CfdShort(time, 6) +
      " has no p and U that vtkOpenFOAMReader can read" +
      (readerMessage.empty() ? std::string() : " (" + readerMessage + ")"));
  }
  CheckFinite(internal->GetCellData(), "the mesh", caseDirectory, time);

  // Every patch of the surface is a patch of the mesh.
  std::map<int, MeshPatch> byLabel;
  double outletArea = 0.0, outletPressure = 0.0;
  for (const auto& label : labels)
  {
    const auto it = meshPatches.find(label.name);
    if (it == meshPatches.end() || it->second->GetNumberOfCells() == 0)
    {
      std::string names;
      for (const auto& [name, patch] : meshPatches)
      {
        names += (names.empty() ? "" : ", ") + name;
      }
      throw InputError(caseDirectory + ": the results do not match the surface: its patch " +
        label.name + " is not a patch of the mesh (the mesh has " + names + ")");
    }
    CheckFinite(it->second->GetCellData(), "patch " + label.name, caseDirectory, time);
    byLabel[label.id] = MakeMeshPatch(it->second);
    // The roles are the case's (bender-case.json): --inlet may have chosen another inlet.
    const bool outlet = std::any_of(run.patches.begin(),
      run.patches.end(),
      [&](const CfdPatchFlow& f) { return f.name == label.name && f.type == PatchType::Outlet; });
    if (outlet)
    {
      outletArea += byLabel[label.id].area;
      outletPressure += byLabel[label.id].area * byLabel[label.id].meanPressure;
    }
  }
  const double reference = outletArea > 0.0 ? outletPressure / outletArea : 0.0;
  const double rho = record.settings.densityKgPerM3;

  // Each surface point takes the values of the closest point of its patch: the wall where
  // it touches the wall (the rims of the caps), else its end.
  std::vector<int> pointPatch(static_cast<std::size_t>(surface->GetNumberOfPoints()), 0);
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    vtkCell* cell = surface->GetCell(c);
    for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k)
    {
      int& p = pointPatch[static_cast<std::size_t>(cell->GetPointId(k))];
      if (p != kWallEntityId)
      {
        p = cellIds[static_cast<std::size_t>(c)];
      }
    }
  }
  vtkNew<vtkDoubleArray> pressure, wss, magnitude;
  pressure->SetName(kPressureArrayName);
  wss->SetName(kWallShearStressArrayName);
  wss->SetNumberOfComponents(3);
  magnitude->SetName(kWallShearStressMagnitudeArrayName);
  const vtkIdType n = surface->GetNumberOfPoints();
  pressure->SetNumberOfTuples(n);
  wss->SetNumberOfTuples(n);
  magnitude->SetNumberOfTuples(n);
  vtkNew<vtkGenericCell> scratch;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3], p = 0.0, tau[3] = { 0.0, 0.0, 0.0 };
    surface->GetPoint(i, x);
    const auto it = byLabel.find(pointPatch[static_cast<std::size_t>(i)]);
    if (it != byLabel.end())
    {
      Sample(it->second, x, scratch, p, tau);
    }
    for (double& t : tau)
    {
      t *= rho;
    }
    pressure->SetValue(i, rho * (p - reference));
    wss->SetTuple(i, tau);
    magnitude->SetValue(i, std::sqrt(tau[0] * tau[0] + tau[1] * tau[1] + tau[2] * tau[2]));
  }
  surface->GetPointData()->AddArray(pressure);
  surface->GetPointData()->AddArray(wss);
  surface->GetPointData()->AddArray(magnitude);

  // The volume in mm with U (m/s) and Pressure (Pa), for streamlines.
  vtkNew<vtkUnstructuredGrid> volume;
  volume->ShallowCopy(internal);
  volume->SetPoints(PointsInMm(internal));
  for (vtkFieldData* data : { static_cast<vtkFieldData*>(volume->GetPointData()),
         static_cast<vtkFieldData*>(volume->GetCellData()) })
  {
    vtkSmartPointer<vtkDataArray> kinematic = data->GetArray("p");
    vtkSmartPointer<vtkDataArray> velocity = data->GetArray("U");
    data->Initialize();
    if (velocity)
    {
      data->AddArray(velocity);
    }
    if (kinematic)
    {
      vtkNew<vtkDoubleArray> pa;
      pa->SetName(kPressureArrayName);
      pa->SetNumberOfTuples(kinematic->GetNumberOfTuples());
      for (vtkIdType i = 0; i < kinematic->GetNumberOfTuples(); ++i)
      {
        pa->SetValue(i, rho * (kinematic->GetTuple1(i) - reference));
      }
      data->AddArray(pa);
    }
  }

  CfdFlowResults results;
  results.caseDirectory = caseDirectory;
  results.time = time;
  results.run = Summarise(run, record.iterationLimit);
  results.settings = record.settings;
  results.meshCells = CheckMeshCells(dir);
  if (results.meshCells == 0)
  {
    results.meshCells = internal->GetNumberOfCells();
  }
  results.inletFlowRateMlPerMin = run.inletFlowRate * 6e7;
  results.massImbalancePercent = 100.0 * run.massImbalance;
  double inletPressure = 0.0;
  for (const auto& f : run.patches)
  {
    if (f.type == PatchType::Inlet)
    {
      inletPressure = f.pressure - rho * reference;
    }
  }
  for (const PatchType role : { PatchType::Inlet, PatchType::Outlet })
  {
    for (const auto& f : run.patches)
    {
      if (f.type != role)
      {
        continue;
      }
      CfdEndFlow e;
      e.name = f.name;
      e.role = role;
      e.flowRateMlPerMin = (role == PatchType::Inlet ? -f.flowRate : f.flowRate) * 6e7;
      e.splitPercent = role == PatchType::Inlet ? 100.0 : f.percentOfInlet;
      e.meanPressurePa = f.pressure - rho * reference;
      e.pressureDropPa = inletPressure - e.meanPressurePa;
      results.ends.push_back(e);
    }
  }
  results.wallShearStress = ComputeWallShearStats(surface);
  WriteResultsFolder(dir, surface, volume, results);
  return results;
}

} // namespace bender
