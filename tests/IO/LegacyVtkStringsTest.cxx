// String arrays in legacy VTK files: the layout vtkDataWriter gives a vtkStringArray (Bender's
// PatchNames/PatchTypes field data) is read back, ASCII and binary, and every malformed form of
// it is refused in one line before vtkDataReader sees it.

#include "InputValidation.h"
#include "MeshIO.h"
#include "PatchLabels.h"

#include "IOTestUtilities.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using bender::PatchLabel;
using bender::PatchType;
using bender::io_detail::CheckLegacyVtk;
using bender_test::ReadText;
using bender_test::TempDir;
using bender_test::WriteText;

namespace
{

/// Two triangles of a square: the wall (id 1) and an inlet (id 3; id 2 has no cell, so its
/// name is the empty string the table writes for a gap).
vtkSmartPointer<vtkPolyData> LabelledSquare()
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(1, 1, 0);
  points->InsertNextPoint(0, 1, 0);
  vtkNew<vtkCellArray> polys;
  const vtkIdType a[3] = { 0, 1, 2 }, b[3] = { 0, 2, 3 };
  polys->InsertNextCell(3, a);
  polys->InsertNextCell(3, b);
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  bender::WritePatchLabels(mesh,
    { 1, 3 },
    { PatchLabel{ 1, "wall", PatchType::Wall }, PatchLabel{ 3, "inlet", PatchType::Inlet } });
  return mesh;
}

std::string WriteWithVtk(vtkPolyData* mesh, const std::string& path, bool binary)
{
  vtkNew<vtkPolyDataWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileName(path.c_str());
  if (binary)
  {
    writer->SetFileTypeToBinary();
  }
  EXPECT_EQ(writer->Write(), 1) << path;
  return ReadText(path);
}

std::string Problem(const std::string& bytes)
{
  std::string problem;
  EXPECT_FALSE(CheckLegacyVtk(bytes, problem)) << "accepted:\n" << bytes;
  EXPECT_EQ(problem.find('\n'), std::string::npos) << problem;
  return problem;
}

const std::string Head = "# vtk DataFile Version 5.1\nt\nASCII\nDATASET POLYDATA\n"
                         "POINTS 3 float\n0 0 0 1 0 0 0 1 0\n";
const std::string BinaryHead = "# vtk DataFile Version 5.1\nt\nBINARY\nDATASET POLYDATA\n"
                               "POINTS 0 float\n\n";

} // namespace

TEST(LegacyVtkStrings, ALabelledSurfaceWrittenByVtkIsReadBackWithItsTable)
{
  TempDir dir;
  const vtkSmartPointer<vtkPolyData> mesh = LabelledSquare();
  const std::vector<PatchLabel> table = bender::ReadPatchLabels(mesh);
  ASSERT_EQ(table.size(), 2u);
  for (const bool binary : { false, true })
  {
    const std::string path = dir / (binary ? "binary.vtk" : "ascii.vtk");
    const std::string bytes = WriteWithVtk(mesh, path, binary);
    ASSERT_NE(bytes.find(" string\n"), std::string::npos) << "no string array in " << path;
    std::string problem;
    EXPECT_TRUE(CheckLegacyVtk(bytes, problem)) << path << ": " << problem;
    const vtkSmartPointer<vtkPolyData> back = bender::ReadMesh(path);
    ASSERT_EQ(back->GetNumberOfCells(), mesh->GetNumberOfCells()) << path;
    const std::vector<PatchLabel> read = bender::ReadPatchLabels(back);
    ASSERT_EQ(read.size(), table.size()) << path;
    for (std::size_t k = 0; k < table.size(); ++k)
    {
      EXPECT_EQ(read[k].id, table[k].id) << path;
      EXPECT_EQ(read[k].name, table[k].name) << path;
      EXPECT_EQ(read[k].type, table[k].type) << path;
    }
    EXPECT_EQ(bender::CellPatchIds(back), bender::CellPatchIds(mesh)) << path;
  }
}

