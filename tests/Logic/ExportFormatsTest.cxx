// ExportSurface writes every format the mesh-format table marks writable, a registered one too.

#include "ExportSurface.h"
#include "LogicTestUtilities.h"
#include "MeshFormats.h"
#include "MeshIO.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <filesystem>

using namespace bender;

TEST(ExportFormats, EveryWritableFormatIsExported)
{
  const std::string folder = test::TemporaryFolder("export-formats");
  const vtkSmartPointer<vtkPolyData> tube = test::MakeTube(0, 20, 3, 11, 16);
  ASSERT_GT(tube->GetNumberOfPolys(), 0);
  MeshFormat dummy = *FindMeshFormatByName("off");
  dummy.name = "dummy";
  dummy.extensions = { ".dmy" };
  dummy.label = "Dummy mesh";
  const ScopedMeshFormat scoped(dummy);
  int exported = 0;
  for (const MeshFormat& format : MeshFormats())
  {
    if (!format.CanWrite())
    {
      continue;
    }
    ExportSurfaceOptions options;
    options.output = folder + "/tube" + format.extensions.front();
    const ExportSurfaceResult result = ExportSurface(tube, options);
    ASSERT_EQ(result.written.size(), 1u) << format.name;
    EXPECT_EQ(result.written.front(), options.output);
    EXPECT_TRUE(std::filesystem::exists(options.output)) << format.name;
    EXPECT_EQ(result.measured, format.regionPoint) << format.name;
    if (format.CanRead())
    {
      EXPECT_EQ(ReadMesh(options.output)->GetNumberOfPolys(), tube->GetNumberOfPolys())
        << format.name;
    }
    ++exported;
  }
  EXPECT_EQ(static_cast<std::size_t>(exported), MeshFormatFilters(MeshAccess::Write).size());
  std::filesystem::remove_all(folder);
}
