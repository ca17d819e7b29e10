#include "SurfaceMetrics.h"

#include <vtkCellArray.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace bender
{
namespace
{

/// Distance from every vertex of `from` to the surface `to`; NaN for excluded vertices.
std::vector<double> Distances(vtkPolyData* from,
  vtkPolyData* to,
  vtkStaticCellLocator* excludeLocator,
  double exclusion)
{
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(to);
  locator->BuildLocator();
  // Cell links are built lazily: build them here, not inside the threads.
  to->BuildCells();
  const vtkIdType n = from->GetNumberOfPoints();
  std::vector<double> d(static_cast<std::size_t>(n));
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkNew<vtkGenericCell> cell;
      for (vtkIdType i = begin; i < end; ++i)
      {
        double x[3], closest[3], d2 = 0.0;
        vtkIdType cellId = -1;
        int subId = 0;
        from->GetPoint(i, x);
        if (excludeLocator)
        {
          excludeLocator->FindClosestPoint(x, closest, cell, cellId, subId, d2);
          if (cellId >= 0 && std::sqrt(d2) < exclusion)
          {
            d[static_cast<std::size_t>(i)] = std::numeric_limits<double>::quiet_NaN();
            continue;
          }
        }
        locator->FindClosestPoint(x, closest, cell, cellId, subId, d2);
        d[static_cast<std::size_t>(i)] = std::sqrt(d2);
      }
    });
  return d;
}

DistanceStats Summarise(std::vector<double> d)
{
  d.erase(std::remove_if(d.begin(), d.end(), [](double v) { return std::isnan(v); }), d.end());
  if (d.empty())
  {
    throw std::invalid_argument("surface accuracy: every vertex is excluded");
  }
  DistanceStats s;
  s.samples = d.size();
  s.mean = std::accumulate(d.begin(), d.end(), 0.0) / double(d.size());
  const std::size_t k = std::min(d.size() - 1, static_cast<std::size_t>(0.95 * double(d.size())));
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(k), d.end());
  s.p95 = d[k];
  s.max = *std::max_element(d.begin(), d.end());
  return s;
}

} // namespace

SurfaceAccuracy MeasureSurfaceAccuracy(vtkPolyData* extracted,
  vtkPolyData* truth,
  vtkPolyData* exclude,
  double exclusionDistance)
{
  if (!extracted || !truth || extracted->GetNumberOfPolys() == 0 || truth->GetNumberOfPolys() == 0)
  {
    throw std::invalid_argument("surface accuracy: empty surface");
  }
  vtkNew<vtkStaticCellLocator> excludeLocator;
  const bool excluding = exclude && exclude->GetNumberOfCells() > 0 && exclusionDistance > 0.0;
  if (excluding)
  {
    excludeLocator->SetDataSet(exclude);
    excludeLocator->BuildLocator();
    exclude->BuildCells();
  }
  vtkStaticCellLocator* ex = excluding ? excludeLocator.GetPointer() : nullptr;
  SurfaceAccuracy a;
  a.toTruth = Summarise(Distances(extracted, truth, ex, exclusionDistance));
  a.fromTruth = Summarise(Distances(truth, extracted, ex, exclusionDistance));
  return a;
}

TriangleQuality MeasureTriangleQuality(vtkPolyData* surface)
{
  TriangleQuality q;
  if (!surface)
  {
    return q;
  }
  vtkPoints* points = surface->GetPoints();
  vtkCellArray* polys = surface->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  double sum = 0.0;
  std::size_t below10 = 0;
  std::size_t below30 = 0;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      continue;
    }
    double p[3][3];
    for (int v = 0; v < 3; ++v)
    {
      points->GetPoint(ids[v], p[v]);
    }
    double minAngle = 180.0;
    for (int v = 0; v < 3; ++v)
    {
      const double* a = p[v];
      const double* b = p[(v + 1) % 3];
      const double* c = p[(v + 2) % 3];
      double u[3], w[3];
      for (int k = 0; k < 3; ++k)
      {
        u[k] = b[k] - a[k];
        w[k] = c[k] - a[k];
      }
      const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      const double nw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      const double cosine =
        nu > 0 && nw > 0 ? (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) / (nu * nw) : 1.0;
      minAngle = std::min(minAngle, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI);
    }
    sum += minAngle;
    below10 += minAngle < 10.0 ? 1 : 0;
    below30 += minAngle < 30.0 ? 1 : 0;
    ++q.triangles;
  }
  if (q.triangles > 0)
  {
    q.meanMinAngle = sum / double(q.triangles);
    q.fractionBelow10Deg = double(below10) / double(q.triangles);
    q.fractionBelow30Deg = double(below30) / double(q.triangles);
  }
  return q;
}

} // namespace bender
