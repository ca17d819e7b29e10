#include "vtkBenderRegionOutline.h"

#include "Vec3.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkContourFilter.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStripper.h>

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkBenderRegionOutline);

namespace
{
using bender::Vec3;

struct Point2
{
  double u = 0.0;
  double v = 0.0;
};

// The distance from p to the segment ab of the view plane, and where along it (0 at a, 1 at b).
double SegmentDistance(const Point2& p, const Point2& a, const Point2& b, double& t)
{
  const double du = b.u - a.u, dv = b.v - a.v;
  const double length2 = du * du + dv * dv;
  t = length2 > 0.0 ? std::clamp(((p.u - a.u) * du + (p.v - a.v) * dv) / length2, 0.0, 1.0) : 0.0;
  const double eu = a.u + t * du - p.u, ev = a.v + t * dv - p.v;
  return std::sqrt(eu * eu + ev * ev);
}

// The wire's points in the order of its polyline (the points in order without one).
std::vector<Vec3> WirePoints(vtkPolyData* wire)
{
  std::vector<Vec3> points;
  vtkCellArray* lines = wire->GetLines();
  if (lines && lines->GetNumberOfCells() > 0)
  {
    vtkIdType count = 0;
    const vtkIdType* ids = nullptr;
    lines->InitTraversal();
    while (lines->GetNextCell(count, ids))
    {
      for (vtkIdType i = 0; i < count; ++i)
      {
        double p[3];
        wire->GetPoint(ids[i], p);
        points.push_back({ p[0], p[1], p[2] });
      }
    }
    return points;
  }
  for (vtkIdType i = 0; i < wire->GetNumberOfPoints(); ++i)
  {
    double p[3];
    wire->GetPoint(i, p);
    points.push_back({ p[0], p[1], p[2] });
  }
  return points;
}
} // namespace

vtkBenderRegionOutline::vtkBenderRegionOutline() = default;
vtkBenderRegionOutline::~vtkBenderRegionOutline() = default;

void vtkBenderRegionOutline::SetCamera(vtkCamera* camera)
{
  if (this->Camera.GetPointer() != camera)
  {
    this->Camera = camera;
    this->Modified();
  }
}

vtkCamera* vtkBenderRegionOutline::GetCamera() const
{
  return this->Camera.GetPointer();
}

vtkMTimeType vtkBenderRegionOutline::GetMTime()
{
  const vtkMTimeType own = this->Superclass::GetMTime();
  return this->Camera ? std::max(own, this->Camera->GetMTime()) : own;
}

