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

// A file carries its frame as it carries its unit (issue 22): every format exported in RAS, in
// millimetres and in metres, reads back in LPS millimetres where the surface was. The tube lies
// off the origin on every axis, so that a frame ignored on reading moves its bounds.
TEST(ExportFormats, AnExportInRasReadsBackInLps)
{
  const std::string folder = test::TemporaryFolder("export-ras");
  const vtkSmartPointer<vtkPolyData> tube = test::MakeTube(0, 20, 3, 11, 16);
  for (vtkIdType i = 0; i < tube->GetNumberOfPoints(); ++i)
  {
    double p[3];
    tube->GetPoint(i, p);
    tube->GetPoints()->SetPoint(i, p[0] + 31.0, p[1] - 47.0, p[2] + 5.0);
  }
  double expected[6];
  tube->GetBounds(expected);
  int read = 0;
  for (const MeshFormat& format : MeshFormats())
  {
    if (!format.CanWrite() || !format.CanRead())
    {
      continue;
    }
    for (const std::string unit : { "mm", "m" })
    {
      ExportSurfaceOptions options;
      options.output = folder + "/tube-" + unit + format.extensions.front();
      options.frame = StlFrame::RAS;
      options.unit = unit;
      ExportSurface(tube, options);
      StatedSpace stated;
      const vtkSmartPointer<vtkPolyData> back = ReadMesh(options.output, stated);
      EXPECT_EQ(stated.frame, "RAS") << options.output;
      EXPECT_EQ(stated.unit, unit) << options.output;
      double bounds[6];
      back->GetBounds(bounds);
      for (int k = 0; k < 6; ++k)
      {
        EXPECT_NEAR(bounds[k], expected[k], 1e-4) << options.output << " bound " << k;
      }
      ++read;
    }
  }
  EXPECT_GE(read, 2 * 6); // stl, obj, ply, vtp, vtk, off (and the TetGen files)
  std::filesystem::remove_all(folder);
}
