// Regression tests for issue 13 (input that cannot hurt): each input below crashed, hung or
// was silently accepted before the pre-validators in modules/IO/InputValidation.cxx and
// PlyValidation.cxx. Every reader must answer one line naming the file.

#include "InputValidation.h"
#include "MeshIO.h"
#include "PlyValidation.h"

#include "IOTestUtilities.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;
using bender::MeshIOError;
using bender::ReadMesh;
using bender::WriteMesh;
using bender_test::ReadText;
using bender_test::TempDir;
using bender_test::TestData;
using bender_test::WriteText;

namespace
{

std::string ReadError(const std::string& path)
{
  try
  {
    ReadMesh(path);
  }
  catch (const MeshIOError& e)
  {
    return e.what();
  }
  ADD_FAILURE() << path << " was accepted";
  return {};
}

void ExpectRefused(const std::string& path, const std::string& expected)
{
  SCOPED_TRACE(path);
  ::testing::internal::CaptureStderr();
  const std::string message = ReadError(path);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(message.rfind(fs::path(path).filename().string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(expected), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
  EXPECT_EQ(err, "");
}

vtkSmartPointer<vtkPolyData> Triangle(double scale = 1.0)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(scale, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  vtkNew<vtkCellArray> polys;
  const vtkIdType t[3] = { 0, 1, 2 };
  polys->InsertNextCell(3, t);
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

const char* const LegacyHead = "# vtk DataFile Version 3.0\ntest\nASCII\nDATASET POLYDATA\n"
                               "POINTS 3 float\n0 0 0 1 0 0 0 1 0\n";
const char* const Legacy51Head = "# vtk DataFile Version 5.1\ntest\nASCII\nDATASET POLYDATA\n"
                                 "POINTS 3 float\n0 0 0 1 0 0 0 1 0\n";

} // namespace

// Before: Tidy() replaced the bare path by the identical display name and found it again at
// the same spot, forever.
TEST(InputValidation, BareFileNameInAVtkErrorDoesNotHang)
{
  TempDir dir;
  WriteText(
    dir / "truncated.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0");
  const fs::path previous = fs::current_path();
  fs::current_path(dir.path());
  const std::string message = ReadError("truncated.stl");
  fs::current_path(previous);
  EXPECT_EQ(message.rfind("truncated.stl: ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// Before: SIGSEGV inside vtkDataReader.
TEST(InputValidation, LegacyVtkShortOrNonNumericPolygons)
{
  TempDir dir;
  WriteText(dir / "short.vtk", std::string(LegacyHead) + "POLYGONS 2 8\n3 0 1 2\n3 0\n");
  ExpectRefused(dir / "short.vtk", "truncated data");
  WriteText(dir / "word.vtk", std::string(LegacyHead) + "POLYGONS 1 4\n3 0 x 2\n");
  ExpectRefused(dir / "word.vtk", "\"x\" is not an integer");
  WriteText(dir / "count.vtk", std::string(LegacyHead) + "POLYGONS 1 4\n9 0 1 2\n");
  ExpectRefused(dir / "count.vtk", "cell 0 has 9 points");
  WriteText(
    dir / "huge.vtk", std::string(LegacyHead) + "POLYGONS 1000000000 4000000000\n3 0 1 2\n");
  ExpectRefused(dir / "huge.vtk", "truncated data");
  WriteText(dir / "points.vtk",
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0\n");
  ExpectRefused(dir / "points.vtk", "truncated data");
  WriteText(dir / "keyword.vtk", std::string(LegacyHead) + "POLYGONZ 1 4\n3 0 1 2\n");
  ExpectRefused(dir / "keyword.vtk", "unknown keyword \"POLYGONZ\"");
}

// Before: out-of-bounds read in the triangle collection (offsets out of range), or triangles
// from stray memory (decreasing offsets).
TEST(InputValidation, LegacyVtk51OffsetsOutOfRangeOrDecreasing)
{
  TempDir dir;
  const std::string conn = "CONNECTIVITY vtktypeint64\n0 1 2\n";
  WriteText(dir / "range.vtk",
    std::string(Legacy51Head) + "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 30\n" + conn);
  ExpectRefused(dir / "range.vtk", "offset 1 is 30");
  WriteText(dir / "down.vtk",
    std::string(Legacy51Head) + "POLYGONS 3 3\nOFFSETS vtktypeint64\n0 3 1\n" + conn);
  ExpectRefused(dir / "down.vtk", "must not decrease");
  WriteText(dir / "start.vtk",
    std::string(Legacy51Head) + "POLYGONS 2 3\nOFFSETS vtktypeint64\n1 3\n" + conn);
  ExpectRefused(dir / "start.vtk", "must be 0");
  WriteText(dir / "id.vtk",
    std::string(Legacy51Head) +
      "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1 5\n");
  ExpectRefused(dir / "id.vtk", "refers to point 5");
  // The same file with valid offsets reads.
  WriteText(dir / "good.vtk",
    std::string(Legacy51Head) + "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\n" + conn);
  EXPECT_EQ(ReadMesh(dir / "good.vtk")->GetNumberOfPolys(), 1);
}

// Found by fuzz_mesh_vtk: "Version 5|||.1" passed as 5.1 while VTK read it as an older version
// and crashed in vtkDataReader::ReadString. The version must be exactly "major.minor".
TEST(InputValidation, LegacyVtkVersionMustBeExactlyMajorDotMinor)
{
  TempDir dir;
  const std::string body = std::string(Legacy51Head).substr(std::string(Legacy51Head).find('\n')) +
    "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1 2\n";
  for (const char* version : { "5|||.1", "5.1x", "5 .1", "5.", ".1" })
  {
    WriteText(dir / "version.vtk", std::string("# vtk DataFile Version ") + version + body);
    ExpectRefused(dir / "version.vtk", "is not 1.0 to 5.1");
  }
  WriteText(dir / "crlf.vtk", "# vtk DataFile Version 5.1\r" + body);
  EXPECT_EQ(ReadMesh(dir / "crlf.vtk")->GetNumberOfPolys(), 1);
}

// Binary legacy files written by the project: every prefix is refused without a crash.
TEST(InputValidation, LegacyVtkBinaryPrefixesAreRefused)
{
  TempDir dir;
  WriteMesh(Triangle(), dir / "whole.vtk");
  const std::string bytes = ReadText(dir / "whole.vtk");
  std::string problem;
  ASSERT_TRUE(bender::io_detail::CheckLegacyVtk(bytes, problem)) << problem;
  for (std::size_t n = 0; n + 1 < bytes.size(); ++n)
  {
    // Trailing blank lines are not data: a prefix that only lacks them may pass.
    if (bytes.find_first_not_of(" \n", n) == std::string::npos)
    {
      break;
    }
    const std::string prefix = bytes.substr(0, n);
    if (bender::io_detail::CheckLegacyVtk(prefix, problem))
    {
      // Sections are not counted: a prefix that ends between two sections is a valid file
      // with fewer sections, and must read consistently (all 3 points, at most the triangle).
      WriteText(dir / "prefix.vtk", prefix);
      const auto mesh = ReadMesh(dir / "prefix.vtk");
      EXPECT_EQ(mesh->GetNumberOfPoints(), 3) << n;
      EXPECT_LE(mesh->GetNumberOfPolys(), 1) << n;
    }
  }
}

// Before: the validator read tokens across lines; vtkPLY reads one record per line of at most
// 4096 bytes and crashed (SIGSEGV, invalid free, abort).
TEST(InputValidation, AsciiPlyRecordsMustBeOneLineEach)
{
  TempDir dir;
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n";
  WriteText(dir / "split.ply", header + "0 0\n0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectRefused(dir / "split.ply", "one record per line");
  WriteText(dir / "joined.ply", header + "0 0 0 1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectRefused(dir / "joined.ply", "one record per line");
  WriteText(dir / "long.ply",
    "ply\nformat ascii 1.0\ncomment " + std::string(5000, 'c') +
      "\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n");
  ExpectRefused(dir / "long.ply", "longer than 4000 bytes");
  WriteText(
    dir / "spaces.ply", header + "0 0 0" + std::string(5000, ' ') + "\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectRefused(dir / "spaces.ply", "longer than 4000 bytes");
  WriteText(dir / "good.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(ReadMesh(dir / "good.ply")->GetNumberOfPolys(), 1);
}

// Before: SIGFPE in vtkXMLReader (a damaged header_type), 7.8 GB of memory for a component
// count of 10^9.
TEST(InputValidation, VtpDamagedHeaderTypeAndHugeComponentCount)
{
  TempDir dir;
  WriteMesh(Triangle(), dir / "ok.vtp");
  const std::string bytes = ReadText(dir / "ok.vtp");
  const std::size_t at = bytes.find("header_type=\"UInt64\"");
  ASSERT_NE(at, std::string::npos);
  std::string damaged = bytes;
  damaged.erase(at + 18, 1); // "UInt6"
  WriteText(dir / "damaged.vtp", damaged);
  ExpectRefused(dir / "damaged.vtp", "header_type \"UInt6\"");

  const std::string huge =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
    "byte_order=\"LittleEndian\">\n<PolyData>\n<Piece NumberOfPoints=\"3\" "
    "NumberOfPolys=\"0\">\n<PointData>\n<DataArray type=\"Float64\" Name=\"a\" "
    "NumberOfComponents=\"1000000000\" format=\"ascii\">0</DataArray>\n"
    "</PointData>\n<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" "
    "format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>\n</Points>\n</Piece>\n"
    "</PolyData>\n</VTKFile>\n";
  WriteText(dir / "huge.vtp", huge);
  ExpectRefused(dir / "huge.vtp", "NumberOfComponents=\"1000000000\"");

  WriteText(dir / "cut.vtp", bytes.substr(0, bytes.size() - 30));
  ExpectRefused(dir / "cut.vtp", "truncated VTK XML file");
}

// Before: a binary STL longer than its count was accepted and its extra bytes read as
// triangles; a 2 GB file took minutes and gigabytes.
TEST(InputValidation, OversizedMeshFilesAreRefusedUpFront)
{
  TempDir dir;
  std::string stl(84 + 50 + 5000, '\0');
  stl[80] = 1;
  WriteText(dir / "padded.stl", stl);
  ExpectRefused(dir / "padded.stl", "longer than its header says");

  for (const char* name : { "zeros.stl", "zeros.off", "zeros.obj", "zeros.vtk", "zeros.ply" })
  {
    const std::string path = dir / name;
    {
      std::ofstream out(path, std::ios::binary);
    }
    fs::resize_file(path, (std::uintmax_t(2) << 30)); // sparse: no disk space used
    ExpectRefused(path, "limit for mesh files");
  }
}

// Before: 1e39 passed the double check and became inf in the single-precision formats. One
// range rule for every format (CoordinateRange.h): the double-precision ones refuse it too.
TEST(InputValidation, CoordinatesBeyondFloatRangeAreNotWrittenAsInf)
{
  TempDir dir;
  const auto mesh = Triangle(1e39);
  for (const char* name : { "big.stl", "big.ply", "big.obj", "big.vtp", "big.vtk", "big.off" })
  {
    try
    {
      WriteMesh(mesh, dir / name);
      ADD_FAILURE() << name << " written";
    }
    catch (const MeshIOError& e)
    {
      EXPECT_NE(std::string(e.what()).find("single-precision range"), std::string::npos)
        << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / name));
  }
}

TEST(InputValidation, MessageCleanerGivesOneSafeLine)
{
  using bender::io_detail::CleanMessage;
  EXPECT_EQ(CleanMessage("ERROR: In ./IO/XML/vtkXMLReader.cxx, line 521\n"
                         "vtkXMLPolyDataReader (0x55d0c3a0): Error parsing XML\n\n"),
    "Error parsing XML");
  EXPECT_EQ(
    CleanMessage("\x1b[1;31mITK ERROR: MetaImageIO(0x55d0c3a0): File cannot be read\x1b[0m"),
    "File cannot be read");
  EXPECT_EQ(CleanMessage("itk::ERROR: NrrdImageIO(0x1234): ReadImageInformation: "
                         "[nrrd] nrrdLoad: trouble\n[nrrd] _nrrdRead: bad size"),
    "bad size");
  EXPECT_EQ(CleanMessage("a\x07"
                         "b\x1b]0;title\x07"
                         "c\x7f"),
    "a\\x07bc\\x7f");
  EXPECT_EQ(CleanMessage(""), "unknown error");
  const std::string longText(1000, 'x');
  EXPECT_EQ(CleanMessage(longText).size(), 200u);
  EXPECT_EQ(bender::io_detail::QuoteBytes(std::string("ab\0\xff", 4)), "ab\\x00\\xff");
}

// Truncation: every prefix of every valid fixture is refused with one line, or (for formats
// whose sections or records are not counted: OBJ, ASCII STL, legacy VTK sections) read
// consistently: no more points than the whole file (ReadMesh checks coordinates and ids). For
// the counted formats (binary STL, PLY, VTP, OFF) an accepted prefix must give the same mesh
// (only optional trailing columns, such as an OFF face colour, may be cut).
TEST(InputValidation, EveryPrefixOfEveryFixtureIsRefusedOrConsistent)
{
  TempDir dir;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  const double corners[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (const auto& c : corners)
  {
    points->InsertNextPoint(c);
  }
  const vtkIdType faces[4][3] = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
  for (const auto& f : faces)
  {
    polys->InsertNextCell(3, f);
  }
  vtkNew<vtkPolyData> tetra;
  tetra->SetPoints(points);
  tetra->SetPolys(polys);

  struct Fixture
  {
    std::string name;
    bool counted;
  };
  std::vector<Fixture> fixtures = { { "w.stl", true },
    { "w.ply", true },
    { "w.vtp", true },
    { "w.off", true },
    { "w.obj", false },
    { "w.vtk", false } };
  for (const Fixture& f : fixtures)
  {
    WriteMesh(tetra, dir / f.name);
  }
  bender::MeshWriteOptions ascii;
  ascii.stlEncoding = bender::StlEncoding::Ascii;
  WriteMesh(tetra, dir / "a.stl", ascii);
  fixtures.push_back({ "a.stl", false });
  for (const char* data :
    { "io/tetra_ascii.stl", "io/cube_commented.off", "io/tetra_crlf_coloured.off" })
  {
    const std::string name = fs::path(data).filename().string();
    fs::copy_file(TestData(data), dir / name);
    fixtures.push_back({ name, fs::path(name).extension() == ".off" });
  }
  for (const Fixture& f : fixtures)
  {
    SCOPED_TRACE(f.name);
    const std::string bytes = ReadText(dir / f.name);
    const auto whole = ReadMesh(dir / f.name);
    const vtkIdType wholePoints = whole->GetNumberOfPoints();
    const vtkIdType wholePolys = whole->GetNumberOfPolys();
    const std::string ext = fs::path(f.name).extension().string();
    const std::size_t last = bytes.find_last_not_of(" \t\r\n");
    for (std::size_t n = 0; n < bytes.size(); ++n)
    {
      const std::string path = dir / ("prefix" + ext);
      WriteText(path, bytes.substr(0, n));
      try
      {
        const auto mesh = ReadMesh(path);
        EXPECT_LE(mesh->GetNumberOfPoints(), wholePoints) << n;
        if (f.counted && n <= last)
        {
          // Only optional trailing columns (an OFF face colour) may be missing: the same mesh.
          EXPECT_EQ(mesh->GetNumberOfPoints(), wholePoints) << n;
          EXPECT_EQ(mesh->GetNumberOfPolys(), wholePolys) << n;
        }
      }
      catch (const MeshIOError& e)
      {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind("prefix" + ext + ": ", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      }
    }
  }
}

// Found by fuzz_mesh_obj: vtkOBJReader reads normals by index without checking (SEGV).
TEST(InputValidation, ObjIndicesOutOfRangeAreRefused)
{
  TempDir dir;
  WriteText(dir / "normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n");
  ExpectRefused(dir / "normals.obj", "normal index \"1\" out of range (the file has 0)");
  WriteText(dir / "tcoord.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/2 2/1 3/1\n");
  ExpectRefused(dir / "tcoord.obj", "texture coordinate index \"2\" out of range");
  WriteText(dir / "vertex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  ExpectRefused(dir / "vertex.obj", "vertex index \"4\" out of range");
  WriteText(dir / "good.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  EXPECT_EQ(ReadMesh(dir / "good.obj")->GetNumberOfPolys(), 1);
}

// Found by fuzz_mesh_obj on CI: "f 1/ 2" (an empty texture index after '/') in a file without
// texture coordinates made vtkOBJReader index an empty array (SEGV).
TEST(InputValidation, ObjMalformedOrMixedIndexFormsAreRefused)
{
  TempDir dir;
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n";
  for (const char* face : { "f 1/ 1",
         "f 1/ 2/ 3/",
         "f 1 2 3/",
         "f 1// 2// 3//",
         "f 1/1/ 2 3",
         "f 1/1/1/1 2 3",
         "f /1 2 3",
         "l 1/ 2" })
  {
    WriteText(dir / "bad.obj", head + face + "\n");
    ExpectRefused(dir / "bad.obj", "malformed element");
  }
  for (const char* face : { "f 1/1 2 3", "f 1 2//1 3", "f 1/1/1 2/1 3/1" })
  {
    WriteText(dir / "mixed.obj", head + face + "\n");
    ExpectRefused(dir / "mixed.obj", "mixes index forms");
  }
  for (const char* face : { "f 1 2 3", "f 1/1 2/2 3/3", "f 1//1 2//1 3//1", "f 1/1/1 2/2/1 3/3/1" })
  {
    WriteText(dir / "good.obj", head + face + "\n");
    EXPECT_EQ(ReadMesh(dir / "good.obj")->GetNumberOfPolys(), 1) << face;
  }
}

// Found by fuzz_mesh_stl: a malformed ASCII facet made vtkSTLReader ask for 19 GB.
TEST(InputValidation, MalformedAsciiStlIsRefused)
{
  TempDir dir;
  WriteText(dir / "broken.stl",
    "solid broken\n  facet normal 0 0 \x89\x89\x89 1\n    ou\x16"
    "er l 0\n"
    "      vertex 1 0\n");
  ExpectRefused(dir / "broken.stl", "expected \"facet normal x y z\"");
  WriteText(dir / "cut.stl",
    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
    "vertex 0 1 0\nendloop\nendfacet\n");
  ExpectRefused(dir / "cut.stl", "truncated ASCII STL (no \"endsolid\" after 1 facets)");
  WriteText(dir / "good.stl",
    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
    "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
  EXPECT_EQ(ReadMesh(dir / "good.stl")->GetNumberOfPolys(), 1);
}

// Found by fuzz_mesh_ply: a vertical tab in a header line made vtkPLY see another element
// list than a stream reader (null dereference in find_element).
TEST(InputValidation, PlyHeaderControlBytesAreRefused)
{
  TempDir dir;
  WriteText(dir / "vt.ply",
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
    "property float y\nproperty float z\x0b"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectRefused(dir / "vt.ply", "control or non-ASCII byte in the header");
}

// Found by fuzz_mesh_ply: a blank line between two property lines of the header crashed
// vtkPLY (null element in find_element).
TEST(InputValidation, PlyHeaderBlankLinesAreRefused)
{
  TempDir dir;
  WriteText(dir / "blank.ply",
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectRefused(dir / "blank.ply", "PLY header line 6: blank line in the header");
}

// Found by fuzz_mesh_ply: an element without properties (with records or none) made vtkPLY
// free an invalid pointer when closing the file.
TEST(InputValidation, PlyElementsWithoutPropertiesAreRefused)
{
  TempDir dir;
  WriteText(dir / "empty.ply",
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement extra 4\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectRefused(dir / "empty.ply", "PLY element \"extra\" (4 records) has no properties");
  WriteText(dir / "none.ply",
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement extra 0\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ExpectRefused(dir / "none.ply", "PLY element \"extra\" (0 records) has no properties");
}

// Found by fuzz_mesh_ply: a NUL byte at the end of the last ASCII record made vtkPLYReader
// free a face's index list twice.
TEST(InputValidation, PlyAsciiDataWithANulByteIsRefused)
{
  TempDir dir;
  std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                     "property float y\nproperty float z\nelement face 1\n"
                     "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                     "3 0 1 2";
  text.push_back('\0');
  WriteText(dir / "nul.ply", text);
  ExpectRefused(dir / "nul.ply", "ASCII PLY data holds a NUL byte at offset");
}

// Found by fuzz_mesh_vtp: VTK reads an array with an offset attribute as appended even when its
// format attribute is misspelt, so its block headers must be checked too.
TEST(InputValidation, VtpArraysWithAnOffsetAreCheckedWhateverTheirFormat)
{
  TempDir dir;
  WriteMesh(Triangle(), dir / "ok.vtp");
  std::string bytes = ReadText(dir / "ok.vtp");
  const std::size_t format = bytes.find("format=\"appended\"");
  ASSERT_NE(format, std::string::npos);
  bytes.replace(format, 6, "formAt");
  const std::size_t data = bytes.find('_', bytes.find("<AppendedData")) + 1;
  ASSERT_LT(data + 16, bytes.size());
  bytes[data + 8 + 7] = 0x73; // the first block's size word (UInt64, little endian): top byte
  WriteText(dir / "formAt.vtp", bytes);
  ExpectRefused(dir / "formAt.vtp", "compressed block header at offset 0");
}

// Found by fuzz_mesh_vtp: a compressed block header announcing a 2^62-byte block made
// vtkXMLDataParser allocate it.
TEST(InputValidation, VtpCompressedBlockHeadersAreBounded)
{
  TempDir dir;
  WriteMesh(Triangle(), dir / "ok.vtp");
  std::string bytes = ReadText(dir / "ok.vtp");
  const std::size_t data = bytes.find('_', bytes.find("<AppendedData")) + 1;
  ASSERT_LT(data + 16, bytes.size());
  bytes[data + 8 + 7] = 0x73; // block size word (UInt64, little endian): top byte
  WriteText(dir / "block.vtp", bytes);
  ExpectRefused(dir / "block.vtp", "compressed block header at offset 0");
}

namespace
{

// The PLY whitelist (PlyValidation.cxx) on bytes: refused with the expected words, or accepted.
void ExpectPly(const std::string& bytes, const std::string& expected)
{
  SCOPED_TRACE(bytes.substr(0, 300));
  std::string problem;
  const bool ok = bender::io_detail::CheckPlyBytes(bytes, problem);
  if (expected.empty())
  {
    EXPECT_TRUE(ok) << problem;
    return;
  }
  EXPECT_FALSE(ok);
  EXPECT_NE(problem.find(expected), std::string::npos) << problem;
  EXPECT_EQ(problem.find('\n'), std::string::npos) << problem;
}

const char* const PlyVertices = "element vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\n";
const char* const PlyFace = "element face 1\nproperty list uchar int vertex_indices\n";
const char* const PlyRecords = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

std::string AsciiPly(const std::string& header, const std::string& records = PlyRecords)
{
  return "ply\nformat ascii 1.0\n" + header + "end_header\n" + records;
}

// Little-endian bytes of an integer.
std::string Le(std::uint32_t value, int size)
{
  std::string bytes;
  for (int b = 0; b < size; ++b)
  {
    bytes.push_back(static_cast<char>((value >> (8 * b)) & 0xff));
  }
  return bytes;
}

std::string LeFloat(float value)
{
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, 4);
  return Le(bits, 4);
}

} // namespace

// The header is a whitelist of vtkPLY's grammar: each line exactly its words (vtkPLY reads
// missing words from an uninitialised array), known types, version 1.0, nothing twice.
TEST(InputValidation, PlyHeaderGrammarIsAWhitelist)
{
  const std::string v = PlyVertices;
  const std::string f = PlyFace;
  ExpectPly(AsciiPly(v + f), "");
  ExpectPly(AsciiPly(v + "element face 1\nproperty list uchar int vertex_index\n"), "");
  ExpectPly("ply\nformat ascii 2.0\n" + v + f + "end_header\n" + PlyRecords,
    "expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
  ExpectPly("ply\nformat ascii\n" + v + f + "end_header\n" + PlyRecords, "1.0");
  ExpectPly("ply\nformat ascii 1.0\nformat ascii 1.0\n" + v + f + "end_header\n" + PlyRecords,
    "a second \"format\" line");
  ExpectPly("ply\n" + v + "format ascii 1.0\n" + f + "end_header\n" + PlyRecords,
    "element before the \"format\" line");
  ExpectPly("ply extra\nformat ascii 1.0\n" + v + f + "end_header\n" + PlyRecords,
    "the first line is not \"ply\"");
  ExpectPly(AsciiPly("element vertex\nproperty float x\nproperty float y\nproperty float z\n" + f),
    "expected \"element NAME COUNT\"");
  ExpectPly(AsciiPly("element vertex 3 4\nproperty float x\nproperty float y\n"
                     "property float z\n" +
              f),
    "expected \"element NAME COUNT\"");
  ExpectPly(AsciiPly("element vertex -3\nproperty float x\nproperty float y\nproperty float z\n"),
    "element count \"-3\"");
  ExpectPly(AsciiPly("element vertex 3000000000\nproperty float x\nproperty float y\n"
                     "property float z\n"),
    "element count \"3000000000\"");
  ExpectPly(AsciiPly(v + "property float\n" + f), "expected \"property TYPE NAME\"");
  ExpectPly(AsciiPly(v + "property float w extra\n" + f), "expected \"property TYPE NAME\"");
  ExpectPly(AsciiPly(v + "element face 1\nproperty list uchar vertex_indices\n"),
    "expected \"property list COUNT_TYPE ITEM_TYPE NAME\"");
  ExpectPly(AsciiPly(v + "property int64 w\n" + f), "unknown property type \"int64\"");
  ExpectPly(AsciiPly(v + "element face 1\nproperty list float int vertex_indices\n"),
    "unsupported list types \"float int\"");
  ExpectPly(AsciiPly(v + "property float x\n" + f), "a second property \"x\"");
  ExpectPly(AsciiPly(v + f + v), "a second element \"vertex\"");
  ExpectPly(AsciiPly(v + f + "weird line\n"), "unexpected \"weird\"");
  ExpectPly("ply\nformat ascii 1.0\n" + v + f + "end_header now\n" + PlyRecords,
    "words after \"end_header\"");
  // vtkPLY rewrites "vertex_index" in place as "vertex_indices" on every header line: as an
  // element name it swallowed the count.
  ExpectPly(AsciiPly("element vertex_indexes 3\nproperty float x\n" + v + f),
    "\"vertex_index\" is reserved for the face's index list");
  ExpectPly(AsciiPly("comment made from vertex_index data\n" + v + f), "");
}

// vtkPLYReader reads the vertex element as scalars and then the face element's one index list:
// anything else in those places would be read as something it is not.
TEST(InputValidation, PlyElementsAreWhatVtkPlyReaderReads)
{
  const std::string v = PlyVertices;
  const std::string f = PlyFace;
  ExpectPly(AsciiPly(f + v, "3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n"),
    "PLY face element before the vertex element");
  ExpectPly(
    AsciiPly(v + "element edge 1\nproperty int a\n" + f, "0 0 0\n1 0 0\n0 1 0\n5\n3 0 1 2\n"),
    "PLY element \"edge\" before the vertex and face elements");
  ExpectPly(
    AsciiPly(v + f + "element edge 1\nproperty int a\n", std::string(PlyRecords) + "5\n"), "");
  ExpectPly(
    AsciiPly(v + "property list uchar float n\n" + f, "0 0 0 1 0\n1 0 0 1 0\n0 1 0 1 0\n3 0 1 2\n"),
    "PLY vertex property \"n\" is a list");
  ExpectPly(AsciiPly(v + f + "property list uchar float texcoord\n",
              "0 0 0\n1 0 0\n0 1 0\n"
              "3 0 1 2 6 0 0 1 0 0 1\n"),
    "PLY face property \"texcoord\" is not supported");
  ExpectPly(AsciiPly(v + "element face 1\nproperty list uchar float vertex_indices\n"),
    "PLY face indices of a floating-point type");
  ExpectPly(AsciiPly(v + f + "property list uchar int vertex_index\n",
              "0 0 0\n1 0 0\n0 1 0\n"
              "3 0 1 2 3 0 1 2\n"),
    "with both \"vertex_indices\" and \"vertex_index\"");
  ExpectPly(AsciiPly(v + "element face 0\nproperty uchar red\n", "0 0 0\n1 0 0\n0 1 0\n"),
    "PLY face element without a \"vertex_indices\" list");
}

// Every ASCII record against its declared types, as vtkPLY splits lines (spaces and tabs only).
TEST(InputValidation, PlyAsciiRecordsMatchTheirTypes)
{
  const std::string v = PlyVertices;
  const std::string f = PlyFace;
  ExpectPly(AsciiPly(v + f, "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), "a face of 2 vertices (3 to 255");
  std::string zeros;
  for (int i = 0; i < 256; ++i)
  {
    zeros += " 0";
  }
  ExpectPly(AsciiPly(v + "element face 1\nproperty list ushort int vertex_indices\n",
              "0 0 0\n1 0 0\n0 1 0\n256" + zeros + "\n"),
    "a face of 256 vertices");
  ExpectPly(AsciiPly(v + f, "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n"), "\"2.5\" is not an integer");
  ExpectPly(AsciiPly(v + f, "0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n"), "vertex index -1 out of range");
  ExpectPly(AsciiPly(v + f, "0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n"), "\"x\" is not a number");
  ExpectPly(AsciiPly(v + "property uchar red\n" + f, "0 0 0 1\n1 0 0 2\n0 1 0 300\n3 0 1 2\n"),
    "\"300\" is out of range for \"red\"");
  // vtkPLY splits at spaces and tabs only: a vertical tab or form feed joins two values.
  ExpectPly(AsciiPly(v + f, "0 0 0\n1\v0 0 0\n0 1 0\n3 0 1 2\n"), "control or non-ASCII byte");
  ExpectPly(AsciiPly(v + f, "0 0 0\n1 0 0\n0 1 0\n3 0\f1 2\n"), "control or non-ASCII byte");
  ExpectPly(AsciiPly(v + f, "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n"), "");
  ExpectPly(AsciiPly(v + f, "0 0 0\n1 0\r0\n0 1 0\n3 0 1 2\n"), "carriage return inside the line");
  ExpectPly(AsciiPly(v + f, std::string(PlyRecords) + "\n  \n"), "");
  ExpectPly(AsciiPly(v + f, std::string(PlyRecords) + "3 0 1 2\n"), "data after the last record");
}

// Binary records: exactly as long as the header says, list counts bounded (an unsigned byte
// count of 200 is a count, not a negative number), indices in range.
TEST(InputValidation, PlyBinaryRecordsMatchTheirTypes)
{
  const std::string header = "ply\nformat binary_little_endian 1.0\n" + std::string(PlyVertices) +
    "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  std::string vertices;
  for (int i = 0; i < 3; ++i)
  {
    vertices += LeFloat(i == 1 ? 1.f : 0.f) + LeFloat(i == 2 ? 1.f : 0.f) + LeFloat(0.f);
  }
  const std::string face = Le(3, 1) + Le(0, 4) + Le(1, 4) + Le(2, 4);
  ExpectPly(header + vertices + face, "");
  ExpectPly(header + vertices + face + "x", "binary PLY with 1 bytes after the last record");
  ExpectPly(header + vertices + face.substr(0, 9), "truncated binary PLY");
  ExpectPly(header + vertices + Le(3, 1) + Le(0, 4) + Le(1, 4) + Le(0xffffffffu, 4),
    "vertex index 4294967295 out of range");
  ExpectPly(header + vertices + Le(2, 1) + Le(0, 4) + Le(1, 4), "a face of 2 vertices");
  std::string big;
  for (int i = 0; i < 200; ++i)
  {
    big += Le(static_cast<std::uint32_t>(i % 3), 4);
  }
  ExpectPly(header + vertices + Le(200, 1) + big, "");
  const std::string signedCount = "ply\nformat binary_little_endian 1.0\n" +
    std::string(PlyVertices) +
    "element face 1\nproperty list char int vertex_indices\nend_header\n";
  ExpectPly(signedCount + vertices + Le(0xff, 1), "negative list length");
}

// Files that pass the whitelist read with VTK ("vertex_index"); a refused one names the file.
TEST(InputValidation, PlyWhitelistedShapesRead)
{
  TempDir dir;
  WriteText(dir / "index.ply",
    AsciiPly(std::string(PlyVertices) + "element face 1\nproperty list uchar int vertex_index\n"));
  EXPECT_EQ(ReadMesh(dir / "index.ply")->GetNumberOfPolys(), 1);
  WriteText(dir / "texcoord.ply",
    AsciiPly(std::string(PlyVertices) + PlyFace + "property list uchar float texcoord\n",
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 6 0 0 1 0 0 1\n"));
  ExpectRefused(dir / "texcoord.ply", "PLY face property \"texcoord\" is not supported");
}

namespace
{

// A compressed (zlib, UInt64 headers) VTP of one triangle whose points' inline binary data is
// `points` (base64 of the block header, then of the compressed block).
std::string InlineBinaryVtp(const std::string& points)
{
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\" "
         "compressor=\"vtkZLibDataCompressor\">\n<PolyData>\n<Piece NumberOfPoints=\"4\" "
         "NumberOfPolys=\"4\">\n<Points>\n<DataArray type=\"Float64\" "
         "NumberOfComponents=\"3\" format=\"binary\">" +
    points +
    "</DataArray>\n</Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
    "format=\"binary\">AQAAAAAAAABgAAAAAAAAAGAAAAAAAAAAHQAAAAAAAAA=eJxjYIAAJijNyIAKYHxmNHEYH10fE5o8"
    "AANQABM=</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
    "format=\"binary\">AQAAAAAAAAAgAAAAAAAAACAAAAAAAAAAEwAAAAAAAAA=eJxjZoAANijNCaV5oDQAAgAAHw=="
    "</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
}

} // namespace

// Found by hand (the fuzzers' seeds had no inline binary arrays): the block header of a
// compressed inline binary array (base64) was not checked, and a forged block count made
// vtkXMLDataParser allocate 8 TB (std::bad_alloc, abort). Appended base64 blocks the same.
TEST(InputValidation, VtpInlineAndBase64CompressedHeadersAreChecked)
{
  TempDir dir;
  const std::string points = "AQAAAAAAAABgAAAAAAAAAGAAAAAAAAAAEgAAAAAAAAA=eJxjYMAHPtjjlSZCHgB4XQOO";
  WriteText(dir / "inline.vtp", InlineBinaryVtp(points));
  EXPECT_EQ(ReadMesh(dir / "inline.vtp")->GetNumberOfPolys(), 4);
  // 2^40 blocks of 64 KiB.
  WriteText(dir / "blocks.vtp",
    InlineBinaryVtp("AAAAAAABAAAAAAEAAAAAAAAAAQAAAAAACgAAAAAAAAA=eHh4eHh4eHh4eA=="));
  ExpectRefused(dir / "blocks.vtp",
    "compressed block header of an inline binary DataArray announces 1099511627776 blocks");
  WriteText(dir / "garbage.vtp", InlineBinaryVtp("AQAA*AAA"));
  ExpectRefused(dir / "garbage.vtp", "without a valid base64 compressed block header");

  // The same blocks appended as base64: offsets count base64 characters.
  const std::size_t at = points.find('=') + 1;
  const std::string appended = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" "
                               "version=\"1.0\" byte_order=\"LittleEndian\" "
                               "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
                               "<PolyData>\n<Piece NumberOfPoints=\"4\" NumberOfPolys=\"0\">\n"
                               "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
                               "format=\"appended\" offset=\"0\"/>\n</Points>\n</Piece>\n"
                               "</PolyData>\n<AppendedData encoding=\"base64\">\n_";
  WriteText(dir / "appended.vtp",
    appended + "AAAAAAABAAAAAAEAAAAAAAAAAQAAAAAACgAAAAAAAAA=eHh4eHh4eHh4eA==" +
      "\n</AppendedData>\n</VTKFile>\n");
  ExpectRefused(dir / "appended.vtp", "at offset 0 announces 1099511627776 blocks");
  WriteText(dir / "appended-ok.vtp",
    appended + points.substr(0, at) + points.substr(at) + "\n</AppendedData>\n</VTKFile>\n");
  EXPECT_EQ(ReadMesh(dir / "appended-ok.vtp")->GetNumberOfPoints(), 4);
}

// Found by fuzz_mesh_vtp: vtkXMLUnstructuredDataReader sizes the connectivity by the last cell
// offset before reading it; an offset of 5e10 (ASCII, or binary read with the wrong header
// size) made it allocate hundreds of GB.
TEST(InputValidation, VtpCellOffsetsBeyondTheFileAreRefused)
{
  TempDir dir;
  const std::string head =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
    "byte_order=\"LittleEndian\">\n<PolyData>\n<Piece NumberOfPoints=\"3\" "
    "NumberOfPolys=\"1\">\n<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" "
    "format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>\n</Points>\n<Polys>\n<DataArray "
    "type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>\n<DataArray "
    "type=\"Int64\" Name=\"offsets\" format=\"ascii\">";
  const std::string tail = "</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  WriteText(dir / "ok.vtp", head + "3" + tail);
  EXPECT_EQ(ReadMesh(dir / "ok.vtp")->GetNumberOfPolys(), 1);
  WriteText(dir / "huge.vtp", head + "50000000000" + tail);
  ExpectRefused(dir / "huge.vtp", "cell offsets up to 50000000000");
  // Binary (base64, UInt32 header 8, then the Int64 value 5e10).
  std::string binary = head;
  binary.replace(binary.rfind("format=\"ascii\""), 14, "format=\"binary\"");
  WriteText(dir / "binary.vtp", binary + "CAAAAAB0O6QLAAAA" + tail);
  ExpectRefused(dir / "binary.vtp", "cell offsets up to 50000000000");
}
