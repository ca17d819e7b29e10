#include "SurfaceExtraction.h"

#include "ItkVtkBridge.h"
#include "Private/ItkImage.h"

#include <itkBinaryMask3DMeshSource.h>
#include <itkMesh.h>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkQuadricDecimation.h>
#include <vtkStaticPointLocator.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>

namespace bender
{
namespace
{

using Clock = std::chrono::steady_clock;

/// Forwards a VTK filter's progress and turns the cancel flag into AbortExecute.
class VtkWatch
{
public:
  VtkWatch(vtkAlgorithm* filter, const ProgressReporter& reporter, std::string stage)
    : Reporter(reporter)
    , Stage(std::move(stage))
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback([](vtkObject* caller, unsigned long, void* self, void*) {
      auto* watch = static_cast<VtkWatch*>(self);
      auto* algorithm = static_cast<vtkAlgorithm*>(caller);
      watch->Reporter.Report(watch->Stage, algorithm->GetProgress());
      if (watch->Reporter.Cancelled())
      {
        algorithm->SetAbortExecute(1);
      }
    });
    filter->AddObserver(vtkCommand::ProgressEvent, this->Command);
  }

private:
  const ProgressReporter& Reporter;
  std::string Stage;
  vtkNew<vtkCallbackCommand> Command;
};

class StageClock
{
public:
  StageClock(std::vector<StageTime>& timings, const ProgressReporter& progress)
    : Timings(timings)
    , Progress(progress)
  {
  }
  void Done(const std::string& stage)
  {
    const Clock::time_point now = Clock::now();
    this->Timings.push_back({ stage, std::chrono::duration<double>(now - this->Start).count() });
    this->Start = now;
    this->Progress.Report(stage, 1.0);
    this->Progress.ThrowIfCancelled(stage);
  }

private:
  std::vector<StageTime>& Timings;
  const ProgressReporter& Progress;
  Clock::time_point Start = Clock::now();
};

/// The mask cropped to its voxels plus a one-voxel zero border on every side, so that the
/// surface closes even where the lumen touches the volume's faces. Geometry is local:
/// origin 0, identity direction, the mask's spacing. `offset`: index of local voxel 0 in the mask.
LabelMap CropWithBorder(const LabelMap& mask, std::array<long, 3>& offset)
{
  const auto& size = mask.geometry.size;
  long lo[3] = { long(size[0]), long(size[1]), long(size[2]) };
  long hi[3] = { -1, -1, -1 };
  for (std::size_t k = 0; k < size[2]; ++k)
  {
    for (std::size_t j = 0; j < size[1]; ++j)
    {
      const std::uint8_t* row = mask.voxels.data() + mask.geometry.LinearIndex(0, j, k);
      const std::uint8_t* first = std::find_if(row, row + size[0], [](std::uint8_t v) { return v != 0; });
      if (first == row + size[0])
      {
        continue;
      }
      long last = long(size[0]) - 1;
      while (row[last] == 0)
      {
        --last;
      }
      lo[0] = std::min(lo[0], long(first - row));
      hi[0] = std::max(hi[0], last);
      lo[1] = std::min(lo[1], long(j));
      hi[1] = std::max(hi[1], long(j));
      lo[2] = std::min(lo[2], long(k));
      hi[2] = std::max(hi[2], long(k));
    }
  }
  if (hi[0] < 0)
  {
    throw ParameterError("surface extraction: the mask is empty");
  }
  LabelMap local;
  local.geometry.spacing = mask.geometry.spacing;
  for (int c = 0; c < 3; ++c)
  {
    offset[c] = lo[c] - 1;
    local.geometry.size[c] = static_cast<std::size_t>(hi[c] - lo[c] + 3);
  }
  local.voxels.assign(local.geometry.VoxelCount(), 0);
  for (long k = lo[2]; k <= hi[2]; ++k)
  {
    for (long j = lo[1]; j <= hi[1]; ++j)
    {
      const std::uint8_t* src = mask.voxels.data() + mask.geometry.LinearIndex(std::size_t(lo[0]), std::size_t(j), std::size_t(k));
      std::uint8_t* dst = local.voxels.data() +
        local.geometry.LinearIndex(1, std::size_t(j - offset[1]), std::size_t(k - offset[2]));
      std::transform(src, src + (hi[0] - lo[0] + 1), dst, [](std::uint8_t v) { return v ? 1 : 0; });
    }
  }
  return local;
}

vtkSmartPointer<vtkPolyData> FlyingEdges(const LabelMap& local, const ProgressReporter& progress)
{
  vtkSmartPointer<vtkImageData> image = LabelMapToVtkImage(local);
  vtkNew<vtkFlyingEdges3D> flyingEdges;
  VtkWatch watch(flyingEdges, progress, "marching cubes");
  flyingEdges->SetInputData(image);
  flyingEdges->SetValue(0, 0.5);
  flyingEdges->ComputeNormalsOff();
  flyingEdges->ComputeGradientsOff();
  flyingEdges->ComputeScalarsOff();
  flyingEdges->InterpolateAttributesOff();
  flyingEdges->Update();
  vtkSmartPointer<vtkPolyData> surface = flyingEdges->GetOutput();
  return surface;
}

vtkSmartPointer<vtkPolyData> ItkMarchingCubes(const LabelMap& local, const ProgressReporter& progress)
{
  using MeshType = itk::Mesh<double, 3>;
  using SourceType = itk::BinaryMask3DMeshSource<detail::MaskImage, MeshType>;
  auto image = detail::WrapLabelMap(local);
  auto source = SourceType::New();
  source->SetInput(image);
  source->SetObjectValue(1);
  detail::WatchFilter(source, progress, "marching cubes");
  try
  {
    source->Update();
  }
  catch (const itk::ProcessAborted&)
  {
    throw SegmentationCancelled("cancelled during marching cubes");
  }
  catch (const itk::ExceptionObject& e)
  {
    std::string text = e.GetDescription();
    std::replace(text.begin(), text.end(), '\n', ' ');
    throw SegmentationError("ITK marching cubes failed: " + text);
  }
  const MeshType* mesh = source->GetOutput();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh->GetNumberOfPoints()));
  for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it)
  {
    const auto& p = it->Value();
    points->SetPoint(static_cast<vtkIdType>(it->Index()), p[0], p[1], p[2]);
  }
  vtkNew<vtkCellArray> triangles;
  triangles->AllocateExact(static_cast<vtkIdType>(mesh->GetNumberOfCells()), 3 * static_cast<vtkIdType>(mesh->GetNumberOfCells()));
  for (auto it = mesh->GetCells()->Begin(); it != mesh->GetCells()->End(); ++it)
  {
    const auto* cell = it->Value();
    if (cell->GetNumberOfPoints() != 3)
    {
      continue;
    }
    vtkIdType ids[3];
    int n = 0;
    for (auto id = cell->PointIdsBegin(); id != cell->PointIdsEnd(); ++id)
    {
      ids[n++] = static_cast<vtkIdType>(*id);
    }
    triangles->InsertNextCell(3, ids);
  }
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetPolys(triangles);
  return surface;
}

