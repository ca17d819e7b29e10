#include "FlowStreamlines.h"

#include "BenderErrors.h"
#include "CfdFlowResults.h"
#include "PatchLabels.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkRungeKutta45.h>
#include <vtkStreamTracer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
struct Cap
{
  std::vector<std::array<double, 3>> centroids; // of its triangles
  std::array<double, 3> centre{};
  std::array<double, 3> normal{}; // area-weighted, from the triangles' orientation
  double radius = 0.0;            // equivalent, sqrt(area / pi)
};

Cap InletCap(vtkPolyData* surface, const std::string& where)
{
  int inlet = -1;
  for (const PatchLabel& p : ReadPatchLabels(surface))
  {
    inlet = p.type == PatchType::Inlet ? p.id : inlet;
  }
  vtkDataArray* ids = surface->GetCellData()->GetArray(kCellEntityIdsArrayName);
  if (inlet < 0 || !ids)
  {
    throw InputError(where + ": the surface has no inlet to seed streamlines from");
  }
  Cap cap;
  double area = 0.0;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    surface->GetCellPoints(c, cell);
    if (static_cast<int>(ids->GetTuple1(c)) != inlet || cell->GetNumberOfIds() != 3)
    {
      continue;
    }
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      surface->GetPoint(cell->GetId(k), p[k]);
    }
    double u[3], v[3], n[3];
    vtkMath::Subtract(p[1], p[0], u);
    vtkMath::Subtract(p[2], p[0], v);
    vtkMath::Cross(u, v, n); // twice the area, along the normal
    const double a = 0.5 * vtkMath::Norm(n);
    std::array<double, 3> centroid{};
    for (int k = 0; k < 3; ++k)
    {
      centroid[k] = (p[0][k] + p[1][k] + p[2][k]) / 3.0;
      cap.centre[k] += a * centroid[k];
      cap.normal[k] += 0.5 * n[k];
    }
    area += a;
    cap.centroids.push_back(centroid);
  }
  if (!(area > 0.0))
  {
    throw InputError(where + ": the inlet's cap has no area");
  }
  for (int k = 0; k < 3; ++k)
  {
    cap.centre[k] /= area;
  }
  vtkMath::Normalize(cap.normal.data());
  cap.radius = std::sqrt(area / vtkMath::Pi());
  return cap;
}

/// Up to `count` seeds over the cap, pulled a fifth towards its centre and moved `depth` along
/// `direction`.
vtkSmartPointer<vtkPolyData> Seeds(const Cap& cap, int count, double depth, double direction)
{
  vtkNew<vtkPoints> points;
  const std::size_t n = cap.centroids.size();
  const std::size_t step =
    std::max<std::size_t>(1, n / static_cast<std::size_t>(std::max(1, count)));
  for (std::size_t i = 0; i < n; i += step)
  {
    double p[3];
    for (int k = 0; k < 3; ++k)
    {
      p[k] = cap.centre[k] + 0.8 * (cap.centroids[i][k] - cap.centre[k]) +
        direction * depth * cap.normal[k];
    }
    points->InsertNextPoint(p);
  }
  auto seeds = vtkSmartPointer<vtkPolyData>::New();
  seeds->SetPoints(points);
  return seeds;
}
} // namespace

vtkSmartPointer<vtkPolyData> FlowStreamlines(const std::string& caseDirectory,
  vtkPolyData* surface,
  int seeds)
{
  const fs::path file = fs::path(caseDirectory) / kCfdResultsFolder / kCfdVolumeResults;
  std::error_code ec;
  if (!fs::exists(file, ec))
  {
    throw InputError(file.string() + ": missing (has the case been mapped?)");
  }
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkUnstructuredGrid* volume = reader->GetOutput();
  if (!volume || !volume->GetPointData()->GetArray(kVelocityArrayName))
  {
    throw InputError(file.string() + ": no velocity (point data U)");
  }
  const Cap cap = InletCap(surface, file.string());
  double bounds[6];
  volume->GetBounds(bounds);
  const double diagonal = std::sqrt(
    vtkMath::Distance2BetweenPoints(std::array<double, 3>{ bounds[0], bounds[2], bounds[4] }.data(),
      std::array<double, 3>{ bounds[1], bounds[3], bounds[5] }.data()));
  // Inside is against the cap's normal for an outward surface; the other way when the seeds
  // found no cell (a surface oriented inwards).
  vtkSmartPointer<vtkPolyData> lines;
  for (const double direction : { -1.0, 1.0 })
  {
    vtkNew<vtkStreamTracer> tracer;
    tracer->SetInputData(volume);
    tracer->SetSourceData(Seeds(cap, seeds, 0.1 * cap.radius, direction));
    tracer->SetInputArrayToProcess(
      0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, kVelocityArrayName);
    vtkNew<vtkRungeKutta45> integrator;
    tracer->SetIntegrator(integrator);
    tracer->SetIntegrationDirectionToForward();
    tracer->SetMaximumPropagation(3.0 * diagonal);
    tracer->SetInitialIntegrationStep(0.2);
    tracer->SetMaximumNumberOfSteps(4000);
    tracer->SetComputeVorticity(false);
    tracer->Update();
    lines = tracer->GetOutput();
    if (lines->GetNumberOfLines() > 0)
    {
      break;
    }
  }
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->SetPoints(lines->GetPoints());
  result->SetLines(lines->GetLines());
  if (vtkDataArray* velocity = lines->GetPointData()->GetArray(kVelocityArrayName))
  {
    vtkNew<vtkDoubleArray> speed;
    speed->SetName("Speed");
    speed->SetNumberOfTuples(velocity->GetNumberOfTuples());
    for (vtkIdType i = 0; i < velocity->GetNumberOfTuples(); ++i)
    {
      speed->SetValue(i, vtkMath::Norm(velocity->GetTuple3(i)));
    }
    result->GetPointData()->AddArray(speed);
  }
  return result;
}

} // namespace bender