TEST(LegacyVtkStrings, AnyStringVtkWritesIsAcceptedAndReadBackAsWritten)
{
  // Blanks, '%', non-ASCII bytes and the empty string: vtkDataWriter escapes them in ASCII.
  TempDir dir;
  const std::vector<std::string> values = {
    "", "two words", "100%", "caf\xc3\xa9", "a\tb", std::string(300, 'x')
  };
  const vtkSmartPointer<vtkPolyData> mesh = LabelledSquare();
  vtkNew<vtkStringArray> notes;
  notes->SetName("Notes");
  for (const std::string& value : values)
  {
    notes->InsertNextValue(value);
  }
  mesh->GetFieldData()->AddArray(notes);
  for (const bool binary : { false, true })
  {
    const std::string path = dir / (binary ? "binary.vtk" : "ascii.vtk");
    const std::string bytes = WriteWithVtk(mesh, path, binary);
    std::string problem;
    EXPECT_TRUE(CheckLegacyVtk(bytes, problem)) << path << ": " << problem;
    const vtkSmartPointer<vtkPolyData> back = bender::ReadMesh(path);
    auto* read = vtkStringArray::SafeDownCast(back->GetFieldData()->GetAbstractArray("Notes"));
    ASSERT_NE(read, nullptr) << path;
    ASSERT_EQ(read->GetNumberOfValues(), static_cast<vtkIdType>(values.size())) << path;
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      EXPECT_EQ(read->GetValue(static_cast<vtkIdType>(k)), values[k]) << path << " value " << k;
    }
  }
}

TEST(LegacyVtkStrings, MalformedAsciiStringsAreRefusedInOneLine)
{
  const std::string field = Head + "FIELD FieldData 1\nNames 1 2 string\n";
  // vtkDataReader decodes "%XX" without checking that two characters follow.
  EXPECT_NE(Problem(field + "wall\n%\n").find("'%' that is not followed by two hex digits"),
    std::string::npos);
  EXPECT_NE(
    Problem(field + "%zz\nwall\n").find("not followed by two hex digits"), std::string::npos);
  EXPECT_NE(Problem(field + "wall\n").find("string 2 of 2 is missing"), std::string::npos);
  EXPECT_NE(
    Problem(field + "wall\n" + std::string(5000, 'x') + "\n").find("is longer than 4096 bytes"),
    std::string::npos);
  EXPECT_NE(Problem(field + std::string("wa\0ll\nx\n", 8)).find("NUL byte"), std::string::npos);
  EXPECT_NE(Problem(Head + "FIELD FieldData 1\nNames 1 1 string trailing\nwall\n")
              .find("at the end of a keyword line"),
    std::string::npos);
  // Strings only where VTK can take them: a FIELD array, not SCALARS.
  EXPECT_NE(Problem(Head + "POINT_DATA 3\nSCALARS s string 1\nLOOKUP_TABLE default\na\nb\nc\n")
              .find("unsupported data type \"string\" for SCALARS"),
    std::string::npos);
  // A cell FIELD still needs one tuple per cell.
  EXPECT_NE(Problem(Head +
              "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n"
              "0 1 2\nCELL_DATA 1\nFIELD FieldData 1\nNames 1 2 string\na\nb\n")
              .find("FIELD array of 2 tuples, expected 1"),
    std::string::npos);
}

TEST(LegacyVtkStrings, MalformedBinaryStringsAreRefusedInOneLine)
{
  const std::string field = BinaryHead + "FIELD FieldData 1\nNames 1 2 string\n";
  // One-byte lengths (top bits 11): "wall" then a string announcing 9 bytes with 3 left.
  EXPECT_NE(Problem(field + "\xc4wall\xc9" + "abc").find("announces 9 bytes, the file has 3"),
    std::string::npos);
  // An eight-byte length (top bits 00) of 2^40: vtkDataReader would allocate it.
  EXPECT_NE(Problem(field + "\xc4wall" + std::string("\x00\x00\x01\x00\x00\x00\x00\x00", 8))
              .find("(at most 4096)"),
    std::string::npos);
  // A four-byte length (top bits 01) cut by the end of the file.
  EXPECT_NE(Problem(field + "\xc4wall" + std::string("\x40\x00", 2))
              .find("needs 4 bytes, the file has 2 left"),
    std::string::npos);
  EXPECT_NE(Problem(field + "\xc4wall").find("string 2 of 2 is missing"), std::string::npos);
  // Two-byte lengths (top bits 10) are read as written: 0x8003 is 3 bytes.
  std::string problem;
  EXPECT_TRUE(CheckLegacyVtk(field + "\xc4wall" + std::string("\x80\x03", 2) + "abc\n", problem))
    << problem;
}

TEST(LegacyVtkStrings, ReadMeshNamesTheFileAndTheProblem)
{
  TempDir dir;
  const std::string path = dir / "bad-escape.vtk";
  WriteText(path, Head + "FIELD FieldData 1\nPatchNames 1 1 string\n%\n");
  try
  {
    bender::ReadMesh(path);
    ADD_FAILURE() << path << " was accepted";
  }
  catch (const bender::MeshIOError& e)
  {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("bad-escape.vtk: ", 0), 0u) << message;
    EXPECT_NE(message.find("not followed by two hex digits"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}
