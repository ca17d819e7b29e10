#include "SurfaceExtraction.h"

#include "MeshTopology.h"
#include "Private/ItkImage.h"

#include <itkBinaryMask3DMeshSource.h>
#include <itkMesh.h>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkDataArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>
#include <vtkPolyDataNormals.h>
#include <vtkQuadricDecimation.h>
#include <vtkSMPTools.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
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
    this->Command->SetCallback(
      [](vtkObject* caller, unsigned long, void* self, void*)
      {
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
  const std::size_t nx = size[0];
  // Bounding box per slice (slices in parallel), then reduced: {lo x, hi x, lo y, hi y}.
  std::vector<std::array<long, 4>> slices(
    size[2], std::array<long, 4>{ { long(nx), -1, long(size[1]), -1 } });
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(size[2]),
    [&](vtkIdType kBegin, vtkIdType kEnd)
    {
      for (std::size_t k = std::size_t(kBegin); k < std::size_t(kEnd); ++k)
      {
        std::array<long, 4>& box = slices[k];
        for (std::size_t j = 0; j < size[1]; ++j)
        {
          const std::uint8_t* row = mask.voxels.data() + mask.geometry.LinearIndex(0, j, k);
          // Most rows are empty: a branch-free (vectorised) OR over the row rejects them quickly.
          std::uint8_t any = 0;
          for (std::size_t i = 0; i < nx; ++i)
          {
            any |= row[i];
          }
          if (any == 0)
          {
            continue;
          }
          const std::uint8_t* first =
            std::find_if(row, row + nx, [](std::uint8_t v) { return v != 0; });
          long last = long(nx) - 1;
          while (row[last] == 0)
          {
            --last;
          }
          box[0] = std::min(box[0], long(first - row));
          box[1] = std::max(box[1], last);
          box[2] = std::min(box[2], long(j));
          box[3] = std::max(box[3], long(j));
        }
      }
    });
  long lo[3] = { long(size[0]), long(size[1]), long(size[2]) };
  long hi[3] = { -1, -1, -1 };
  for (std::size_t k = 0; k < size[2]; ++k)
  {
    if (slices[k][1] < 0)
    {
      continue;
    }
    lo[0] = std::min(lo[0], slices[k][0]);
    hi[0] = std::max(hi[0], slices[k][1]);
    lo[1] = std::min(lo[1], slices[k][2]);
    hi[1] = std::max(hi[1], slices[k][3]);
    lo[2] = std::min(lo[2], long(k));
    hi[2] = std::max(hi[2], long(k));
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
  vtkSMPTools::For(lo[2],
    hi[2] + 1,
    [&](vtkIdType kBegin, vtkIdType kEnd)
    {
      for (long k = long(kBegin); k < long(kEnd); ++k)
      {
        for (long j = lo[1]; j <= hi[1]; ++j)
        {
          const std::uint8_t* src = mask.voxels.data() +
            mask.geometry.LinearIndex(std::size_t(lo[0]), std::size_t(j), std::size_t(k));
          std::uint8_t* dst = local.voxels.data() +
            local.geometry.LinearIndex(1, std::size_t(j - offset[1]), std::size_t(k - offset[2]));
          std::transform(
            src, src + (hi[0] - lo[0] + 1), dst, [](std::uint8_t v) { return v ? 1 : 0; });
        }
      }
    });
  return local;
}

vtkSmartPointer<vtkPolyData> FlyingEdges(const LabelMap& local, const ProgressReporter& progress)
{
  // Wrap the local map's buffer (no copy); it outlives the filter, whose output does not refer
  // to it. The local geometry is origin 0, identity direction.
  vtkNew<vtkUnsignedCharArray> scalars;
  scalars->SetArray(
    const_cast<std::uint8_t*>(local.voxels.data()), static_cast<vtkIdType>(local.voxels.size()), 1);
  vtkNew<vtkImageData> image;
  image->SetDimensions(
    int(local.geometry.size[0]), int(local.geometry.size[1]), int(local.geometry.size[2]));
  image->SetSpacing(local.geometry.spacing.data());
  image->SetOrigin(0.0, 0.0, 0.0);
  image->GetPointData()->SetScalars(scalars);
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

vtkSmartPointer<vtkPolyData> ItkMarchingCubes(const LabelMap& local,
  const ProgressReporter& progress)
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
  triangles->AllocateExact(static_cast<vtkIdType>(mesh->GetNumberOfCells()),
    3 * static_cast<vtkIdType>(mesh->GetNumberOfCells()));
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
    flipped.assign(std::reverse_iterator<const vtkIdType*>(ids + npts),
      std::reverse_iterator<const vtkIdType*>(ids));
    reversed->InsertNextCell(npts, flipped.data());
  }
  surface->SetPolys(reversed);
}

