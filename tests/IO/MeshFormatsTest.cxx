// The mesh-format table: every row it marks readable and writable round-trips through ReadMesh
// and WriteMesh, a registered format appears in every list users see and disappears with its
// registration, and the export rules.

#include "MeshFormats.h"
#include "MeshIO.h"

#include "IOTestUtilities.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>

using namespace bender;
using bender_test::TempDir;

namespace
{

// A closed tetrahedron with coordinates exact in single precision.
vtkSmartPointer<vtkPolyData> Tetrahedron()
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(0, 0, 1);
  vtkNew<vtkCellArray> triangles;
  const vtkIdType faces[4][3] = { { 0, 2, 1 }, { 0, 1, 3 }, { 1, 2, 3 }, { 0, 3, 2 } };
  for (const auto& face : faces)
  {
    triangles->InsertNextCell(3, face);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  return mesh;
}

bool Contains(const std::vector<std::string>& list, const std::string& item)
{
  return std::find(list.begin(), list.end(), item) != list.end();
}

bool Contains(const std::string& text, const std::string& item)
{
  return text.find(item) != std::string::npos;
}

// A dummy format stored by the OFF row's reader and writer under its own extension.
MeshFormat DummyFormat()
{
  const std::optional<MeshFormat> off = FindMeshFormatByName("off");
  EXPECT_TRUE(off.has_value());
  MeshFormat dummy;
  dummy.name = "dummy";
  dummy.extensions = { ".dmy", ".dummy" };
  dummy.label = "Dummy mesh";
  dummy.read = off->read;
  dummy.write = off->write;
  dummy.precision = MeshPrecision::Double;
  return dummy;
}

} // namespace

TEST(MeshFormats, EveryRowIsWellFormedAndFoundByItsExtensions)
{
  const std::vector<MeshFormat> formats = MeshFormats();
  ASSERT_FALSE(formats.empty());
  for (const MeshFormat& format : formats)
  {
    EXPECT_FALSE(format.name.empty());
    EXPECT_FALSE(format.label.empty()) << format.name;
    EXPECT_TRUE(format.CanRead() || format.CanWrite()) << format.name;
    ASSERT_FALSE(format.extensions.empty()) << format.name;
    for (const std::string& ext : format.extensions)
    {
      const std::optional<MeshFormat> found = FindMeshFormat("/some/dir/Mesh" + ext);
      ASSERT_TRUE(found.has_value()) << ext;
      EXPECT_EQ(found->name, format.name);
      std::string upper = ext;
      std::transform(upper.begin(), upper.end(), upper.begin(), ::toupper);
      ASSERT_TRUE(FindMeshFormat("MESH" + upper).has_value()) << upper;
      EXPECT_TRUE(Contains(MeshExtensions(MeshAccess::Read), ext) == format.CanRead()) << ext;
      EXPECT_TRUE(Contains(MeshExtensions(MeshAccess::Write), ext) == format.CanWrite()) << ext;
    }
    ASSERT_TRUE(FindMeshFormatByName(format.name).has_value());
  }
  EXPECT_FALSE(FindMeshFormat("mesh.xyz").has_value());
  EXPECT_FALSE(FindMeshFormat("mesh").has_value());
  EXPECT_FALSE(FindMeshFormat(".stl").has_value());
  EXPECT_FALSE(FindMeshFormatByName("xyz").has_value());
}

TEST(MeshFormats, EveryReadableWritableRowRoundTrips)
{
  TempDir dir;
  const vtkSmartPointer<vtkPolyData> mesh = Tetrahedron();
  for (const MeshFormat& format : MeshFormats())
  {
    if (!format.CanWrite())
    {
      continue;
    }
    const std::string path = dir / ("tetra" + format.extensions.front());
    ASSERT_NO_THROW(WriteMesh(mesh, path)) << format.name;
    ASSERT_TRUE(std::filesystem::exists(path)) << format.name;
    if (!format.CanRead())
    {
      continue;
    }
    const vtkSmartPointer<vtkPolyData> back = ReadMesh(path);
    EXPECT_EQ(back->GetNumberOfPoints(), mesh->GetNumberOfPoints()) << format.name;
    EXPECT_EQ(back->GetNumberOfPolys(), mesh->GetNumberOfPolys()) << format.name;
  }
  // Nothing but the files: every write was atomic.
  for (const std::string& name : dir.Entries())
  {
    EXPECT_EQ(name.rfind("tetra.", 0), 0u) << name;
  }
}

