// Files carry their unit and are read in it (issue 22, item 7): every format Bender writes with
// a unit, written in metres, reads back in millimetres at the size it had, the unit said; a file
// in millimetres or stating nothing is read as it is.

#include "MeshUnit.h"
#include "BenderStlExport.h"
#include "IOTestUtilities.h"
#include "MeshIO.h"
#include "MesherTestUtilities.h"
#include "TetgenExport.h"

#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
using bender_test::LabelledCylinder;
using bender_test::TempDir;

constexpr const char* MetresHeader = "bender export: frame LPS, unit m";

double BoundsDifference(vtkPolyData* a, vtkPolyData* b)
{
  double p[6], q[6];
  a->GetBounds(p);
  b->GetBounds(q);
  double worst = 0.0;
  for (int k = 0; k < 6; ++k)
  {
    worst = std::max(worst, std::abs(p[k] - q[k]));
  }
  return worst;
}

// `mesh` in metres, as an export in metres holds it; its field data "Unit" says so when asked.
vtkSmartPointer<vtkPolyData> InMetres(vtkPolyData* mesh, bool unitField)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(mesh);
  for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
  {
    double p[3];
    copy->GetPoint(i, p);
    copy->GetPoints()->SetPoint(i, p[0] / 1000.0, p[1] / 1000.0, p[2] / 1000.0);
  }
  // (Without the patch names: the legacy VTK reader refuses string field arrays.)
  copy->GetFieldData()->Initialize();
  if (unitField)
  {
    vtkNew<vtkStringArray> unit;
    unit->SetName("Unit");
    unit->InsertNextValue("m");
    copy->GetFieldData()->AddArray(unit);
  }
  return copy;
}

void ExpectMillimetres(const std::string& path, vtkPolyData* original)
{
  bender::StatedSpace stated;
  const auto back = bender::ReadMesh(path, stated);
  EXPECT_EQ(stated.unit, "m") << path;
  EXPECT_LT(BoundsDifference(back, original), 1e-4) << path;
}
} // namespace

TEST(MeshUnit, EveryFormatWrittenInMetresReadsBackInMillimetres)
{
  TempDir dir;
  const auto mesh = LabelledCylinder();
  // STL: the binary header, the ASCII solids' first endsolid line, one file per patch.
  bender::StlExportOptions stl;
  stl.unit = "m";
  for (const auto mode :
    { bender::StlPatchMode::Single, bender::StlPatchMode::Solids, bender::StlPatchMode::Files })
  {
    stl.patches = mode;
    const std::string name = "v" + std::to_string(static_cast<int>(mode)) + ".stl";
    for (const std::string& written : bender::ExportStl(mesh, dir / name, stl))
    {
      bender::StatedSpace stated;
      const auto back = bender::ReadMesh(written, stated);
      EXPECT_EQ(stated.unit, "m") << written;
      double bounds[6];
      back->GetBounds(bounds);
      EXPECT_NEAR(bounds[1], bender_test::Offset + 1.0, 1e-4) << written; // not 0.101
    }
  }
  // The ASCII STL of the whole surface states it on its "solid" line.
  bender::MeshWriteOptions ascii;
  ascii.stlEncoding = bender::StlEncoding::Ascii;
  ascii.header = MetresHeader;
  bender::WriteMesh(InMetres(mesh, false), dir / "ascii.stl", ascii);
  ExpectMillimetres(dir / "ascii.stl", mesh);
  // The header as a comment or title line: OBJ, PLY, legacy VTK, OFF.
  bender::MeshWriteOptions header;
  header.header = MetresHeader;
  for (const char* name : { "v.obj", "v.ply", "v.vtk", "v.off" })
  {
    bender::WriteMesh(InMetres(mesh, false), dir / name, header);
    ExpectMillimetres(dir / name, mesh);
  }
  // VTK XML polydata: the field data, which then says millimetres.
  bender::WriteMesh(InMetres(mesh, true), dir / "v.vtp");
  ExpectMillimetres(dir / "v.vtp", mesh);
  const auto read = bender::ReadMesh(dir / "v.vtp"); // holds the array read below
  vtkStringArray* field =
    vtkStringArray::SafeDownCast(read->GetFieldData()->GetAbstractArray("Unit"));
  ASSERT_NE(field, nullptr);
  EXPECT_EQ(field->GetValue(0), "mm");
  // TetGen: the first comment line.
  for (const auto& [name, format] : { std::pair{ "v.smesh", bender::TetgenFormat::Smesh },
         std::pair{ "v.poly", bender::TetgenFormat::Poly } })
  {
    std::string problem;
    ASSERT_TRUE(bender::TetgenFile(
      mesh, dir / name, format, bender::ExportTransform(bender::StlFrame::LPS, "m"), nullptr)
                  .produce(dir / name, problem))
      << problem;
    ExpectMillimetres(dir / name, mesh);
    EXPECT_EQ(bender::ReadMesh(dir / name)->GetNumberOfPolys(), mesh->GetNumberOfPolys());
  }
}

TEST(MeshUnit, MillimetresAndFilesWithoutAUnitAreReadAsTheyAre)
{
  TempDir dir;
  const auto mesh = LabelledCylinder();
  bender::MeshWriteOptions header;
  header.header = "bender export: frame LPS, unit mm";
  bender::WriteMesh(mesh, dir / "mm.stl", header);
  bender::WriteMesh(mesh, dir / "plain.obj");
  // A user's comment that names no unit of Bender's.
  header.header = "made by hand, unit m";
  bender::WriteMesh(mesh, dir / "other.off", header);
  for (const auto& [name, stated] :
    { std::pair{ "mm.stl", "mm" }, std::pair{ "plain.obj", "" }, std::pair{ "other.off", "" } })
  {
    bender::StatedSpace space;
    const auto back = bender::ReadMesh(dir / name, space);
    EXPECT_EQ(space.unit, stated) << name;
    EXPECT_EQ(space.frame, std::string(name) == "mm.stl" ? "LPS" : "") << name;
    EXPECT_LT(BoundsDifference(back, mesh), 1e-4) << name;
  }
}
