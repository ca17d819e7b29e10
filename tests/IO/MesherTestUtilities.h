#ifndef bender_MesherTestUtilities_h
#define bender_MesherTestUtilities_h

// A closed, labelled vessel whose every measure is known, for the mesher export tests.

#include "PatchLabels.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <utility>
#include <vector>

namespace bender_test
{
constexpr int Segments = 128;
constexpr int Rings = 11;        // z = 0, 1, ..., 10
constexpr double Offset = 100.0; // x of the axis: coordinates far from 0 test the unit change

// A closed cylinder of radius 1 along z from 0 to 10, axis at (Offset, 0), triangles outward:
// wall (1), inlet (2) the fan closing z = 0, outlet_1 (3) the fan closing z = 10.
inline vtkSmartPointer<vtkPolyData> LabelledCylinder(bool flip = false)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int i = 0; i < Rings; ++i)
  {
    for (int j = 0; j < Segments; ++j)
    {
      const double a = 2 * M_PI * j / Segments;
      points->InsertNextPoint(Offset + std::cos(a), std::sin(a), i);
    }
  }
  const vtkIdType bottom = points->InsertNextPoint(Offset, 0, 0);
  const vtkIdType top = points->InsertNextPoint(Offset, 0, Rings - 1);
  vtkNew<vtkCellArray> polys;
  std::vector<int> ids;
  auto add = [&](vtkIdType a, vtkIdType b, vtkIdType c, int id)
  {
    if (flip)
    {
      std::swap(b, c);
    }
    polys->InsertNextCell({ a, b, c });
    ids.push_back(id);
  };
  auto at = [](int i, int j) { return static_cast<vtkIdType>(i * Segments + (j % Segments)); };
  for (int i = 0; i + 1 < Rings; ++i)
  {
    for (int j = 0; j < Segments; ++j)
    {
      add(at(i, j), at(i, j + 1), at(i + 1, j + 1), 1);
      add(at(i, j), at(i + 1, j + 1), at(i + 1, j), 1);
    }
  }
  for (int j = 0; j < Segments; ++j)
  {
    add(bottom, at(0, j + 1), at(0, j), 2);
    add(top, at(Rings - 1, j), at(Rings - 1, j + 1), 3);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  bender::WritePatchLabels(mesh,
    ids,
    { { 1, "wall", bender::PatchType::Wall },
      { 2, "inlet", bender::PatchType::Inlet },
      { 3, "outlet_1", bender::PatchType::Outlet } });
  return mesh;
}

} // namespace bender_test

#endif
