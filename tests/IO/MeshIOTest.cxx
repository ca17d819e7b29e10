#include "MeshIO.h"

#include "IOTestUtilities.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using bender::MeshIOError;
using bender::MeshWriteOptions;
using bender::ReadMesh;
using bender::StlEncoding;
using bender::WriteMesh;
using bender_test::TempDir;
using bender_test::TestData;
using bender_test::WriteText;

namespace
{

using Point = std::array<double, 3>;
using Triangle = std::array<Point, 3>;

/// A 6 x 5 height field of 40 triangles with coordinates that no float holds exactly, a
/// double point array, a 3-component point array and an integer cell array.
vtkSmartPointer<vtkPolyData> MakeTestMesh()
{
  const int nx = 6, ny = 5;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> temperature;
  temperature->SetName("Temperature");
  vtkNew<vtkDoubleArray> displacement;
  displacement->SetName("Displacement");
  displacement->SetNumberOfComponents(3);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const double x = 1.0 / 3.0 + 0.1 * i;
      const double y = -1e-3 / 7.0 + 0.37 * j;
      const double z = 100.0 + std::sin(i) * std::cos(j) / 3.0;
      points->InsertNextPoint(x, y, z);
      temperature->InsertNextValue(x * y + 0.1);
      displacement->InsertNextTuple3(x / 7.0, -y, z * 1e-9);
    }
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> region;
  region->SetName("Region");
  for (int j = 0; j + 1 < ny; ++j)
  {
    for (int i = 0; i + 1 < nx; ++i)
    {
      const vtkIdType a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      const vtkIdType t1[3] = { a, b, d };
      const vtkIdType t2[3] = { a, d, c };
      polys->InsertNextCell(3, t1);
      polys->InsertNextCell(3, t2);
      region->InsertNextValue(i - 2 * j);
      region->InsertNextValue(1000 + i);
    }
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  mesh->GetPointData()->AddArray(temperature);
  mesh->GetPointData()->AddArray(displacement);
  mesh->GetCellData()->AddArray(region);
  return mesh;
}

/// Triangles as coordinate triples, each rotated to start at its smallest corner (keeping
/// orientation), sorted: a description of the surface independent of point order.
std::vector<Triangle> CanonicalTriangles(vtkPolyData* mesh)
{
  std::vector<Triangle> triangles;
  vtkNew<vtkIdList> ids;
  mesh->GetPolys()->InitTraversal();
  while (mesh->GetPolys()->GetNextCell(ids))
  {
    EXPECT_EQ(ids->GetNumberOfIds(), 3);
    if (ids->GetNumberOfIds() != 3)
    {
      continue;
    }
    Triangle t;
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids->GetId(k), t[k].data());
    }
    const auto smallest = std::min_element(t.begin(), t.end()) - t.begin();
    std::rotate(t.begin(), t.begin() + smallest, t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

void ExpectSameSurface(vtkPolyData* expected, vtkPolyData* actual, double relativeTolerance)
{
  ASSERT_EQ(actual->GetNumberOfPoints(), expected->GetNumberOfPoints());
  ASSERT_EQ(actual->GetNumberOfPolys(), expected->GetNumberOfPolys());
  const auto a = CanonicalTriangles(expected);
  const auto b = CanonicalTriangles(actual);
  ASSERT_EQ(a.size(), b.size());
  double worst = 0;
  for (std::size_t t = 0; t < a.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double x = a[t][k][c], y = b[t][k][c];
        worst = std::max(worst, std::abs(x - y) / std::max(std::abs(x), 1e-300));
      }
    }
  }
  EXPECT_LE(worst, relativeTolerance);
}

/// Same points in the same order, bit for bit, and the same cells.
void ExpectIdentical(vtkPolyData* expected, vtkPolyData* actual)
{
  ASSERT_EQ(actual->GetNumberOfPoints(), expected->GetNumberOfPoints());
  for (vtkIdType i = 0; i < expected->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    expected->GetPoint(i, p);
    actual->GetPoint(i, q);
    ASSERT_EQ(p[0], q[0]) << "point " << i;
    ASSERT_EQ(p[1], q[1]) << "point " << i;
    ASSERT_EQ(p[2], q[2]) << "point " << i;
  }
  ASSERT_EQ(actual->GetNumberOfPolys(), expected->GetNumberOfPolys());
  vtkNew<vtkIdList> e, g;
  expected->GetPolys()->InitTraversal();
  actual->GetPolys()->InitTraversal();
  while (expected->GetPolys()->GetNextCell(e))
  {
    ASSERT_TRUE(actual->GetPolys()->GetNextCell(g));
    ASSERT_EQ(e->GetNumberOfIds(), g->GetNumberOfIds());
    for (vtkIdType k = 0; k < e->GetNumberOfIds(); ++k)
    {
      EXPECT_EQ(e->GetId(k), g->GetId(k));
    }
  }
}