TEST(MeshFormats, FileDialogFiltersListEveryFormat)
{
  const std::string all = MeshFilesFilter(MeshAccess::Read);
  EXPECT_EQ(all.rfind("Meshes (*.", 0), 0u) << all;
  const std::vector<std::string> readFilters = MeshFormatFilters(MeshAccess::Read);
  const std::string dialog = MeshFileDialogFilters(MeshAccess::Read);
  EXPECT_EQ(dialog.rfind(all, 0), 0u) << dialog;
  for (const MeshFormat& format : MeshFormats())
  {
    for (const std::string& ext : format.extensions)
    {
      EXPECT_EQ(Contains(all, "*" + ext), format.CanRead()) << ext;
      EXPECT_EQ(Contains(MeshFileDialogFilters(MeshAccess::Write), "*" + ext), format.CanWrite())
        << ext;
    }
    if (format.CanRead())
    {
      EXPECT_TRUE(std::any_of(readFilters.begin(),
        readFilters.end(),
        [&](const std::string& filter)
        { return filter.rfind(format.label + " (*" + format.extensions.front(), 0) == 0; }))
        << format.name;
      EXPECT_TRUE(Contains(dialog, format.label)) << format.name;
    }
  }
  EXPECT_EQ(dialog.find('\n'), std::string::npos);
}

TEST(MeshFormats, ARegisteredFormatAppearsInEveryListAndGoesWithItsRegistration)
{
  TempDir dir;
  const std::string path = dir / "tetra.DMY";
  {
    ScopedMeshFormat scoped(DummyFormat());
    ASSERT_TRUE(FindMeshFormat(path).has_value());
    EXPECT_EQ(FindMeshFormat(path)->name, "dummy");
    EXPECT_EQ(FindMeshFormat("x.dummy")->name, "dummy");
    EXPECT_EQ(MeshFormats().back().name, "dummy");
    for (const MeshAccess access : { MeshAccess::Read, MeshAccess::Write })
    {
      EXPECT_TRUE(Contains(MeshExtensions(access), ".dmy"));
      EXPECT_TRUE(Contains(MeshExtensions(access), ".dummy"));
      EXPECT_TRUE(Contains(MeshExtensionList(access), ".dmy"));
      EXPECT_TRUE(Contains(MeshFormatFilters(access), "Dummy mesh (*.dmy *.dummy)"));
      EXPECT_TRUE(Contains(MeshFileDialogFilters(access), "Dummy mesh (*.dmy *.dummy)"));
    }
    EXPECT_TRUE(Contains(MeshFilesFilter(MeshAccess::Read), "*.dmy *.dummy"));
    // ReadMesh and WriteMesh dispatch on the table: no caller changes.
    WriteMesh(Tetrahedron(), path);
    EXPECT_EQ(ReadMesh(path)->GetNumberOfPolys(), 4);
  }
  EXPECT_FALSE(FindMeshFormat(path).has_value());
  EXPECT_FALSE(Contains(MeshExtensions(MeshAccess::Read), ".dmy"));
  EXPECT_FALSE(Contains(MeshFileDialogFilters(MeshAccess::Write), "Dummy"));
  try
  {
    ReadMesh(path);
    FAIL() << "read a file of an unregistered format";
  }
  catch (const MeshIOError& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("tetra.DMY: unknown extension \".dmy\"", 0), 0u)
      << e.what();
  }
}