int vtkBenderRegionOutline::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  const double r = this->Radius;
  const std::vector<Vec3> wire = input ? WirePoints(input) : std::vector<Vec3>();
  if (!this->Camera || !(r > 0.0) || wire.empty())
  {
    return 1;
  }

  // The view plane through the wire's centre: u, v across the view, depth along it.
  Vec3 centre{ 0, 0, 0 };
  for (const Vec3& p : wire)
  {
    centre += p;
  }
  centre = centre / double(wire.size());
  double d[3], up[3], eye[3];
  this->Camera->GetDirectionOfProjection(d);
  this->Camera->GetViewUp(up);
  this->Camera->GetPosition(eye);
  Vec3 depth{ d[0], d[1], d[2] };
  if (!this->Camera->GetParallelProjection())
  {
    const Vec3 toCentre = centre - Vec3{ eye[0], eye[1], eye[2] };
    if (bender::Norm(toCentre) > 0.0)
    {
      depth = toCentre;
    }
  }
  depth = bender::Normalized(depth);
  Vec3 across = bender::Cross(depth, { up[0], up[1], up[2] });
  if (!(bender::Norm(across) > 1e-9))
  {
    across = bender::Cross(depth, std::abs(depth.x) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 });
  }
  across = bender::Normalized(across);
  const Vec3 upward = bender::Cross(across, depth);
  std::vector<Point2> flat(wire.size());
  std::vector<double> depths(wire.size());
  double lo[2] = { HUGE_VAL, HUGE_VAL }, hi[2] = { -HUGE_VAL, -HUGE_VAL };
  for (std::size_t i = 0; i < wire.size(); ++i)
  {
    const Vec3 q = wire[i] - centre;
    flat[i] = { bender::Dot(q, across), bender::Dot(q, upward) };
    depths[i] = bender::Dot(q, depth);
    lo[0] = std::min(lo[0], flat[i].u);
    lo[1] = std::min(lo[1], flat[i].v);
    hi[0] = std::max(hi[0], flat[i].u);
    hi[1] = std::max(hi[1], flat[i].v);
  }

  // The grid: the wire's box grown by the radius and two cells, so that its border is outside.
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]) + 2.0 * r;
  const double h = std::max(r / 8.0, extent / (this->GridCells - 4));
  const double origin[2] = { lo[0] - r - 2.0 * h, lo[1] - r - 2.0 * h };
  const int nu = int(std::ceil((hi[0] - lo[0] + 2.0 * r + 4.0 * h) / h)) + 1;
  const int nv = int(std::ceil((hi[1] - lo[1] + 2.0 * r + 4.0 * h) / h)) + 1;
  // The distance to the wire minus r; far from it (beyond r + 2 cells) only its sign matters.
  std::vector<float> field(std::size_t(nu) * std::size_t(nv), float(r));
  const std::size_t segments = wire.size() > 1 ? wire.size() - 1 : 1;
  for (std::size_t s = 0; s < segments; ++s)
  {
    const Point2& a = flat[s];
    const Point2& b = flat[std::min(s + 1, wire.size() - 1)];
    const double reach = r + 2.0 * h;
    const int i0 = std::max(0, int(std::floor((std::min(a.u, b.u) - reach - origin[0]) / h)));
    const int i1 = std::min(nu - 1, int(std::ceil((std::max(a.u, b.u) + reach - origin[0]) / h)));
    const int j0 = std::max(0, int(std::floor((std::min(a.v, b.v) - reach - origin[1]) / h)));
    const int j1 = std::min(nv - 1, int(std::ceil((std::max(a.v, b.v) + reach - origin[1]) / h)));
    for (int j = j0; j <= j1; ++j)
    {
      for (int i = i0; i <= i1; ++i)
      {
        double t = 0.0;
        const double f = SegmentDistance({ origin[0] + i * h, origin[1] + j * h }, a, b, t) - r;
        float& value = field[std::size_t(j) * std::size_t(nu) + std::size_t(i)];
        value = std::min(value, float(f));
      }
    }
  }
  vtkNew<vtkImageData> grid;
  grid->SetDimensions(nu, nv, 1);
  grid->SetSpacing(h, h, 1.0);
  grid->SetOrigin(origin[0], origin[1], 0.0);
  vtkNew<vtkFloatArray> values;
  values->SetName("distance");
  values->SetNumberOfTuples(vtkIdType(field.size()));
  std::copy(field.begin(), field.end(), values->GetPointer(0));
  grid->GetPointData()->SetScalars(values);
  vtkNew<vtkContourFilter> contour;
  contour->SetInputData(grid);
  contour->SetValue(0, 0.0);
  vtkNew<vtkStripper> stripper;
  stripper->SetInputConnection(contour->GetOutputPort());
  stripper->JoinContiguousSegmentsOn();
  stripper->Update();
  vtkPolyData* loops = stripper->GetOutput();

  // Back to the model: each point at the depth of the nearest point of the wire.
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(loops->GetNumberOfPoints());
  for (vtkIdType k = 0; k < loops->GetNumberOfPoints(); ++k)
  {
    double p[3];
    loops->GetPoint(k, p);
    const Point2 at{ p[0], p[1] };
    double best = HUGE_VAL, z = depths.front();
    for (std::size_t s = 0; s < segments; ++s)
    {
      const std::size_t e = std::min(s + 1, wire.size() - 1);
      double t = 0.0;
      const double distance = SegmentDistance(at, flat[s], flat[e], t);
      if (distance < best)
      {
        best = distance;
        z = (1.0 - t) * depths[s] + t * depths[e];
      }
    }
    const Vec3 q = centre + p[0] * across + p[1] * upward + z * depth;
    points->SetPoint(k, q.x, q.y, q.z);
  }
  output->SetPoints(points);
  output->SetLines(loops->GetLines());
  return 1;
}

void vtkBenderRegionOutline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "GridCells: " << this->GridCells << "\n";
  os << indent << "Camera: " << this->Camera.GetPointer() << "\n";
}
