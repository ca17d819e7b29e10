// A labelled surface (geometry plus its patch table, read once) through clip -> export ->
// case: the table the clip carries is the one its cell data hold, survives the export and a
// read back, and the sidecar, the read back and the OpenFOAM case measure the same patches.

#include "BenderErrors.h"
#include "CfdCase.h"
#include "ExportSurface.h"
#include "LabelledSurface.h"
#include "LogicTestUtilities.h"
#include "MeshFormats.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "PatchSidecar.h"
#include "PrepareForCfd.h"

#include <gtest/gtest.h>

#include <vtkPolyData.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

using namespace bender;

namespace
{
const std::string Aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";

void ExpectSameTable(const std::vector<PatchLabel>& a, const std::vector<PatchLabel>& b)
{
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_EQ(a[k].id, b[k].id) << k;
    EXPECT_EQ(a[k].name, b[k].name) << k;
    EXPECT_EQ(a[k].type, b[k].type) << k;
  }
}

PatchSidecar MeasureInMillimetres(const LabelledSurface& surface)
{
  return ComputePatchSidecar(surface, ExportTransform(StlFrame::LPS, "mm"));
}

/// Triangles per patch id (CellPatchIds: all wall without labels).
std::map<int, std::size_t> TrianglesPerPatch(vtkPolyData* surface)
{
  std::map<int, std::size_t> counts;
  for (int id : CellPatchIds(surface))
  {
    ++counts[id];
  }
  return counts;
}
} // namespace

TEST(LabelledSurfaceFlow, ClipExportReadBackAndCaseKeepTheTableAndTheAreas)
{
  PrepareForCfdOptions options;
  options.inputName = "aneurysm_data.stl";
  const PrepareForCfdResult prepared = PrepareForCfd(ReadMesh(Aneurysm), options);
  const LabelledSurface& clipped = prepared;
  // The table the clip carries is the one its cell data hold.
  ExpectSameTable(clipped.patches, ReadPatchLabels(prepared.surface));
  ASSERT_EQ(clipped.patches.size(), prepared.ends.size() + 1);

  const std::string folder = test::TemporaryFolder("bender_labelled_surface_flow");
  ExportSurfaceOptions vtp;
  vtp.output = folder + "/clipped.vtp";
  const ExportSurfaceResult exported = ExportSurface(clipped, vtp);
  ExpectSameTable(exported.patches, clipped.patches);

  // Read back: the same names, ids, roles; the same patches, triangle for triangle and area
  // for area (the VTP keeps the coordinates).
  const LabelledSurface back = ReadLabelledSurface(ReadMesh(vtp.output));
  ExpectSameTable(back.patches, clipped.patches);
  const PatchSidecar before = MeasureInMillimetres(clipped);
  const PatchSidecar after = MeasureInMillimetres(back);
  ASSERT_EQ(after.patches.size(), before.patches.size());
  for (std::size_t k = 0; k < before.patches.size(); ++k)
  {
    EXPECT_EQ(after.patches[k].triangles, before.patches[k].triangles) << k;
    EXPECT_NEAR(after.patches[k].area, before.patches[k].area, 1e-9 * before.patches[k].area)
      << before.patches[k].label.name;
    EXPECT_GT(before.patches[k].area, 0.0);
  }

  // The sidecar of a named-solids export measures the same patches (in its metres).
  ExportSurfaceOptions stl;
  stl.output = folder + "/clipped.stl";
  stl.unit = "m";
  stl.patches = StlPatchMode::Solids;
  stl.patchesJson = true;
  const ExportSurfaceResult solids = ExportSurface(back, stl);
  ASSERT_TRUE(solids.measured);
  ASSERT_EQ(solids.sidecar.patches.size(), before.patches.size());
  for (std::size_t k = 0; k < before.patches.size(); ++k)
  {
    EXPECT_EQ(solids.sidecar.patches[k].label.name, before.patches[k].label.name);
    EXPECT_NEAR(
      solids.sidecar.patches[k].area, 1e-6 * before.patches[k].area, 1e-9 * before.patches[k].area);
  }

  // The case measures its patches with the same measure: the same areas, to the bit.
  CfdCaseOptions caseOptions;
  caseOptions.caseDirectory = folder + "/case";
  caseOptions.sourceName = "clipped.vtp";
  const CfdCaseResult written = WriteOpenFoamCase(back, caseOptions);
  ASSERT_EQ(written.patches.size(), before.patches.size());
  for (std::size_t k = 0; k < before.patches.size(); ++k)
  {
    EXPECT_EQ(written.patches[k].name, before.patches[k].label.name);
    EXPECT_EQ(written.patches[k].triangles, static_cast<long long>(before.patches[k].triangles));
    EXPECT_EQ(written.patches[k].area, after.patches[k].area * 1e-6);
  }
  std::filesystem::remove_all(folder);
}