/// Flips the order of every triangle in place.
void ReverseTriangles(vtkPolyData* surface)
{
  vtkNew<vtkCellArray> reversed;
  vtkCellArray* polys = surface->GetPolys();
  reversed->AllocateExact(polys->GetNumberOfCells(), polys->GetNumberOfConnectivityIds());
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  std::vector<vtkIdType> flipped;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    flipped.assign(std::reverse_iterator<const vtkIdType*>(ids + npts), std::reverse_iterator<const vtkIdType*>(ids));
    reversed->InsertNextCell(npts, flipped.data());
  }
  surface->SetPolys(reversed);
}

vtkIdType FindRoot(std::vector<vtkIdType>& parent, vtkIdType i)
{
  while (parent[std::size_t(i)] != i)
  {
    parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    i = parent[std::size_t(i)];
  }
  return i;
}

/// The connected pieces (triangles sharing vertices) nearest to the seeds, or the piece with the
/// most triangles; unused points are dropped. Union-find: linear time, unlike
/// vtkPolyDataConnectivityFilter's cell-link traversal.
vtkSmartPointer<vtkPolyData> KeepComponents(vtkPolyData* surface, const std::vector<Point3>& seeds)
{
  const vtkIdType nPoints = surface->GetNumberOfPoints();
  std::vector<vtkIdType> parent(static_cast<std::size_t>(nPoints));
  for (vtkIdType i = 0; i < nPoints; ++i)
  {
    parent[std::size_t(i)] = i;
  }
  vtkCellArray* polys = surface->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    for (vtkIdType v = 1; v < npts; ++v)
    {
      const vtkIdType a = FindRoot(parent, ids[0]);
      const vtkIdType b = FindRoot(parent, ids[v]);
      if (a != b)
      {
        parent[std::size_t(std::max(a, b))] = std::min(a, b);
      }
    }
  }
  std::vector<std::size_t> triangles(std::size_t(nPoints), 0);
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    ++triangles[std::size_t(FindRoot(parent, ids[0]))];
  }
  std::vector<char> keep(std::size_t(nPoints), 0);
  if (seeds.empty())
  {
    keep[std::size_t(std::max_element(triangles.begin(), triangles.end()) - triangles.begin())] = 1;
  }
  else
  {
    vtkNew<vtkStaticPointLocator> locator;
    locator->SetDataSet(surface);
    locator->BuildLocator();
    for (const Point3& seed : seeds)
    {
      const vtkIdType nearest = locator->FindClosestPoint(seed.data());
      if (nearest >= 0)
      {
        keep[std::size_t(FindRoot(parent, nearest))] = 1;
      }
    }
  }
  std::vector<vtkIdType> newId(std::size_t(nPoints), -1);
  vtkNew<vtkPoints> points;
  points->SetDataType(surface->GetPoints()->GetDataType());
  vtkNew<vtkCellArray> kept;
  std::vector<vtkIdType> cell;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (!keep[std::size_t(FindRoot(parent, ids[0]))])
    {
      continue;
    }
    cell.resize(std::size_t(npts));
    for (vtkIdType v = 0; v < npts; ++v)
    {
      vtkIdType& id = newId[std::size_t(ids[v])];
      if (id < 0)
      {
        id = points->InsertNextPoint(surface->GetPoint(ids[v]));
      }
      cell[std::size_t(v)] = id;
    }
    kept->InsertNextCell(npts, cell.data());
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->SetPoints(points);
  output->SetPolys(kept);
  return output;
}

