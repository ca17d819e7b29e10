#include "VesselTestUtilities.h"

#include "CfdVerificationTubes.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bender
{
namespace test
{
namespace
{
Point3 Sub(const Point3& a, const Point3& b)
{
  return { { a[0] - b[0], a[1] - b[1], a[2] - b[2] } };
}
double Dot(const Point3& a, const Point3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Point3 Cross(const Point3& a, const Point3& b)
{
  return { { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] } };
}
Point3 Unit(const Point3& a)
{
  const double n = std::sqrt(Dot(a, a));
  return { { a[0] / n, a[1] / n, a[2] / n } };
}
double SegmentDistance(const Point3& p, const Point3& a, const Point3& b)
{
  const Point3 ab = Sub(b, a);
  const double l2 = Dot(ab, ab);
  double t = l2 > 0 ? Dot(Sub(p, a), ab) / l2 : 0.0;
  t = std::max(0.0, std::min(1.0, t));
  const Point3 q = { { a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2] } };
  const Point3 d = Sub(p, q);
  return std::sqrt(Dot(d, d));
}
} // namespace

vtkSmartPointer<vtkPolyData> SweptTube(const Curve& curve,
  double t0,
  double t1,
  int rings,
  int sides,
  double radius)
{
  // The curve's stations with a rotation-minimising frame (each normal the previous one
  // projected), swept by the one tube generator (CfdVerificationTubes.h).
  std::vector<TubeStation> stations;
  Point3 normal{ { 0, 0, 0 } };
  for (int i = 0; i < rings; ++i)
  {
    const double t = t0 + (t1 - t0) * i / (rings - 1);
    const double h = 1e-5 * (t1 - t0);
    const Point3 c = curve(t);
    const Point3 tangent = Unit(Sub(curve(t + h), curve(t - h)));
    if (i == 0)
    {
      const Point3 axis =
        std::abs(tangent[0]) < 0.9 ? Point3{ { 1, 0, 0 } } : Point3{ { 0, 1, 0 } };
      normal = Unit(Cross(tangent, Cross(axis, tangent)));
    }
    const double d = Dot(normal, tangent);
    normal = Unit(
      { { normal[0] - d * tangent[0], normal[1] - d * tangent[1], normal[2] - d * tangent[2] } });
    stations.push_back({ { c[0], c[1], c[2] },
      { tangent[0], tangent[1], tangent[2] },
      { normal[0], normal[1], normal[2] } });
  }
  return SweepOpenTube(stations, radius, sides);
}

vtkSmartPointer<vtkPolyData> ImplicitTubes(const std::vector<Segment>& segments,
  const double bounds[6],
  double spacing)
{
  vtkNew<vtkImageData> image;
  int dims[3];
  for (int c = 0; c < 3; ++c)
  {
    dims[c] = static_cast<int>(std::ceil((bounds[2 * c + 1] - bounds[2 * c]) / spacing)) + 1;
  }
  image->SetDimensions(dims);
  image->SetOrigin(bounds[0], bounds[2], bounds[4]);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkDoubleArray> values;
  values->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  vtkIdType id = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i, ++id)
      {
        const Point3 p = {
          { bounds[0] + i * spacing, bounds[2] + j * spacing, bounds[4] + k * spacing }
        };
        double f = std::numeric_limits<double>::infinity();
        for (const auto& s : segments)
        {
          f = std::min(f, SegmentDistance(p, s.a, s.b) - s.radius);
        }
        values->SetValue(id, f);
      }
    }
  }
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(contour->GetOutput());
  return out;
}

std::vector<Point3> SampleCurve(const Curve& curve, double t0, double t1, int count)
{
  std::vector<Point3> samples;
  for (int i = 0; i < count; ++i)
  {
    samples.push_back(curve(t0 + (t1 - t0) * i / (count - 1)));
  }
  return samples;
}

double DistanceToPolyline(const Point3& p, const std::vector<Point3>& samples)
{
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < samples.size(); ++i)
  {
    best = std::min(best, SegmentDistance(p, samples[i], samples[i + 1]));
  }
  return best;
}

std::vector<Point3> PointsOf(vtkPolyData* lines)
{
  std::vector<Point3> out(static_cast<std::size_t>(lines->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < lines->GetNumberOfPoints(); ++i)
  {
    lines->GetPoint(i, out[i].data());
  }
  return out;
}

double MaxDistanceToLines(vtkPolyData* a, vtkPolyData* b)
{
  std::vector<std::vector<Point3>> polylines;
  vtkCellArray* cells = b->GetLines();
  cells->InitTraversal();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  while (cells->GetNextCell(npts, ids))
  {
    std::vector<Point3> line(static_cast<std::size_t>(npts));
    for (vtkIdType i = 0; i < npts; ++i)
    {
      b->GetPoint(ids[i], line[i].data());
    }
    polylines.push_back(line);
  }
  double worst = 0.0;
  for (const auto& p : PointsOf(a))
  {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& line : polylines)
    {
      d = std::min(d, DistanceToPolyline(p, line));
    }
    worst = std::max(worst, d);
  }
  return worst;
}

} // namespace test
} // namespace bender