void ExpectSameArrays(vtkPolyData* expected, vtkPolyData* actual)
{
  for (const char* name : { "Temperature", "Displacement" })
  {
    vtkDataArray* e = expected->GetPointData()->GetArray(name);
    vtkDataArray* a = actual->GetPointData()->GetArray(name);
    ASSERT_NE(a, nullptr) << "point array " << name << " lost";
    EXPECT_EQ(a->GetDataType(), e->GetDataType()) << name;
    ASSERT_EQ(a->GetNumberOfComponents(), e->GetNumberOfComponents());
    ASSERT_EQ(a->GetNumberOfTuples(), e->GetNumberOfTuples());
    for (vtkIdType i = 0; i < e->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < e->GetNumberOfComponents(); ++c)
      {
        EXPECT_EQ(a->GetComponent(i, c), e->GetComponent(i, c)) << name << " " << i;
      }
    }
  }
  vtkDataArray* e = expected->GetCellData()->GetArray("Region");
  vtkDataArray* a = actual->GetCellData()->GetArray("Region");
  ASSERT_NE(a, nullptr) << "cell array Region lost";
  EXPECT_EQ(a->GetDataType(), VTK_INT);
  ASSERT_EQ(a->GetNumberOfTuples(), e->GetNumberOfTuples());
  for (vtkIdType i = 0; i < e->GetNumberOfTuples(); ++i)
  {
    EXPECT_EQ(a->GetComponent(i, 0), e->GetComponent(i, 0));
  }
}

/// Runs f, which must throw MeshIOError; returns its message ("" and a failure otherwise).
template<typename F>
std::string ErrorOf(F&& f)
{
  try
  {
    f();
  }
  catch (const MeshIOError& e)
  {
    return e.what();
  }
  catch (const std::exception& e)
  {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no exception";
  return {};
}

/// Reading path must fail with a one-line message that starts with the file's name and
/// contains the expected text, and must print nothing on stderr.
void ExpectReadError(const std::string& path, const std::string& expected)
{
  SCOPED_TRACE(path);
  ::testing::internal::CaptureStderr();
  const std::string message = ErrorOf([&] { ReadMesh(path); });
  const std::string stderrText = ::testing::internal::GetCapturedStderr();
  const std::string name = fs::path(path).filename().string();
  EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(expected), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(stderrText, "") << "VTK printed on stderr";
}

std::string StlBytesWithTriangles(const std::vector<std::array<float, 9>>& triangles,
  std::uint32_t announced)
{
  std::string bytes(80, ' ');
  bytes.replace(0, 11, "binary test");
  for (int b = 0; b < 4; ++b)
  {
    bytes += static_cast<char>((announced >> (8 * b)) & 0xff);
  }
  for (const auto& t : triangles)
  {
    float record[12] = { 0, 0, 1 };
    std::copy(t.begin(), t.end(), record + 3);
    bytes.append(reinterpret_cast<const char*>(record), sizeof(record));
    bytes += std::string(2, '\0');
  }
  return bytes;
}

} // namespace

// ---------------------------------------------------------------------------------------
// Round trips

TEST(MeshIO, ExactFormatsKeepDoublesCellsAndArrays)
{
  TempDir dir;
  const auto mesh = MakeTestMesh();
  for (const char* name : { "mesh.vtp", "mesh.vtk", "mesh.off", "MESH.VTP" })
  {
    SCOPED_TRACE(name);
    const std::string path = dir / name;
    WriteMesh(mesh, path);
    const auto back = ReadMesh(path);
    ExpectIdentical(mesh, back);
    if (std::string(name) != "mesh.off")
    {
      EXPECT_EQ(back->GetPoints()->GetDataType(), VTK_DOUBLE);
      ExpectSameArrays(mesh, back);
    }
  }
}