/// Maps local coordinates (spacing .* local index) to LPS mm in place.
void ToPhysical(vtkPolyData* surface, const ImageGeometry& g, const std::array<long, 3>& offset)
{
  const Point3 shift = g.IndexToPhysical({ { double(offset[0]), double(offset[1]), double(offset[2]) } });
  vtkPoints* points = surface->GetPoints();
  const vtkIdType n = points->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double l[3];
    points->GetPoint(i, l);
    double p[3];
    for (int r = 0; r < 3; ++r)
    {
      p[r] = shift[r] + g.direction[3 * r] * l[0] + g.direction[3 * r + 1] * l[1] + g.direction[3 * r + 2] * l[2];
    }
    points->SetPoint(i, p);
  }
  points->Modified();
}

/// Six times the signed volume enclosed by the triangles (> 0: counter-clockwise seen from outside).
double SignedVolume6(vtkPolyData* surface)
{
  vtkPoints* points = surface->GetPoints();
  double sum = 0.0;
  vtkCellArray* polys = surface->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      continue;
    }
    double a[3], b[3], c[3];
    points->GetPoint(ids[0], a);
    points->GetPoint(ids[1], b);
    points->GetPoint(ids[2], c);
    sum += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
      a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return sum;
}

void CountEdges(vtkPolyData* surface, std::size_t& boundary, std::size_t& nonManifold)
{
  std::vector<std::uint64_t> edges;
  edges.reserve(static_cast<std::size_t>(3 * surface->GetNumberOfPolys()));
  vtkCellArray* polys = surface->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    for (vtkIdType e = 0; e < npts; ++e)
    {
      std::uint64_t a = static_cast<std::uint64_t>(ids[e]);
      std::uint64_t b = static_cast<std::uint64_t>(ids[(e + 1) % npts]);
      if (a > b)
      {
        std::swap(a, b);
      }
      edges.push_back((a << 32) | b);
    }
  }
  std::sort(edges.begin(), edges.end());
  boundary = 0;
  nonManifold = 0;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
    {
      ++j;
    }
    boundary += (j - i == 1) ? 1 : 0;
    nonManifold += (j - i > 2) ? 1 : 0;
    i = j;
  }
}