TEST(LabelledSurfaceFlow, WithoutCapsTheTableIsTheWall)
{
  PrepareForCfdOptions options;
  options.inputName = "aneurysm_data.stl";
  options.cap = false;
  const PrepareForCfdResult prepared = PrepareForCfd(ReadMesh(Aneurysm), options);
  ASSERT_EQ(prepared.patches.size(), 1u);
  EXPECT_EQ(prepared.patches[0].name, "wall");
  ExpectSameTable(prepared.patches, ReadPatchLabels(prepared.surface));
}

TEST(LabelledSurfaceFlow, ATableOfAnotherSurfaceIsRefusedInOneLine)
{
  PrepareForCfdOptions options;
  options.inputName = "aneurysm_data.stl";
  const PrepareForCfdResult prepared = PrepareForCfd(ReadMesh(Aneurysm), options);
  // Only the wall in the table: the caps' cells have ids it does not know.
  const LabelledSurface mismatched{ prepared.surface, { prepared.patches[0] } };
  const std::string folder = test::TemporaryFolder("bender_labelled_surface_mismatch");
  ExportSurfaceOptions stl;
  stl.output = folder + "/x.stl";
  stl.patches = StlPatchMode::Solids;
  try
  {
    ExportSurface(mismatched, stl);
    ADD_FAILURE() << "a table without the caps was exported";
  }
  catch (const InputError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("patch id 2 of cell"), std::string::npos) << what;
    EXPECT_NE(what.find("is not in the surface's patch table"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_FALSE(std::filesystem::exists(stl.output));
  std::filesystem::remove_all(folder);
}

// Every writable format that carries patches, read back after an export of a labelled tube:
// the label formats (.vtp, .vtk) give back the table, each cell's patch and the coordinates;
// TetGen's facet markers each triangle's patch id; the STL's one file per patch the triangles
// of that patch.
TEST(LabelledSurfaceFlow, EveryFormatThatCarriesPatchesIsReadBackWithThem)
{
  PrepareForCfdOptions options;
  options.clip = false; // the tube's open ends as they are
  options.inletExtension = options.outletExtension = 0.0;
  const PrepareForCfdResult prepared = PrepareForCfd(test::MakeTube(0, 60, 3), options);
  ASSERT_EQ(prepared.patches.size(), 3u);
  const std::map<int, std::size_t> triangles = TrianglesPerPatch(prepared.surface);
  ASSERT_EQ(triangles.size(), 3u);
  const std::string folder = test::TemporaryFolder("bender_labelled_formats");
  std::vector<std::string> checked;
  for (const MeshFormat& format : MeshFormats())
  {
    if (!format.CanWrite() || !format.CanRead() ||
      !(format.patchLabels || format.namedPatches || format.regionPoint))
    {
      continue;
    }
    SCOPED_TRACE(format.name);
    checked.push_back(format.name);
    ExportSurfaceOptions exportOptions;
    exportOptions.output = folder + "/tube" + format.extensions.front();
    exportOptions.patches = format.namedPatches ? StlPatchMode::Files : StlPatchMode::Single;
    const ExportSurfaceResult exported = ExportSurface(prepared, exportOptions);
    ExpectSameTable(exported.patches, prepared.patches);
    if (format.namedPatches)
    {
      for (const PatchLabel& patch : prepared.patches)
      {
        const vtkSmartPointer<vtkPolyData> part =
          ReadMesh(folder + "/tube_" + patch.name + format.extensions.front());
        EXPECT_EQ(static_cast<std::size_t>(part->GetNumberOfPolys()), triangles.at(patch.id))
          << patch.name;
      }
      continue;
    }
    const vtkSmartPointer<vtkPolyData> back = ReadMesh(exportOptions.output);
    EXPECT_EQ(TrianglesPerPatch(back), triangles);
    if (format.patchLabels)
    {
      ExpectSameTable(ReadPatchLabels(back), prepared.patches);
      EXPECT_EQ(CellPatchIds(back), CellPatchIds(prepared.surface));
      EXPECT_EQ(test::MaxDifference(back, prepared.surface), 0.0);
    }
  }
  EXPECT_EQ(checked, (std::vector<std::string>{ "stl", "vtp", "vtk", "smesh", "poly" }));
  std::filesystem::remove_all(folder);
}