TEST(MeshIO, FloatFormatsKeepTheSurfaceWithin1e7)
{
  TempDir dir;
  const auto mesh = MakeTestMesh();
  struct Case
  {
    const char* name;
    StlEncoding encoding;
  };
  for (const Case& c : { Case{ "mesh.stl", StlEncoding::Binary },
         Case{ "ascii.stl", StlEncoding::Ascii },
         Case{ "mesh.obj", StlEncoding::Binary },
         Case{ "mesh.ply", StlEncoding::Binary } })
  {
    SCOPED_TRACE(c.name);
    MeshWriteOptions options;
    options.stlEncoding = c.encoding;
    const std::string path = dir / c.name;
    WriteMesh(mesh, path, options);
    const auto back = ReadMesh(path);
    ExpectSameSurface(mesh, back, 1e-7);
  }
}

TEST(MeshIO, WritesPolygonsAsTrianglesToStl)
{
  TempDir dir;
  const auto cube = ReadMesh(TestData("io/cube_commented.off"));
  ASSERT_EQ(cube->GetNumberOfPolys(), 6);
  WriteMesh(cube, dir / "cube.stl");
  const auto back = ReadMesh(dir / "cube.stl");
  EXPECT_EQ(back->GetNumberOfPoints(), 8);
  EXPECT_EQ(back->GetNumberOfPolys(), 12);
}

TEST(MeshIO, StlHeaderCarriesTheOptionText)
{
  TempDir dir;
  const auto mesh = MakeTestMesh();
  MeshWriteOptions options;
  options.header = "bender: LPS mm";
  WriteMesh(mesh, dir / "b.stl", options);
  const std::string binary = bender_test::ReadText(dir / "b.stl");
  ASSERT_GE(binary.size(), 84u);
  EXPECT_EQ(binary.substr(0, options.header.size()), options.header);
  EXPECT_EQ(binary.size(), 84u + 50u * 40u);

  options.stlEncoding = StlEncoding::Ascii;
  WriteMesh(mesh, dir / "a.stl", options);
  const std::string ascii = bender_test::ReadText(dir / "a.stl");
  EXPECT_EQ(ascii.substr(0, ascii.find('\n')), "solid " + options.header);

  // A header longer than 80 bytes is truncated; the file stays valid binary STL.
  options.stlEncoding = StlEncoding::Binary;
  options.header = std::string(200, 'x');
  WriteMesh(mesh, dir / "long.stl", options);
  EXPECT_EQ(bender_test::ReadText(dir / "long.stl").size(), 84u + 50u * 40u);
  EXPECT_EQ(ReadMesh(dir / "long.stl")->GetNumberOfPolys(), 40);
}

TEST(MeshIO, OffReaderHandlesCommentsQuadsColoursAndCrlf)
{
  const auto cube = ReadMesh(TestData("io/cube_commented.off"));
  EXPECT_EQ(cube->GetNumberOfPoints(), 8);
  EXPECT_EQ(cube->GetNumberOfPolys(), 6);
  EXPECT_EQ(cube->GetPolys()->GetMaxCellSize(), 4);
  double p[3];
  cube->GetPoint(6, p);
  EXPECT_EQ(p[0], 1.0);
  EXPECT_EQ(p[1], 1.0);
  EXPECT_EQ(p[2], 1.0);

  const auto tetra = ReadMesh(TestData("io/tetra_crlf_coloured.off"));
  EXPECT_EQ(tetra->GetNumberOfPoints(), 4);
  EXPECT_EQ(tetra->GetNumberOfPolys(), 2);
  tetra->GetPoint(3, p);
  EXPECT_EQ(p[0], 1e-3);
  EXPECT_EQ(p[1], -250.0);
  EXPECT_EQ(p[2], 3.0);
}

TEST(MeshIO, OffKeepsAwkwardDoublesBitForBit)
{
  TempDir dir;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->InsertNextPoint(0.1, 1.0 / 3.0, -0.0);
  // The largest magnitude is the float range's end (CoordinateRange.h): beyond it no mesh is
  // read or written.
  points->InsertNextPoint(1e-300, 4.9406564584124654e-324, 3.4028234663852886e38);
  points->InsertNextPoint(-123456789.123456789, 2.0 / 3.0, 1e22);
  vtkNew<vtkCellArray> polys;
  const vtkIdType t[3] = { 0, 1, 2 };
  polys->InsertNextCell(3, t);
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  WriteMesh(mesh, dir / "awkward.off");
  ExpectIdentical(mesh, ReadMesh(dir / "awkward.off"));
  WriteMesh(mesh, dir / "awkward.vtk");
  ExpectIdentical(mesh, ReadMesh(dir / "awkward.vtk"));
  WriteMesh(mesh, dir / "awkward.vtp");
  ExpectIdentical(mesh, ReadMesh(dir / "awkward.vtp"));
}

