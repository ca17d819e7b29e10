// The one coordinate range rule (CoordinateRange.h) on every read and write path: a coordinate
// beyond single precision (an OFF file with -1e308 was read, exported as an STL of -inf and
// measured as 1.1e+307 mm^3) is refused with one line naming the file, and nothing is written.

#include "CoordinateRange.h"
#include "BenderStlExport.h"
#include "IOTestUtilities.h"
#include "LabelledSurface.h"
#include "MeshFormats.h"
#include "MeshIO.h"
#include "PatchSidecar.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace
{
using bender_test::TempDir;

// A closed tetrahedron with one coordinate set to `far`.
vtkSmartPointer<vtkPolyData> Tetrahedron(double far)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(far, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(0, 0, 1);
  vtkNew<vtkCellArray> polys;
  const vtkIdType faces[4][3] = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
  for (const auto& f : faces)
  {
    polys->InsertNextCell(3, f);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

std::string OffText(const std::string& far)
{
  return "OFF\n4 4 0\n0 0 0\n" + far + " 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
}

template<typename F>
std::string ErrorOf(F&& f)
{
  try
  {
    f();
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "(no error)";
}
} // namespace

TEST(CoordinateRange, TheRule)
{
  const double big = bender::MaxMeshCoordinate;
  const double p[3] = { -big, big, 0.0 };
  EXPECT_TRUE(bender::InMeshCoordinateRange(p));
  EXPECT_EQ(bender::CoordinateRangeProblem(p), "");
  for (const double bad : { std::nextafter(big, 2 * big),
         -1e308,
         1e39,
         std::numeric_limits<double>::infinity(),
         std::numeric_limits<double>::quiet_NaN() })
  {
    const double q[3] = { 0.0, 0.0, bad };
    EXPECT_FALSE(bender::InMeshCoordinateRange(q)) << bad;
    const std::string problem = bender::CoordinateRangeProblem(q);
    EXPECT_TRUE(problem.find("single-precision range") != std::string::npos ||
      problem.find("non-finite") != std::string::npos)
      << problem;
  }
  // The largest coordinate let through is a finite float.
  EXPECT_TRUE(std::isfinite(static_cast<float>(big)));
  EXPECT_EQ(bender::MeshCoordinateRangeProblem(Tetrahedron(1.0)), "");
  EXPECT_EQ(bender::MeshCoordinateRangeProblem(Tetrahedron(-1e308)).rfind("point 1: ", 0), 0u);
}

// The reproducer: an OFF file (double precision) with -1e308 is refused on read, naming it.
TEST(CoordinateRange, ReadersRefuseCoordinatesBeyondSinglePrecision)
{
  TempDir dir;
  bender_test::WriteText(dir / "far.off", OffText("-1e308"));
  std::string message = ErrorOf([&] { bender::ReadMesh(dir / "far.off"); });
  EXPECT_EQ(message.rfind("far.off: line 4: ", 0), 0u) << message;
  EXPECT_NE(message.find("single-precision range"), std::string::npos) << message;
  // The largest float itself is read.
  bender_test::WriteText(dir / "edge.off", OffText("-3.4028234663852886e+38"));
  EXPECT_EQ(bender::ReadMesh(dir / "edge.off")->GetPoint(1)[0], -bender::MaxMeshCoordinate);
  // A double-precision VTK file with 1e39, written by VTK directly (WriteMesh refuses it).
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(Tetrahedron(1e39));
  writer->SetFileName((dir / "far.vtp").c_str());
  ASSERT_EQ(writer->Write(), 1);
  message = ErrorOf([&] { bender::ReadMesh(dir / "far.vtp"); });
  EXPECT_EQ(message.rfind("far.vtp: point 1: ", 0), 0u) << message;
  EXPECT_NE(message.find("single-precision range"), std::string::npos) << message;
}

// Every writable format refuses it, double-precision ones included, and leaves no file.
TEST(CoordinateRange, EveryWriterRefusesCoordinatesBeyondSinglePrecision)
{
  TempDir dir;
  const auto mesh = Tetrahedron(-1e308);
  for (const bender::MeshFormat& format : bender::MeshFormats())
  {
    if (!format.CanWrite())
    {
      continue;
    }
    const std::string name = "far" + format.extensions.front();
    const std::string message = ErrorOf([&] { bender::WriteMesh(mesh, dir / name); });
    EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("single-precision range"), std::string::npos) << message;
  }
  EXPECT_TRUE(dir.Entries().empty());
}

// The named-patch STL exports and the sidecar: in every frame and unit, nothing is written.
TEST(CoordinateRange, StlExportsRefuseCoordinatesBeyondSinglePrecision)
{
  TempDir dir;
  const auto mesh = Tetrahedron(-1e308);
  for (const auto mode :
    { bender::StlPatchMode::Single, bender::StlPatchMode::Solids, bender::StlPatchMode::Files })
  {
    for (const auto frame : { bender::StlFrame::LPS, bender::StlFrame::RAS })
    {
      for (const char* unit : { "mm", "m" })
      {
        bender::StlExportOptions options;
        options.patches = mode;
        options.frame = frame;
        options.unit = unit;
        const std::string message =
          ErrorOf([&] { bender::ExportStl(mesh, dir / "o.stl", options); });
        EXPECT_EQ(message.rfind("o.stl: point 1", 0), 0u) << message;
        EXPECT_NE(message.find("single-precision range"), std::string::npos) << message;
      }
    }
  }
  std::string problem;
  EXPECT_FALSE(bender::WriteStlFile(mesh, dir / "w.stl", false, "", problem));
  EXPECT_NE(problem.find("single-precision range"), std::string::npos) << problem;
  // The sidecar's volumes are measured only from coordinates within the range.
  const bender::ExportTransform ras(bender::StlFrame::RAS, "mm");
  EXPECT_NE(ErrorOf([&] { bender::ComputePatchSidecar(bender::ReadLabelledSurface(mesh), ras); })
              .find("single-precision range"),
    std::string::npos);
  EXPECT_TRUE(dir.Entries().empty());
}