/// The connected pieces (triangles sharing points) nearest to the seeds, or the piece with the
/// most triangles; unused points are dropped (vtkPolyDataConnectivityFilter).
vtkSmartPointer<vtkPolyData> KeepComponents(vtkPolyData* surface,
  const std::vector<Point3>& seeds,
  const ProgressReporter& progress)
{
  vtkNew<vtkPolyDataConnectivityFilter> connectivity;
  VtkWatch watch(connectivity, progress, "keep component");
  connectivity->SetInputData(surface);
  if (seeds.empty())
  {
    connectivity->SetExtractionModeToLargestRegion();
  }
  else
  {
    // Label every piece, then keep those of the points nearest to the seeds (a few seeds: a
    // linear scan beats building a locator).
    connectivity->SetExtractionModeToAllRegions();
    connectivity->ColorRegionsOn();
    connectivity->Update();
    vtkPolyData* labelled = connectivity->GetOutput();
    vtkDataArray* region = labelled->GetPointData()->GetArray("RegionId");
    std::vector<vtkIdType> regions;
    for (const Point3& seed : seeds)
    {
      vtkIdType nearest = -1;
      double best = std::numeric_limits<double>::max();
      for (vtkIdType i = 0; i < labelled->GetNumberOfPoints(); ++i)
      {
        double x[3];
        labelled->GetPoint(i, x);
        const double d = vtkMath::Distance2BetweenPoints(x, seed.data());
        if (d < best)
        {
          best = d;
          nearest = i;
        }
      }
      if (nearest >= 0 && region)
      {
        regions.push_back(static_cast<vtkIdType>(region->GetTuple1(nearest)));
      }
    }
    connectivity->ColorRegionsOff();
    connectivity->SetExtractionModeToSpecifiedRegions();
    connectivity->InitializeSpecifiedRegionList();
    for (const vtkIdType r : regions)
    {
      connectivity->AddSpecifiedRegion(r);
    }
  }
  // The filter keeps every input point: drop those of the other pieces (no merging).
  vtkNew<vtkCleanPolyData> unused;
  unused->SetInputConnection(connectivity->GetOutputPort());
  unused->PointMergingOff();
  unused->ConvertPolysToLinesOff();
  unused->ConvertLinesToPointsOff();
  unused->ConvertStripsToPolysOff();
  unused->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->SetPoints(unused->GetOutput()->GetPoints());
  output->SetPolys(unused->GetOutput()->GetPolys());
  return output;
}

