// Centerlines of shapes that are no vessel (issue 22): a bunny, a cow, a sphere and a torus,
// closed surfaces without open ends. Whatever the centerline search makes of them, it never
// leaves the surface: either every point of every centerline lies inside the shape, or the
// shape is refused with one line.

#include "MeshIO.h"
#include "VesselCenterlines.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSelectEnclosedPoints.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace bender;

namespace
{

// A closed torus about z: the tube of radius `r` round the circle of radius `R`.
vtkSmartPointer<vtkPolyData> Torus(double R, double r, int around, int across)
{
  vtkNew<vtkPoints> points;
  for (int i = 0; i < around; ++i)
  {
    const double u = 2.0 * M_PI * i / around;
    for (int k = 0; k < across; ++k)
    {
      const double v = 2.0 * M_PI * k / across;
      const double w = R + r * std::cos(v);
      points->InsertNextPoint(w * std::cos(u), w * std::sin(u), r * std::sin(v));
    }
  }
  vtkNew<vtkCellArray> cells;
  for (int i = 0; i < around; ++i)
  {
    for (int k = 0; k < across; ++k)
    {
      const vtkIdType a = i * across + k, b = i * across + (k + 1) % across;
      const vtkIdType c = ((i + 1) % around) * across + (k + 1) % across;
      const vtkIdType d = ((i + 1) % around) * across + k;
      const vtkIdType t1[3] = { a, d, c }, t2[3] = { a, c, b };
      cells->InsertNextCell(3, t1);
      cells->InsertNextCell(3, t2);
    }
  }
  auto torus = vtkSmartPointer<vtkPolyData>::New();
  torus->SetPoints(points);
  torus->SetPolys(cells);
  return torus;
}

// The points of `lines` outside the closed `surface`.
vtkIdType PointsOutside(vtkPolyData* surface, vtkPolyData* lines)
{
  vtkNew<vtkSelectEnclosedPoints> enclosed;
  enclosed->SetSurfaceData(surface);
  enclosed->Initialize(surface);
  vtkIdType outside = 0;
  for (vtkIdType i = 0; i < lines->GetNumberOfPoints(); ++i)
  {
    outside += enclosed->IsInsideSurface(lines->GetPoint(i)) ? 0 : 1;
  }
  enclosed->Complete();
  return outside;
}

void ExpectInsideOrRefused(vtkPolyData* surface, const std::string& name)
{
  const CenterlineResult result = ComputeCenterlines(surface);
  if (!result.ok)
  {
    EXPECT_FALSE(result.message.empty()) << name;
    EXPECT_EQ(result.message.find('\n'), std::string::npos) << name << ": " << result.message;
    return;
  }
  ASSERT_GT(result.paths->GetNumberOfPoints(), 0) << name;
  EXPECT_EQ(PointsOutside(surface, result.paths), 0)
    << name << ": of " << result.paths->GetNumberOfPoints() << " centerline points";
}

std::string External(const std::string& name)
{
  return std::string(BENDER_EXTERNAL_DATA_DIR) + "/" + name;
}

} // namespace

TEST(NonTubularShapes, TheCenterlinesOfABunnyACowAndASphereStayInsideOrAreRefused)
{
  for (const char* name : { "bunny.obj", "cow.off", "sphere.off" })
  {
    ExpectInsideOrRefused(ReadMesh(External(name)), name);
  }
}

TEST(NonTubularShapes, TheCenterlinesOfATorusStayInsideOrAreRefused)
{
  ExpectInsideOrRefused(Torus(20.0, 4.0, 96, 24), "torus");
}

TEST(NonTubularShapes, ACowIsRefusedAsNotTubular)
{
  // Its legs and horns are tubes, its body is no tube: the paths from one tip to the others
  // cross the body, and smoothed they cut through its wall.
  const CenterlineResult result = ComputeCenterlines(ReadMesh(External("cow.off")));
  ASSERT_FALSE(result.ok);
  EXPECT_NE(result.message.find("not tubular"), std::string::npos) << result.message;
}
