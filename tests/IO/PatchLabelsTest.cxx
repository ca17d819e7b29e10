#include "PatchLabels.h"
#include "BenderErrors.h"
#include "LabelledSurface.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

namespace
{
// n triangles sharing nothing (labels only care about cells).
vtkSmartPointer<vtkPolyData> Triangles(int n)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  for (int t = 0; t < n; ++t)
  {
    const vtkIdType a = points->InsertNextPoint(t, 0, 0);
    const vtkIdType b = points->InsertNextPoint(t + 1, 0, 0);
    const vtkIdType c = points->InsertNextPoint(t, 1, 0);
    const vtkIdType ids[3] = { a, b, c };
    polys->InsertNextCell(3, ids);
  }
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}
} // namespace

TEST(PatchLabels, WrittenLabelsReadBackWithNamesAndTypes)
{
  auto mesh = Triangles(5);
  const std::vector<bender::PatchLabel> patches = { { 1, "wall", bender::PatchType::Wall },
    { 2, "ascending_aorta", bender::PatchType::Inlet },
    { 4, "outlet_2", bender::PatchType::Outlet } };
  bender::WritePatchLabels(mesh, { 1, 1, 2, 4, 1 }, patches);
  EXPECT_EQ(bender::CellPatchIds(mesh), (std::vector<int>{ 1, 1, 2, 4, 1 }));
  auto* face =
    vtkIntArray::SafeDownCast(mesh->GetCellData()->GetArray(bender::kModelFaceIdArrayName));
  ASSERT_NE(face, nullptr);
  EXPECT_EQ(face->GetValue(3), 4);
  const auto read = bender::ReadPatchLabels(mesh);
  ASSERT_EQ(read.size(), 3u);
  EXPECT_EQ(read[1].name, "ascending_aorta");
  EXPECT_EQ(read[1].type, bender::PatchType::Inlet);
  EXPECT_EQ(read[2].id, 4);
  EXPECT_EQ(read[2].type, bender::PatchType::Outlet);
  EXPECT_TRUE(bender::HasPatchLabels(mesh));
}

TEST(PatchLabels, LegacyPatchIdIsReadShiftedByOne)
{
  auto mesh = Triangles(3);
  vtkNew<vtkIntArray> legacy;
  legacy->SetName(bender::kLegacyPatchIdArrayName);
  legacy->InsertNextValue(0);
  legacy->InsertNextValue(2);
  legacy->InsertNextValue(1);
  mesh->GetCellData()->AddArray(legacy);
  EXPECT_EQ(bender::CellPatchIds(mesh), (std::vector<int>{ 1, 3, 2 }));
  const auto read = bender::ReadPatchLabels(mesh);
  ASSERT_EQ(read.size(), 3u);
  EXPECT_EQ(read[0].name, "wall");
  EXPECT_EQ(read[1].name, "cap_1");
  EXPECT_EQ(read[2].name, "cap_2");
  // Writing replaces the legacy array.
  bender::WritePatchLabels(mesh,
    bender::CellPatchIds(mesh),
    { { 1, "wall", bender::PatchType::Wall },
      { 2, "inlet", bender::PatchType::Inlet },
      { 3, "outlet_1", bender::PatchType::Outlet } });
  EXPECT_EQ(mesh->GetCellData()->GetArray(bender::kLegacyPatchIdArrayName), nullptr);
}

TEST(PatchLabels, UnlabelledSurfaceIsAllWall)
{
  auto mesh = Triangles(2);
  EXPECT_FALSE(bender::HasPatchLabels(mesh));
  EXPECT_EQ(bender::CellPatchIds(mesh), (std::vector<int>{ 1, 1 }));
  const auto read = bender::ReadPatchLabels(mesh);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].name, "wall");
}