TEST(MeshFormats, RegistrationRefusesBadAndDuplicateRows)
{
  MeshFormat clash = DummyFormat();
  clash.extensions = { ".stl" };
  EXPECT_THROW(RegisterMeshFormat(clash), std::invalid_argument);
  MeshFormat sameName = DummyFormat();
  sameName.name = "STL";
  EXPECT_THROW(RegisterMeshFormat(sameName), std::invalid_argument);
  MeshFormat upper = DummyFormat();
  upper.extensions = { ".DMY" };
  EXPECT_THROW(RegisterMeshFormat(upper), std::invalid_argument);
  MeshFormat nothing = DummyFormat();
  nothing.read = nullptr;
  nothing.write = nullptr;
  EXPECT_THROW(RegisterMeshFormat(nothing), std::invalid_argument);
  EXPECT_FALSE(FindMeshFormatByName("dummy").has_value());
  EXPECT_FALSE(UnregisterMeshFormat("dummy"));
  {
    ScopedMeshFormat scoped(DummyFormat());
    EXPECT_THROW(RegisterMeshFormat(DummyFormat()), std::invalid_argument);
  }
  EXPECT_FALSE(FindMeshFormatByName("dummy").has_value());
}

TEST(MeshFormats, ExportRules)
{
  const MeshFormat stl = *FindMeshFormatByName("stl");
  const MeshFormat vtp = *FindMeshFormatByName("vtp");
  const MeshFormat smesh = *FindMeshFormatByName("smesh");
  MeshExportRequest request;

  // Named solids are ASCII; ASCII of the whole surface is written as named solids.
  request.patches = StlPatchMode::Solids;
  EXPECT_EQ(ResolveMeshExport(stl, request).encoding, StlEncoding::Ascii);
  request.patches = StlPatchMode::Single;
  request.encoding = StlEncoding::Ascii;
  EXPECT_EQ(ResolveMeshExport(stl, request).patches, StlPatchMode::Solids);
  request.encoding = StlEncoding::Binary;
  EXPECT_EQ(ResolveMeshExport(stl, request).patches, StlPatchMode::Single);
  EXPECT_TRUE(ResolveMeshExport(stl, request).problem.empty());

  // Patches as parts only where the format names them.
  for (const MeshFormat& format : MeshFormats())
  {
    for (const StlPatchMode mode : { StlPatchMode::Solids, StlPatchMode::Files })
    {
      request.patches = mode;
      EXPECT_EQ(ResolveMeshExport(format, request).problem.empty(), format.namedPatches)
        << format.name;
    }
  }
  request.patches = StlPatchMode::Files;
  const std::string problem = ResolveMeshExport(vtp, request).problem;
  EXPECT_TRUE(Contains(problem, ".stl")) << problem;
  EXPECT_TRUE(Contains(problem, ".vtp")) << problem;

  // The sidecar: asked for, refused, or with every export of patches and region points.
  request.patches = StlPatchMode::Single;
  request.sidecar = SidecarChoice::Auto;
  EXPECT_FALSE(ResolveMeshExport(stl, request).sidecar);
  EXPECT_FALSE(ResolveMeshExport(vtp, request).measure);
  EXPECT_TRUE(ResolveMeshExport(smesh, request).sidecar);
  request.patches = StlPatchMode::Files;
  EXPECT_TRUE(ResolveMeshExport(stl, request).sidecar);
  request.sidecar = SidecarChoice::Off;
  EXPECT_FALSE(ResolveMeshExport(stl, request).sidecar);
  request.patches = StlPatchMode::Single;
  const MeshExportRules tetgen = ResolveMeshExport(smesh, request);
  EXPECT_FALSE(tetgen.sidecar);
  EXPECT_TRUE(tetgen.measure); // its region point
  request.sidecar = SidecarChoice::On;
  EXPECT_TRUE(ResolveMeshExport(vtp, request).sidecar);
  EXPECT_TRUE(ResolveMeshExport(vtp, request).measure);
}