TEST(MeshIO, OffHeaderBecomesAComment)
{
  TempDir dir;
  MeshWriteOptions options;
  options.header = "bender: LPS mm\nsecond line";
  WriteMesh(MakeTestMesh(), dir / "h.off", options);
  const std::string text = bender_test::ReadText(dir / "h.off");
  EXPECT_EQ(text.rfind("OFF\n# bender: LPS mm second line\n30 40 0\n", 0), 0u)
    << text.substr(0, 80);
}

// ---------------------------------------------------------------------------------------
// Real meshes (fetched by scripts/fetch-data)

TEST(MeshIO, AneurysmStlIsWeldedIntoOneSurface)
{
  BENDER_REQUIRE_EXTERNAL(path, "aneurysm_data.stl");
  const auto mesh = ReadMesh(path);
  EXPECT_EQ(mesh->GetNumberOfPoints(), 10204);
  EXPECT_EQ(mesh->GetNumberOfPolys(), 20294);
  double bounds[6];
  mesh->GetBounds(bounds);
  EXPECT_NEAR(bounds[1] - bounds[0], 55, 3);
  EXPECT_NEAR(bounds[3] - bounds[2], 51, 3);
  EXPECT_NEAR(bounds[5] - bounds[4], 59, 3);

  // Binary and ASCII STL round trips keep the welded surface.
  TempDir dir;
  for (StlEncoding encoding : { StlEncoding::Binary, StlEncoding::Ascii })
  {
    MeshWriteOptions options;
    options.stlEncoding = encoding;
    WriteMesh(mesh, dir / "aneurysm.stl", options);
    const auto back = ReadMesh(dir / "aneurysm.stl");
    ExpectSameSurface(mesh, back, 1e-7);
  }
  // And the exact formats keep it bit for bit.
  for (const char* name : { "aneurysm.off", "aneurysm.vtp", "aneurysm.vtk" })
  {
    WriteMesh(mesh, dir / name);
    ExpectIdentical(mesh, ReadMesh(dir / name));
  }
}

TEST(MeshIO, RealOffMeshesHaveTheirAnnouncedSizes)
{
  struct Expected
  {
    const char* name;
    vtkIdType points;
    vtkIdType faces;
  };
  for (const Expected& e : { Expected{ "cow.off", 2904, 5804 },
         Expected{ "sphere.off", 162, 320 },
         Expected{ "plane.off", 841, 1600 },
         Expected{ "pipe.off", 160, 320 },
         Expected{ "bunny00.off", 37706, 75408 } })
  {
    SCOPED_TRACE(e.name);
    BENDER_REQUIRE_EXTERNAL(path, e.name);
    const auto mesh = ReadMesh(path);
    EXPECT_EQ(mesh->GetNumberOfPoints(), e.points);
    EXPECT_EQ(mesh->GetNumberOfPolys(), e.faces);
  }
}

TEST(MeshIO, RealObjRoundTripsThroughEveryFormat)
{
  BENDER_REQUIRE_EXTERNAL(path, "bunny.obj");
  const auto bunny = ReadMesh(path);
  EXPECT_EQ(bunny->GetNumberOfPoints(), 34835);
  EXPECT_EQ(bunny->GetNumberOfPolys(), 69666);
  TempDir dir;
  for (const char* name : { "b.obj", "b.ply", "b.stl", "b.off", "b.vtp", "b.vtk" })
  {
    SCOPED_TRACE(name);
    WriteMesh(bunny, dir / name);
    ExpectSameSurface(bunny, ReadMesh(dir / name), 1e-7);
  }
}

// ---------------------------------------------------------------------------------------
// Bad input: one line naming the file, no crash, nothing on stderr

TEST(MeshIOBadInput, MissingFolderAndEmptyFiles)
{
  TempDir dir;
  ExpectReadError(dir / "nothere.stl", "no such file");
  fs::create_directory(dir / "folder.stl");
  ExpectReadError(dir / "folder.stl", "is a folder");
  for (const char* name :
    { "empty.stl", "empty.obj", "empty.ply", "empty.vtp", "empty.vtk", "empty.off" })
  {
    WriteText(dir / name, "");
    ExpectReadError(dir / name, "empty file");
  }
  WriteText(dir / "mesh.xyz", "whatever");
  ExpectReadError(dir / "mesh.xyz", "unknown extension \".xyz\"");
  WriteText(dir / "mesh", "whatever");
  ExpectReadError(dir / "mesh", "no file extension");
}