/// Chebyshev coefficients of the windowed-sinc low-pass filter of Taubin, Zhang and Golub
/// ("Optimal surface smoothing as filter design", 1996) with a Hamming window, the pass band
/// widened by the offset sigma (Newton search) so that the filter is 1 at the requested band,
/// as vtkWindowedSincPolyDataFilter computes them.
std::vector<double> WindowedSincCoefficients(int iterations, double passBand)
{
  const int n = iterations;
  const double pi = 3.14159265358979323846;
  const double theta = std::acos(1.0 - 0.5 * passBand);
  std::vector<double> w(std::size_t(n) + 1), c(std::size_t(n) + 1), dc(std::size_t(n) + 1);
  for (int i = 0; i <= n; ++i)
  {
    w[std::size_t(i)] = 0.54 + 0.46 * std::cos(double(i) * pi / double(n + 1));
  }
  double sigma = 0.0;
  for (int step = 0; step < 500; ++step)
  {
    c[0] = w[0] * (theta + sigma) / pi;
    for (int i = 1; i <= n; ++i)
    {
      c[std::size_t(i)] =
        2.0 * w[std::size_t(i)] * std::sin(double(i) * (theta + sigma)) / (double(i) * pi);
    }
    // Coefficients of the derivative series.
    dc[std::size_t(n)] = 0.0;
    dc[std::size_t(n - 1)] = 0.0;
    if (n > 1)
    {
      dc[std::size_t(n - 2)] = 2.0 * (n - 1) * c[std::size_t(n - 1)];
    }
    for (int i = n - 3; i >= 0; --i)
    {
      dc[std::size_t(i)] = dc[std::size_t(i + 2)] + 2.0 * (i + 1) * c[std::size_t(i + 1)];
    }
    double f = c[0];
    double df = dc[0];
    for (int i = 1; i <= n; ++i)
    {
      const double t = i == 1 ? 1.0 - 0.5 * passBand : std::cos(double(i) * theta);
      f += c[std::size_t(i)] * t;
      df += dc[std::size_t(i)] * t;
    }
    if (n <= 1 || std::fabs(f - 1.0) < 1e-3)
    {
      break;
    }
    sigma -= (f - 1.0) / df;
  }
  return c;
}

