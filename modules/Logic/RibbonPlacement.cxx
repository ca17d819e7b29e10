#include "RibbonPlacement.h"

#include <vtkMath.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace bender
{

namespace
{

struct LocalFit
{
  Vec3 centre;
  Vec3 axis;
  Vec3 across;
  double radius = 0.0;
  std::size_t count = 0;
};

// Principal axes of the points of `surface` within `sphere` of `centre`.
LocalFit FitNeighbourhood(vtkPolyData* surface, const Vec3& centre, double sphere)
{
  LocalFit fit;
  std::vector<Vec3> near;
  const vtkIdType n = surface->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    surface->GetPoint(i, x);
    const Vec3 p{ x[0], x[1], x[2] };
    if (Distance(p, centre) <= sphere)
    {
      near.push_back(p);
    }
  }
  fit.count = near.size();
  if (near.size() < 8)
  {
    return fit;
  }
  Vec3 mean{ 0, 0, 0 };
  for (const Vec3& p : near)
  {
    mean = mean + p;
  }
  mean = (1.0 / static_cast<double>(near.size())) * mean;
  double c[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
  for (const Vec3& p : near)
  {
    const Vec3 d = p - mean;
    const double v[3] = { d.x, d.y, d.z };
    for (int r = 0; r < 3; ++r)
    {
      for (int k = 0; k < 3; ++k)
      {
        c[r][k] += v[r] * v[k];
      }
    }
  }
  double* rows[3] = { c[0], c[1], c[2] };
  double values[3];
  double vectorStorage[3][3];
  double* vectors[3] = { vectorStorage[0], vectorStorage[1], vectorStorage[2] };
  // Jacobi sorts eigenvalues in decreasing order; eigenvectors are the columns.
  vtkMath::Jacobi(rows, values, vectors);
  fit.axis = Normalized(Vec3{ vectors[0][0], vectors[1][0], vectors[2][0] });
  fit.across = Normalized(Vec3{ vectors[0][1], vectors[1][1], vectors[2][1] });
  fit.centre = mean;
  double sum = 0.0;
  for (const Vec3& p : near)
  {
    const Vec3 d = p - mean;
    const Vec3 radial = d - Dot(d, fit.axis) * fit.axis;
    sum += Norm(radial);
  }
  fit.radius = sum / static_cast<double>(near.size());
  return fit;
}

}

RibbonPlacement PlaceRibbonOnSurface(vtkPolyData* surface,
  const Vec3& picked,
  const RibbonPlacementOptions& options)
{
  if (!surface || surface->GetNumberOfPoints() < 8)
  {
    throw RibbonPlacementError("place ribbon: there is no surface to place it on");
  }
  if (!IsFinite(picked))
  {
    throw RibbonPlacementError("place ribbon: the picked point is not finite");
  }
  if (!(options.lengthFactor >= 2.0 && options.lengthFactor <= 40.0) ||
    !(options.radiusFactor >= 1.1 && options.radiusFactor <= 10.0))
  {
    throw RibbonPlacementError(
      "place ribbon: lengthFactor must be in [2, 40] and radiusFactor in [1.1, 10]");
  }
  double bounds[6];
  surface->GetBounds(bounds);
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  if (!(diagonal > 0.0))
  {
    throw RibbonPlacementError("place ribbon: the surface has no extent");
  }

  // Start from a sphere of 5% of the model and refine on three local radii around the axis.
  double sphere = 0.05 * diagonal;
  Vec3 centre = picked;
  LocalFit fit;
  for (int pass = 0; pass < 3; ++pass)
  {
    const LocalFit next = FitNeighbourhood(surface, centre, sphere);
    if (next.count < 8 || !(next.radius > 0.0))
    {
      break;
    }
    fit = next;
    // Stay at the picked place along the vessel: the neighbourhood's centroid drifts along the
    // axis near ends and bends, its foot on the axis does not.
    fit.centre = fit.centre + Dot(picked - fit.centre, fit.axis) * fit.axis;
    centre = fit.centre;
    sphere = std::max(3.0 * fit.radius, 1e-6 * diagonal);
  }
  if (fit.count < 8)
  {
    throw RibbonPlacementError(
      "place ribbon: too few surface points near the picked point; pick on the vessel wall");
  }

  RibbonPlacement placement;
  placement.vesselRadius = fit.radius;
  placement.suggestedRadius = options.radiusFactor * fit.radius;
  const double half = 0.5 * options.lengthFactor * fit.radius;
  placement.ribbon.start.position = fit.centre - half * fit.axis;
  placement.ribbon.end.position = fit.centre + half * fit.axis;
  placement.ribbon.start.tangent = fit.axis;
  placement.ribbon.end.tangent = fit.axis;
  placement.ribbon.start.normal = fit.across;
  placement.ribbon.end.normal = fit.across;
  placement.ribbon.extraTurns = 0;
  return placement;
}

} // namespace bender