TEST(MeshIOBadInput, TruncatedBinaryStlNamesBothCounts)
{
  BENDER_REQUIRE_EXTERNAL(source, "aneurysm_data.stl");
  TempDir dir;
  const std::string path = dir / "aneurysm.stl";
  WriteMesh(ReadMesh(source), path);
  fs::resize_file(path, 84 + 50 * 1200 + 17);
  ExpectReadError(path, "truncated binary STL (header says 20294 triangles, file holds 1200)");
  const std::string message = ErrorOf([&] { ReadMesh(path); });
  EXPECT_EQ(
    message, "aneurysm.stl: truncated binary STL (header says 20294 triangles, file holds 1200)");
}

TEST(MeshIOBadInput, SmallOrGarbledStl)
{
  TempDir dir;
  WriteText(dir / "short.stl", std::string(40, '\x01'));
  ExpectReadError(dir / "short.stl", "not an STL file");
  WriteText(dir / "text.stl", std::string(200, 'a') + "\nhello world\n");
  ExpectReadError(dir / "text.stl", "not an STL file");
  WriteText(
    dir / "solid.stl", "solid broken\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 x\n");
  ExpectReadError(dir / "solid.stl", "");
  WriteText(dir / "nofacet.stl", "solid nothing\nendsolid nothing\n");
  ExpectReadError(dir / "nofacet.stl", "");
  std::string random(5000, '\0');
  std::mt19937 rng(7);
  for (char& c : random)
  {
    c = static_cast<char>(rng());
  }
  for (const char* name :
    { "random.stl", "random.obj", "random.ply", "random.vtp", "random.vtk", "random.off" })
  {
    WriteText(dir / name, random);
    ExpectReadError(dir / name, "");
    // No binary garbage quoted into the message.
    const std::string message = ErrorOf([&] { ReadMesh(dir / name); });
    EXPECT_TRUE(std::all_of(message.begin(),
      message.end(),
      [](char c)
      { return static_cast<unsigned char>(c) >= 32 && static_cast<unsigned char>(c) < 127; }))
      << message;
    EXPECT_EQ(message.find(dir.path().string()), std::string::npos) << message;
  }
  for (const char* name :
    { "garbage.stl", "garbage.obj", "garbage.ply", "garbage.vtp", "garbage.vtk", "garbage.off" })
  {
    WriteText(dir / name, "this is not a mesh\nat all, just words 1 2 3\n");
    ExpectReadError(dir / name, "");
  }
}

// vtkSTLReader chooses ASCII or binary from the share of non-text bytes in the first 256 bytes,
// whatever the file starts with: ReadMesh must check the file the way VTK will read it.
TEST(MeshIOBadInput, StlReadTheWayVtkWillReadIt)
{
  TempDir dir;
  const std::string facet = "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n"
                            "      vertex 1 0 0\n      vertex 0 1 0\n    endloop\n  endfacet\n";
  // An ASCII STL whose solid name is 40 bytes of 0xff: VTK reads it as binary, with the text
  // after the 80-byte header as the triangle count (fuzz_mesh_stl: a 19 GB allocation).
  const std::string name(40, '\xff');
  WriteText(dir / "name.stl", "solid " + name + "\n" + facet + "endsolid " + name + "\n");
  ExpectReadError(dir / "name.stl", "would take it for binary");
  // The same with a plain name is read.
  WriteText(dir / "plain.stl", "solid plain\n" + facet + "endsolid plain\n");
  EXPECT_EQ(ReadMesh(dir / "plain.stl")->GetNumberOfPolys(), 1);
  // Exactly as long as a binary STL with the count in bytes 80..83 says (10 triangles), but
  // text that VTK parses as ASCII: checked as ASCII STL (its NUL bytes refused).
  std::string text = "solid x";
  text.resize(80, ' ');
  text += std::string("\n\0\0\0", 4) + facet + "endsolid x\n";
  text.resize(84 + 50 * 10, ' ');
  WriteText(dir / "sized.stl", text);
  ExpectReadError(dir / "sized.stl", "NUL byte");
}