/// Windowed-sinc smoothing of a closed 2-manifold triangle surface (every edge shared by exactly
/// two triangles): the same filter as vtkWindowedSincPolyDataFilter with normalised coordinates
/// and no feature edges, where every vertex is "simple" and moves; the vertex loop of each
/// iteration runs in parallel (vtkSMPTools) on a compact neighbour table. Returns null when the
/// surface is not such a surface (the caller then uses VTK's filter).
/// Kept instead of VTK's filter because it gives the same points (within 1e-4 mm:
/// SurfaceExtraction.SmoothingMatchesVtkWindowedSinc) 1.7-2.7x as fast on the vessel surfaces
/// (bench_segmentation --smoothing-only, both in the same run; docs/performance.md).
vtkSmartPointer<vtkPolyData> SmoothClosedSurface(vtkPolyData* surface,
  int iterations,
  double passBand,
  const ProgressReporter& progress)
{
  const std::size_t nPoints = static_cast<std::size_t>(surface->GetNumberOfPoints());
  vtkCellArray* polys = surface->GetPolys();
  if (nPoints == 0 || nPoints > std::numeric_limits<std::uint32_t>::max() || iterations < 2 ||
    surface->GetNumberOfVerts() > 0 || surface->GetNumberOfLines() > 0 ||
    surface->GetNumberOfStrips() > 0)
  {
    return nullptr;
  }
  // Neighbour table (CSR): every triangle adds its two other corners to each corner; on a closed
  // 2-manifold each neighbour then appears exactly twice.
  std::vector<std::size_t> start(nPoints + 1, 0);
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      return nullptr;
    }
    for (int v = 0; v < 3; ++v)
    {
      start[std::size_t(ids[v]) + 1] += 2;
    }
  }
  for (std::size_t i = 0; i < nPoints; ++i)
  {
    start[i + 1] += start[i];
  }
  std::vector<vtkIdType> raw(start[nPoints]);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
    {
      for (int v = 0; v < 3; ++v)
      {
        std::size_t& f = fill[std::size_t(ids[v])];
        raw[f++] = ids[(v + 1) % 3];
        raw[f++] = ids[(v + 2) % 3];
      }
    }
  }
  std::vector<std::size_t> first(nPoints + 1, 0);
  std::vector<std::uint32_t> neighbours;
  neighbours.reserve(raw.size() / 2);
  for (std::size_t i = 0; i < nPoints; ++i)
  {
    auto a = raw.begin() + static_cast<std::ptrdiff_t>(start[i]);
    auto b = raw.begin() + static_cast<std::ptrdiff_t>(start[i + 1]);
    if (a == b)
    {
      return nullptr; // unused point
    }
    std::sort(a, b);
    for (auto it = a; it != b; it += 2)
    {
      if (it + 1 == b || *(it + 1) != *it || (it + 2 != b && *(it + 2) == *it))
      {
        return nullptr; // boundary or non-manifold edge
      }
      neighbours.push_back(static_cast<std::uint32_t>(*it));
    }
    first[i + 1] = neighbours.size();
  }
  // Coordinates centred on the bounding box and scaled by its diagonal (NormalizeCoordinatesOn).
  double bounds[6];
  surface->GetBounds(bounds);
  const double centre[3] = {
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  const double length = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  if (!(length > 0.0))
  {
    return nullptr;
  }
  const std::vector<double> c = WindowedSincCoefficients(iterations, passBand);
  // x[0], x[1], x[2]: the last three terms of the Chebyshev recursion; result: the filtered sum.
  std::vector<double> x[3];
  for (auto& v : x)
  {
    v.resize(3 * nPoints);
  }
  std::vector<double> result(3 * nPoints);
  vtkPoints* points = surface->GetPoints();
  for (std::size_t i = 0; i < nPoints; ++i)
  {
    double q[3];
    points->GetPoint(vtkIdType(i), q);
    for (int r = 0; r < 3; ++r)
    {
      x[0][3 * i + std::size_t(r)] = (q[r] - centre[r]) / length;
    }
  }
  // Minus the umbrella Laplacian of `in` at point i.
  const auto laplacian = [&](const std::vector<double>& in, std::size_t i, double d[3])
  {
    double sum[3] = { 0.0, 0.0, 0.0 };
    const double* xi = in.data() + 3 * i;
    for (std::size_t e = first[i]; e < first[i + 1]; ++e)
    {
      const double* xj = in.data() + 3 * std::size_t(neighbours[e]);
      sum[0] += xj[0];
      sum[1] += xj[1];
      sum[2] += xj[2];
    }
    const double weight = 1.0 / double(first[i + 1] - first[i]);
    for (int r = 0; r < 3; ++r)
    {
      d[r] = xi[r] - weight * sum[r];
    }
  };
  vtkSMPTools::For(0,
    vtkIdType(nPoints),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (std::size_t i = std::size_t(begin); i < std::size_t(end); ++i)
      {
        double d[3];
        laplacian(x[0], i, d);
        for (int r = 0; r < 3; ++r)
        {
          const std::size_t k = 3 * i + std::size_t(r);
          x[1][k] = x[0][k] - 0.5 * d[r];
          result[k] = c[0] * x[0][k] + c[1] * x[1][k];
        }
      }
    });
  int zero = 0, one = 1, two = 2;
  for (int iteration = 2; iteration <= iterations; ++iteration)
  {
    if (iteration % 5 == 0)
    {
      progress.Report("smoothing", double(iteration) / double(iterations));
      progress.ThrowIfCancelled("smoothing");
    }
    const std::vector<double>& x0 = x[zero];
    const std::vector<double>& x1 = x[one];
    std::vector<double>& x2 = x[two];
    const double ci = c[std::size_t(iteration)];
    vtkSMPTools::For(0,
      vtkIdType(nPoints),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (std::size_t i = std::size_t(begin); i < std::size_t(end); ++i)
        {
          double d[3];
          laplacian(x1, i, d);
          for (int r = 0; r < 3; ++r)
          {
            const std::size_t k = 3 * i + std::size_t(r);
            x2[k] = x1[k] - x0[k] + x1[k] - d[r];
            result[k] += ci * x2[k];
          }
        }
      });
    zero = (zero + 1) % 3;
    one = (one + 1) % 3;
    two = (two + 1) % 3;
  }
  vtkNew<vtkPoints> smoothed;
  smoothed->SetDataTypeToFloat();
  smoothed->SetNumberOfPoints(vtkIdType(nPoints));
  for (std::size_t i = 0; i < nPoints; ++i)
  {
    const double* q = result.data() + 3 * i;
    smoothed->SetPoint(vtkIdType(i),
      q[0] * length + centre[0],
      q[1] * length + centre[1],
      q[2] * length + centre[2]);
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->SetPoints(smoothed);
  output->SetPolys(polys);
  return output;
}