TEST(PatchLabels, BadLabelsAreRefusedWithTheArrayNamed)
{
  auto mesh = Triangles(2);
  vtkNew<vtkDoubleArray> ids;
  ids->SetName(bender::kCellEntityIdsArrayName);
  ids->InsertNextValue(1);
  ids->InsertNextValue(std::nan(""));
  mesh->GetCellData()->AddArray(ids);
  try
  {
    bender::CellPatchIds(mesh);
    FAIL() << "a NaN label was accepted";
  }
  catch (const bender::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("CellEntityIds"), std::string::npos) << e.what();
  }
  ids->SetValue(1, 0.0);
  EXPECT_THROW(bender::CellPatchIds(mesh), bender::InputError);
  ids->SetValue(1, 1.5);
  EXPECT_THROW(bender::CellPatchIds(mesh), bender::InputError);
  ids->InsertNextValue(1);
  EXPECT_THROW(bender::CellPatchIds(mesh), bender::InputError); // 3 values for 2 cells
}

TEST(PatchLabels, WriteRefusesBadNamesUnknownIdsAndDuplicates)
{
  auto mesh = Triangles(2);
  using bender::PatchType;
  EXPECT_THROW(bender::WritePatchLabels(mesh, { 1, 2 }, { { 1, "wall", PatchType::Wall } }),
    bender::InputError);
  EXPECT_THROW(
    bender::WritePatchLabels(
      mesh, { 1, 2 }, { { 1, "wall", PatchType::Wall }, { 2, "in let", PatchType::Inlet } }),
    bender::InputError);
  EXPECT_THROW(
    bender::WritePatchLabels(
      mesh, { 1, 2 }, { { 1, "wall", PatchType::Wall }, { 2, "wall", PatchType::Inlet } }),
    bender::InputError);
  EXPECT_THROW(
    bender::WritePatchLabels(mesh, { 1 }, { { 1, "wall", PatchType::Wall } }), bender::InputError);
  EXPECT_FALSE(bender::IsValidPatchName("1outlet"));
  EXPECT_TRUE(bender::IsValidPatchName("outlet_1"));
}

TEST(PatchLabels, CorruptFieldDataNamesAreRefused)
{
  auto mesh = Triangles(2);
  bender::WritePatchLabels(mesh,
    { 1, 2 },
    { { 1, "wall", bender::PatchType::Wall }, { 2, "inlet", bender::PatchType::Inlet } });
  auto* names = vtkStringArray::SafeDownCast(
    mesh->GetFieldData()->GetAbstractArray(bender::kPatchNamesArrayName));
  ASSERT_NE(names, nullptr);
  names->SetValue(1, "wall");
  EXPECT_THROW(bender::ReadPatchLabels(mesh), bender::InputError);
  names->SetValue(1, "bad name;rm");
  EXPECT_THROW(bender::ReadPatchLabels(mesh), bender::InputError);
}

TEST(LabelledSurface, ReadsTheTableWrittenWithTheSurface)
{
  auto mesh = Triangles(4);
  const std::vector<bender::PatchLabel> written = { { 1, "wall", bender::PatchType::Wall },
    { 2, "inlet", bender::PatchType::Inlet },
    { 3, "outlet_1", bender::PatchType::Outlet } };
  bender::WritePatchLabels(mesh, { 1, 2, 1, 3 }, written);
  const bender::LabelledSurface labelled = bender::ReadLabelledSurface(mesh);
  EXPECT_EQ(labelled.surface.Get(), mesh.Get());
  ASSERT_EQ(labelled.patches.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i)
  {
    EXPECT_EQ(labelled.patches[i].id, written[i].id);
    EXPECT_EQ(labelled.patches[i].name, written[i].name);
    EXPECT_EQ(labelled.patches[i].type, written[i].type);
  }
}

TEST(LabelledSurface, BadLabelsAreRefusedInOneLineNamingTheArray)
{
  auto mesh = Triangles(2);
  vtkNew<vtkDoubleArray> ids;
  ids->SetName(bender::kCellEntityIdsArrayName);
  ids->InsertNextValue(1);
  ids->InsertNextValue(0);
  mesh->GetCellData()->AddArray(ids);
  try
  {
    bender::ReadLabelledSurface(mesh);
    FAIL() << "a label below 1 was accepted";
  }
  catch (const bender::InputError& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find(bender::kCellEntityIdsArrayName), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}
