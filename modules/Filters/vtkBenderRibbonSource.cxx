#include "vtkBenderRibbonSource.h"

#include "GeometryErrors.h"
#include "Ribbon.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkBenderRibbonSource);

namespace
{
constexpr double Pi = 3.14159265358979323846;

void Insert(vtkPoints* pts, const bender::Vec3& p)
{
  pts->InsertNextPoint(p.x, p.y, p.z);
}

// Appends a ring of `sides` points of radius r around c in the plane spanned by u, v.
void Ring(vtkPoints* pts,
  const bender::Vec3& c,
  const bender::Vec3& u,
  const bender::Vec3& v,
  double r,
  int sides)
{
  for (int k = 0; k < sides; ++k)
  {
    const double a = 2.0 * Pi * k / sides;
    Insert(pts, c + (u * std::cos(a) + v * std::sin(a)) * r);
  }
}

// Connects ring i (first point index a) to ring i+1 (index b) with quads split in triangles.
void Stitch(vtkCellArray* polys, vtkIdType a, vtkIdType b, int sides)
{
  for (int k = 0; k < sides; ++k)
  {
    const vtkIdType k1 = (k + 1) % sides;
    const vtkIdType t0[3] = { a + k, b + k, b + k1 };
    const vtkIdType t1[3] = { a + k, b + k1, a + k1 };
    polys->InsertNextCell(3, t0);
    polys->InsertNextCell(3, t1);
  }
}
} // namespace

vtkBenderRibbonSource::vtkBenderRibbonSource()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(3);
  this->Ribbon.start.position = { 0, 0, 0 };
  this->Ribbon.end.position = { 10, 0, 0 };
}

void vtkBenderRibbonSource::SetRibbon(const bender::RibbonSpec& ribbon)
{
  this->Ribbon = ribbon;
  this->Modified();
}

int vtkBenderRibbonSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* strip = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* wire = vtkPolyData::GetData(outputVector, 1);
  vtkPolyData* tube = vtkPolyData::GetData(outputVector, 2);
  strip->Initialize();
  wire->Initialize();
  tube->Initialize();

  bender::Ribbon ribbon;
  try
  {
    ribbon = bender::Ribbon(this->Ribbon);
  }
  catch (const bender::InvalidRibbonError& e)
  {
    this->Valid = false;
    this->LastError = e.what();
    return 1;
  }
  this->Valid = true;
  this->LastError.clear();

  const int n = this->Resolution;
  std::vector<bender::Frame> frames(n + 1);
  for (int i = 0; i <= n; ++i)
  {
    frames[i] = ribbon.FrameAt(static_cast<double>(i) / n);
  }

  // Wire.
  {
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    vtkNew<vtkDoubleArray> s;
    s->SetName("s");
    std::vector<vtkIdType> ids(n + 1);
    for (int i = 0; i <= n; ++i)
    {
      Insert(pts, frames[i].origin);
      s->InsertNextValue(static_cast<double>(i) / n);
      ids[i] = i;
    }
    vtkNew<vtkCellArray> lines;
    lines->InsertNextCell(n + 1, ids.data());
    wire->SetPoints(pts);
    wire->SetLines(lines);
    wire->GetPointData()->AddArray(s);
  }

  // Strip along N_s, normals along B_s.
  {
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    vtkNew<vtkDoubleArray> s;
    s->SetName("s");
    std::vector<vtkIdType> ids(2 * (n + 1));
    for (int i = 0; i <= n; ++i)
    {
      const bender::Frame& f = frames[i];
      Insert(pts, f.origin - f.n * this->Width);
      Insert(pts, f.origin + f.n * this->Width);
      for (int k = 0; k < 2; ++k)
      {
        normals->InsertNextTuple3(f.b.x, f.b.y, f.b.z);
        s->InsertNextValue(static_cast<double>(i) / n);
      }
      ids[2 * i] = 2 * i;
      ids[2 * i + 1] = 2 * i + 1;
    }
    vtkNew<vtkCellArray> strips;
    strips->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    strip->SetPoints(pts);
    strip->SetStrips(strips);
    strip->GetPointData()->SetNormals(normals);
    strip->GetPointData()->AddArray(s);
  }

  // Region-of-influence tube: rings of radius R in the normal planes (spanned by N_s and B_s,
  // so the tube follows the wire without kinks), closed by hemispheres at the free ends.
  if (this->Radius > 0.0)
  {
    const int sides = this->TubeSides;
    const int capRings = std::max(2, sides / 4);
    const double r = this->Radius;
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    vtkNew<vtkCellArray> polys;
    // Start cap: pole, then rings from the pole towards the equator at P0.
    const bender::Frame& f0 = frames.front();
    Insert(pts, f0.origin - f0.t * r);
    for (int k = 1; k < capRings; ++k)
    {
      const double a = 0.5 * Pi * k / capRings;
      Ring(pts, f0.origin - f0.t * (r * std::cos(a)), f0.n, f0.b, r * std::sin(a), sides);
    }
    for (int i = 0; i <= n; ++i)
    {
      Ring(pts, frames[i].origin, frames[i].n, frames[i].b, r, sides);
    }
    const bender::Frame& f1 = frames.back();
    for (int k = capRings - 1; k >= 1; --k)
    {
      const double a = 0.5 * Pi * k / capRings;
      Ring(pts, f1.origin + f1.t * (r * std::cos(a)), f1.n, f1.b, r * std::sin(a), sides);
    }
    Insert(pts, f1.origin + f1.t * r);

    const vtkIdType rings = (capRings - 1) + (n + 1) + (capRings - 1);
    // Fan from the start pole to the first ring.
    for (int k = 0; k < sides; ++k)
    {
      const vtkIdType tri[3] = { 0, 1 + (k + 1) % sides, 1 + k };
      polys->InsertNextCell(3, tri);
    }
    for (vtkIdType i = 0; i + 1 < rings; ++i)
    {
      Stitch(polys, 1 + i * sides, 1 + (i + 1) * sides, sides);
    }
    const vtkIdType lastRing = 1 + (rings - 1) * sides;
    const vtkIdType pole = lastRing + sides;
    for (int k = 0; k < sides; ++k)
    {
      const vtkIdType tri[3] = { pole, lastRing + k, lastRing + (k + 1) % sides };
      polys->InsertNextCell(3, tri);
    }
    tube->SetPoints(pts);
    tube->SetPolys(polys);
  }
  return 1;
}

void vtkBenderRibbonSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "Width: " << this->Width << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "TubeSides: " << this->TubeSides << "\n";
  os << indent << "Valid: " << this->Valid << "\n";
}