SurfaceResult Extract(const LabelMap& mask, const SurfaceParameters& p, const ProgressReporter& progress)
{
  SurfaceResult result;
  StageClock clock(result.timings, progress);
  std::array<long, 3> offset{ { 0, 0, 0 } };
  const LabelMap local = CropWithBorder(mask, offset);
  clock.Done("crop");

  vtkSmartPointer<vtkPolyData> surface = p.extractor == SurfaceExtractor::Vtk
    ? FlyingEdges(local, progress)
    : ItkMarchingCubes(local, progress);
  clock.Done("marching cubes");
  if (surface->GetNumberOfPolys() == 0)
  {
    throw SegmentationError("surface extraction produced no triangles");
  }

  // Keep the piece(s) nearest the seeds (or the largest); stray specks go.
  std::vector<Point3> localSeeds;
  for (const Point3& seed : p.seeds)
  {
    ImageGeometry localToMask = mask.geometry;
    localToMask.origin = mask.geometry.IndexToPhysical({ { double(offset[0]), double(offset[1]), double(offset[2]) } });
    const Point3 index = localToMask.PhysicalToIndex(seed);
    localSeeds.push_back({ { index[0] * mask.geometry.spacing[0], index[1] * mask.geometry.spacing[1],
      index[2] * mask.geometry.spacing[2] } });
  }
  surface = KeepComponents(surface, localSeeds);
  clock.Done("keep component");

  if (p.smoothing > 0.0)
  {
    vtkNew<vtkWindowedSincPolyDataFilter> smoother;
    VtkWatch watch(smoother, progress, "smoothing");
    smoother->SetInputData(surface);
    smoother->SetNumberOfIterations(20);
    smoother->SetPassBand(std::pow(10.0, -4.0 * p.smoothing));
    smoother->BoundarySmoothingOff();
    smoother->FeatureEdgeSmoothingOff();
    smoother->NonManifoldSmoothingOn();
    smoother->NormalizeCoordinatesOn();
    smoother->Update();
    surface = smoother->GetOutput();
    clock.Done("smoothing");
  }

  const auto triangles = static_cast<std::size_t>(surface->GetNumberOfPolys());
  if (p.targetTriangles > 0 && p.targetTriangles < triangles)
  {
    vtkNew<vtkQuadricDecimation> decimate;
    VtkWatch watch(decimate, progress, "decimation");
    decimate->SetInputData(surface);
    decimate->SetTargetReduction(1.0 - double(p.targetTriangles) / double(triangles));
    decimate->VolumePreservationOn();
    decimate->Update();
    surface = decimate->GetOutput();
    clock.Done("decimation");
  }

  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(surface);
  vtkNew<vtkPoints> points;
  points->DeepCopy(surface->GetPoints());
  output->SetPoints(points);
  output->GetPointData()->Initialize();
  ToPhysical(output, mask.geometry, offset);
  clock.Done("to LPS");

  // Marching cubes orders every triangle the same way: one global sign remains, chosen so that
  // the enclosed volume is positive (normals point out of the lumen).
  if (SignedVolume6(output) < 0.0)
  {
    ReverseTriangles(output);
  }
  vtkNew<vtkPolyDataNormals> normals;
  VtkWatch normalsWatch(normals, progress, "normals");
  normals->SetInputData(output);
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->ComputeCellNormalsOff();
  normals->ComputePointNormalsOn();
  normals->Update();
  output = normals->GetOutput();
  clock.Done("normals");
  CountEdges(output, result.boundaryEdges, result.nonManifoldEdges);
  result.surface = output;
  return result;
}

} // namespace

SurfaceResult ExtractSurface(const LabelMap& mask, const SurfaceParameters& parameters, const ProgressReporter& progress)
{
  if (!(parameters.smoothing >= 0.0 && parameters.smoothing <= 1.0))
  {
    throw ParameterError("surface parameter smoothing: must be in [0, 1]");
  }
  if (mask.geometry.VoxelCount() == 0 || mask.voxels.size() != mask.geometry.VoxelCount())
  {
    throw ParameterError("surface extraction: empty or inconsistent mask");
  }
  return Extract(mask, parameters, progress);
}

} // namespace bender