TEST(MeshIOBadInput, NonFiniteCoordinatesAreRejected)
{
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  WriteText(dir / "nan.stl", StlBytesWithTriangles({ { 0, 0, 0, 1, 0, 0, 0, nan, 0 } }, 1));
  ExpectReadError(dir / "nan.stl", "non-finite coordinate");
  WriteText(dir / "inf.stl", StlBytesWithTriangles({ { 0, 0, 0, 1, 0, 0, 0, inf, 0 } }, 1));
  ExpectReadError(dir / "inf.stl", "non-finite coordinate");
  WriteText(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  ExpectReadError(dir / "nan.obj", "non-finite coordinate");
  WriteText(dir / "nan.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n");
  ExpectReadError(dir / "nan.off", "line 5: non-finite coordinate");
  WriteText(dir / "inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n");
  ExpectReadError(dir / "inf.off", "line 5: non-finite coordinate");
  WriteText(dir / "huge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e999 0\n3 0 1 2\n");
  ExpectReadError(dir / "huge.off", "line 5: non-finite coordinate");
  // Below the double range is zero, not an error.
  WriteText(dir / "tiny.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e-999 1\n3 0 1 2\n");
  double p[3];
  ReadMesh(dir / "tiny.off")->GetPoint(2, p);
  EXPECT_EQ(p[1], 0.0);
}

TEST(MeshIOBadInput, MalformedOff)
{
  TempDir dir;
  struct Case
  {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
    { "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n", "file ends after 3 of 4 vertices" },
    { "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "file ends after 1 of 2 faces" },
    { "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n",
      "line 7: more data than the header announces (3 vertices, 1 faces)" },
    { "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
      "line 6: vertex index 3 out of range (the file has 3 vertices)" },
    { "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "line 6: vertex index -1 out of range" },
    { "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "line 6: a face needs at least 3 vertices" },
    { "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
      "line 6: face announces 4 vertices but lists 3" },
    { "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n",
      "line 6: vertex index \"1.5\" is not an integer" },
    { "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "line 4: expected 3 coordinates" },
    { "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", "line 4: expected 3 coordinates" },
    { "OFF\nthree one zero\n", "line 2: expected the counts" },
    { "OFF\n-3 1 0\n", "line 2: expected the counts" },
    { "OFF\n99999999999 1 0\n0 0 0\n", "file ends after 1 of 99999999999 vertices" },
    { "OFF\n", "file ends before the vertex and face counts" },
    { "# only a comment\n\n", "no data" },
    { "PLY\n3 1 0\n", "line 1: not an OFF file" },
    { "4OFF\n3 1 0\n", "unsupported OFF variant" },
    { "OFF BINARY\n3 1 0\n", "binary OFF is not supported" },
    { "OFF\n0 0 0\n", "no points" },
  };
  int index = 0;
  for (const Case& c : cases)
  {
    const std::string path = dir / ("bad" + std::to_string(index++) + ".off");
    WriteText(path, c.text);
    ExpectReadError(path, c.expected);
  }
}

TEST(MeshIOBadInput, ObjWithIndicesOutOfRange)
{
  TempDir dir;
  WriteText(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  ExpectReadError(dir / "range.obj", "");
}

// vtkOBJReader passes "vt" / "vn" lists shorter than the vertex list on as point data, and
// "GroupIds" with one value per face also when there are "l" and "p" cells: filters that copy
// attributes by point or cell id would read past the arrays' ends. ReadMesh returns only arrays
// as long as the points and cells (the geometry itself is read).
TEST(MeshIO, ObjAttributesAlwaysMatchThePointsAndCells)
{
  TempDir dir;
  const std::string header = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  const std::vector<std::string> bodies = {
    "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\n",
    "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1/1/1 2/2/2 3/3/3\n",
    "f 1 2 3\nl 1 4\np 2\ng a\nf 1 2 4\n",
  };
  int index = 0;
  for (const std::string& body : bodies)
  {
    SCOPED_TRACE(body);
    const std::string path = dir / ("attributes" + std::to_string(index++) + ".obj");
    WriteText(path, header + body);
    vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(path);
    ASSERT_EQ(mesh->GetNumberOfPoints(), 4);
    EXPECT_GE(mesh->GetNumberOfPolys(), 1);
    for (int a = 0; a < mesh->GetPointData()->GetNumberOfArrays(); ++a)
    {
      EXPECT_EQ(mesh->GetPointData()->GetAbstractArray(a)->GetNumberOfTuples(), 4)
        << mesh->GetPointData()->GetArrayName(a);
    }
    for (int a = 0; a < mesh->GetCellData()->GetNumberOfArrays(); ++a)
    {
      EXPECT_EQ(
        mesh->GetCellData()->GetAbstractArray(a)->GetNumberOfTuples(), mesh->GetNumberOfCells())
        << mesh->GetCellData()->GetArrayName(a);
    }
  }
  // Texture coordinates for every vertex are kept.
  const std::string full = dir / "full.obj";
  WriteText(full, header + "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(full);
  ASSERT_NE(mesh->GetPointData()->GetTCoords(), nullptr);
  EXPECT_EQ(mesh->GetPointData()->GetTCoords()->GetNumberOfTuples(), 4);
}

TEST(MeshIOBadInput, PlyThatVtkWouldCrashOn)
{
  TempDir dir;
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  WriteText(dir / "index.ply",
    header + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" + vertices +
      "3 0 1 7\n");
  ExpectReadError(dir / "index.ply", "vertex index 7 out of range (the file has 3 vertices)");
  WriteText(dir / "name.ply",
    header + "element face 1\nproperty list uchar int vertex_inJices\nend_header\n" + vertices +
      "3 0 1 2\n");
  ExpectReadError(dir / "name.ply", "face element without a \"vertex_indices\" list");
  WriteText(dir / "novertex.ply",
    "ply\nformat ascii 1.0\nelement vetrex 3\nproperty float x\n"
    "property float y\nproperty float z\nend_header\n" +
      vertices);
  ExpectReadError(dir / "novertex.ply", "without a \"vertex\" element");
  WriteText(dir / "short.ply",
    header + "element face 2\nproperty list uchar int vertex_indices\nend_header\n" + vertices +
      "3 0 1 2\n3 0\n");
  ExpectReadError(dir / "short.ply", "truncated ASCII PLY");
  // Points only: no crash; a mesh of points (callers decide).
  WriteText(dir / "cloud.ply", header + "end_header\n" + vertices);
  ::testing::internal::CaptureStderr();
  try
  {
    EXPECT_EQ(ReadMesh(dir / "cloud.ply")->GetNumberOfPoints(), 3);
  }
  catch (const MeshIOError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("cloud.ply: ", 0), 0u) << e.what();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(MeshIOBadInput, TruncatedVtpVtkAndPly)
{
  TempDir dir;
  const auto mesh = MakeTestMesh();
  for (const char* name : { "cut.vtp", "cut.vtk", "cut.ply" })
  {
    const std::string path = dir / name;
    WriteMesh(mesh, path);
    const auto size = fs::file_size(path);
    fs::resize_file(path, size * 2 / 3);
    ExpectReadError(path, "");
  }
}

TEST(MeshIOBadInput, EveryTruncationAndCorruptionFailsCleanly)
{
  // Every format cut at many lengths, and with bytes overwritten: each read either succeeds
  // with a checked mesh or throws MeshIOError; nothing crashes, hangs or prints.
  TempDir dir;
  const auto mesh = MakeTestMesh();
  std::mt19937 rng(2005);
  for (const char* name : { "m.stl", "m.obj", "m.ply", "m.vtp", "m.vtk", "m.off" })
  {
    SCOPED_TRACE(name);
    const std::string good = dir / (std::string("good-") + name);
    WriteMesh(mesh, good);
    const std::string bytes = bender_test::ReadText(good);
    const std::string bad = dir / name;
    std::vector<std::string> variants;
    for (std::size_t cut = 1; cut < bytes.size(); cut += 1 + bytes.size() / 97)
    {
      variants.push_back(bytes.substr(0, cut));
    }
    for (int k = 0; k < 60; ++k)
    {
      std::string corrupt = bytes;
      for (int flips = 0; flips < 4; ++flips)
      {
        corrupt[rng() % corrupt.size()] = static_cast<char>(rng());
      }
      variants.push_back(corrupt);
    }
    for (const std::string& variant : variants)
    {
      WriteText(bad, variant);
      ::testing::internal::CaptureStderr();
      try
      {
        const auto back = ReadMesh(bad);
        EXPECT_GT(back->GetNumberOfPoints(), 0);
      }
      catch (const MeshIOError& e)
      {
        EXPECT_EQ(std::string(e.what()).rfind(std::string(name) + ": ", 0), 0u) << e.what();
      }
      EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    }
  }
}

// ---------------------------------------------------------------------------------------
// Writing

TEST(MeshIOWrite, RefusesNonFiniteCoordinatesAndLeavesNothing)
{
  TempDir dir;
  auto mesh = MakeTestMesh();
  WriteMesh(mesh, dir / "keep.vtp");
  const std::string before = bender_test::ReadText(dir / "keep.vtp");
  mesh->GetPoints()->SetPoint(7, 0, std::numeric_limits<double>::quiet_NaN(), 0);
  for (const char* name : { "keep.vtp", "new.stl", "new.obj", "new.ply", "new.vtk", "new.off" })
  {
    const std::string message = ErrorOf([&] { WriteMesh(mesh, dir / name); });
    EXPECT_EQ(message.rfind(std::string(name) + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
  }
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "keep.vtp" });
  EXPECT_EQ(bender_test::ReadText(dir / "keep.vtp"), before);
}

TEST(MeshIOWrite, FailedWriteLeavesTheTargetAndNoTemporaryFile)
{
  TempDir dir;
  // A mesh of lines only cannot be written as STL: the write fails after the writer started.
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 1 };
  lines->InsertNextCell(2, line);
  vtkNew<vtkPolyData> wire;
  wire->SetPoints(points);
  wire->SetLines(lines);
  WriteText(dir / "target.stl", "previous content");
  const std::string message = ErrorOf([&] { WriteMesh(wire, dir / "target.stl"); });
  EXPECT_EQ(message.rfind("target.stl: ", 0), 0u) << message;
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "target.stl" });
  EXPECT_EQ(bender_test::ReadText(dir / "target.stl"), "previous content");
}

TEST(MeshIOWrite, ReportsUnwritableTargets)
{
  TempDir dir;
  const auto mesh = MakeTestMesh();
  std::string message = ErrorOf([&] { WriteMesh(mesh, dir / "no/such/folder/m.vtp"); });
  EXPECT_EQ(message.rfind("m.vtp: folder ", 0), 0u) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;

  message = ErrorOf([&] { WriteMesh(mesh, dir / "m.xyz"); });
  EXPECT_EQ(message.rfind("m.xyz: unknown extension", 0), 0u) << message;

  fs::create_directory(dir / "folder.off");
  message = ErrorOf([&] { WriteMesh(mesh, dir / "folder.off"); });
  EXPECT_EQ(message, "folder.off: is a folder, not a file");

  message = ErrorOf([&] { WriteMesh(nullptr, dir / "null.off"); });
  EXPECT_EQ(message.rfind("null.off: ", 0), 0u) << message;

  if (::geteuid() != 0) // root writes anywhere
  {
    fs::create_directory(dir / "locked");
    fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    message = ErrorOf([&] { WriteMesh(mesh, dir / "locked/m.off"); });
    EXPECT_NE(message.find("not writable"), std::string::npos) << message;
    fs::permissions(dir / "locked", fs::perms::owner_all);
    EXPECT_TRUE(fs::is_empty(dir / "locked"));
  }
  for (const std::string& entry : dir.Entries())
  {
    EXPECT_TRUE(entry == "folder.off" || entry == "locked") << "left behind: " << entry;
  }
}

TEST(MeshIOWrite, OverwritesAtomically)
{
  TempDir dir;
  const auto mesh = MakeTestMesh();
  WriteText(dir / "m.off", "old");
  WriteMesh(mesh, dir / "m.off");
  EXPECT_EQ(dir.Entries(), std::set<std::string>{ "m.off" });
  ExpectIdentical(mesh, ReadMesh(dir / "m.off"));
}

// ---------------------------------------------------------------------------------------
// SameFile

TEST(MeshIO, SameFile)
{
  TempDir dir;
  WriteText(dir / "a.off", "x");
  WriteText(dir / "b.off", "x");
  fs::create_directory(dir / "sub");
  EXPECT_TRUE(bender::SameFile(dir / "a.off", dir / "a.off"));
  EXPECT_TRUE(bender::SameFile(dir / "a.off", dir / "sub/../a.off"));
  EXPECT_TRUE(bender::SameFile(dir / "a.off", dir / "./a.off"));
  EXPECT_FALSE(bender::SameFile(dir / "a.off", dir / "b.off"));
  fs::create_hard_link(dir / "a.off", dir / "hard.off");
  EXPECT_TRUE(bender::SameFile(dir / "a.off", dir / "hard.off"));
  fs::create_symlink(dir / "a.off", dir / "link.off");
  EXPECT_TRUE(bender::SameFile(dir / "link.off", dir / "a.off"));
  // Not existing yet: the same after normalisation, or not.
  EXPECT_TRUE(bender::SameFile(dir / "new.off", dir / "sub/../new.off"));
  EXPECT_FALSE(bender::SameFile(dir / "new.off", dir / "other.off"));
  EXPECT_FALSE(bender::SameFile(dir / "a.off", dir / "new.off"));
  EXPECT_FALSE(bender::SameFile("", ""));
  // Relative and absolute spellings of one file.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path());
  EXPECT_TRUE(bender::SameFile("a.off", dir / "a.off"));
  fs::current_path(cwd);
}