/// Maps local coordinates (spacing .* local index) to LPS mm in place.
void ToPhysical(vtkPolyData* surface, const ImageGeometry& g, const std::array<long, 3>& offset)
{
  const Point3 shift =
    g.IndexToPhysical({ { double(offset[0]), double(offset[1]), double(offset[2]) } });
  vtkPoints* points = surface->GetPoints();
  const vtkIdType n = points->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double l[3];
    points->GetPoint(i, l);
    double p[3];
    for (int r = 0; r < 3; ++r)
    {
      p[r] = shift[r] + g.direction[3 * r] * l[0] + g.direction[3 * r + 1] * l[1] +
        g.direction[3 * r + 2] * l[2];
    }
    points->SetPoint(i, p);
  }
  points->Modified();
}

/// Six times the signed volume enclosed by the triangles (> 0: counter-clockwise seen from
/// outside).
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

/// Point normals (the "Normals" float array) of a consistently ordered surface: no splitting,
/// no reordering.
void ComputePointNormals(vtkPolyData* surface)
{
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(surface);
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->ComputeCellNormalsOff();
  normals->ComputePointNormalsOn();
  normals->Update();
  surface->GetPointData()->SetNormals(normals->GetOutput()->GetPointData()->GetNormals());
}

void CountEdges(vtkPolyData* surface, std::size_t& boundary, std::size_t& nonManifold)
{
  boundary = 0;
  nonManifold = 0;
  const TriangleEdges edges(CollectTriangles(surface));
  for (const MeshEdge& edge : edges.Edges())
  {
    boundary += edge.uses == 1 ? 1 : 0;
    nonManifold += edge.uses > 2 ? 1 : 0;
  }
}

SurfaceResult Extract(const LabelMap& mask,
  const SurfaceParameters& p,
  const ProgressReporter& progress)
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
    localToMask.origin = mask.geometry.IndexToPhysical(
      { { double(offset[0]), double(offset[1]), double(offset[2]) } });
    const Point3 index = localToMask.PhysicalToIndex(seed);
    localSeeds.push_back({ { index[0] * mask.geometry.spacing[0],
      index[1] * mask.geometry.spacing[1],
      index[2] * mask.geometry.spacing[2] } });
  }
  surface = KeepComponents(surface, localSeeds, progress);
  clock.Done("keep component");

  if (p.smoothing > 0.0)
  {
    const int iterations = 20;
    const double passBand = std::pow(10.0, -4.0 * p.smoothing);
    vtkSmartPointer<vtkPolyData> smoothed =
      SmoothClosedSurface(surface, iterations, passBand, progress);
    if (!smoothed)
    {
      // Not a closed 2-manifold of triangles: VTK's filter, which classifies boundary and
      // non-manifold vertices.
      vtkNew<vtkWindowedSincPolyDataFilter> smoother;
      VtkWatch watch(smoother, progress, "smoothing");
      smoother->SetInputData(surface);
      smoother->SetNumberOfIterations(iterations);
      smoother->SetPassBand(passBand);
      smoother->BoundarySmoothingOff();
      smoother->FeatureEdgeSmoothingOff();
      smoother->NonManifoldSmoothingOn();
      smoother->NormalizeCoordinatesOn();
      smoother->Update();
      smoothed = smoother->GetOutput();
    }
    surface = smoothed;
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
  ComputePointNormals(output);
  clock.Done("normals");
  CountEdges(output, result.boundaryEdges, result.nonManifoldEdges);
  result.surface = output;
  return result;
}

} // namespace

SurfaceResult ExtractSurface(const LabelMap& mask,
  const SurfaceParameters& parameters,
  const ProgressReporter& progress)
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
