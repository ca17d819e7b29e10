// MeshTopology: triangles of a polydata, edges, boundary loops, components.

#include "MeshTopology.h"

#include <vtkAppendPolyData.h>
#include <vtkCellArray.h>
#include <vtkCylinderSource.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>
#include <vtkTriangleFilter.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace
{

vtkSmartPointer<vtkPolyData> Triangulated(vtkAlgorithm* source)
{
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(source->GetOutputPort());
  tri->Update();
  return tri->GetOutput();
}

TEST(MeshTopology, CollectTrianglesFansPolygonsAndConvertsStrips)
{
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 6; ++i)
  {
    points->InsertNextPoint(i, i % 2, 0);
  }
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 3, 2 };
  polys->InsertNextCell(4, quad);
  mesh->SetPolys(polys);
  vtkNew<vtkCellArray> strips;
  const vtkIdType strip[4] = { 2, 3, 4, 5 };
  strips->InsertNextCell(4, strip);
  mesh->SetStrips(strips);
  const std::vector<std::int64_t> expected{ 0, 1, 3, 0, 3, 2, 2, 3, 4, 4, 3, 5 };
  EXPECT_EQ(bender::CollectTriangles(mesh), expected);
  EXPECT_TRUE(bender::CollectTriangles(nullptr).empty());
}

TEST(MeshTopology, ClosedSphereHasNoBoundaryAndOneComponent)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(12);
  const auto tris = bender::CollectTriangles(Triangulated(sphere));
  const bender::TriangleEdges edges(tris);
  EXPECT_EQ(edges.Edges().size() * 2, tris.size()); // E = 3F / 2 on a closed surface
  for (const bender::MeshEdge& e : edges.Edges())
  {
    ASSERT_EQ(e.uses, 2u);
    ASSERT_LT(e.lo, e.hi);
    // A consistently oriented surface runs each edge once each way.
    EXPECT_NE(edges.Uses()[e.first].forward, edges.Uses()[e.first + 1].forward);
  }
  EXPECT_TRUE(bender::BoundaryLoops(tris).empty());
  std::size_t count = 0;
  const auto labels = bender::TriangleComponents(tris, count);
  EXPECT_EQ(count, 1u);
  EXPECT_EQ(std::set<std::int64_t>(labels.begin(), labels.end()), std::set<std::int64_t>{ 0 });
}

TEST(MeshTopology, OpenTubeHasTwoClosedLoops)
{
  vtkNew<vtkCylinderSource> tube;
  tube->SetResolution(20);
  tube->CappingOff();
  const auto tris = bender::CollectTriangles(Triangulated(tube));
  const auto loops = bender::BoundaryLoops(tris);
  ASSERT_EQ(loops.size(), 2u);
  std::set<std::int64_t> seen;
  for (const bender::BoundaryChain& loop : loops)
  {
    EXPECT_TRUE(loop.closed);
    EXPECT_EQ(loop.edges, 20u);
    EXPECT_EQ(loop.vertices.size(), 20u);
    seen.insert(loop.vertices.begin(), loop.vertices.end());
  }
  EXPECT_EQ(seen.size(), 40u); // every rim vertex once
}

TEST(MeshTopology, ComponentsAreLabelledInOrderOfFirstTriangle)
{
  vtkNew<vtkSphereSource> a;
  vtkNew<vtkSphereSource> b;
  b->SetCenter(5, 0, 0);
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(a->GetOutputPort());
  both->AddInputConnection(b->GetOutputPort());
  const auto tris = bender::CollectTriangles(Triangulated(both));
  const std::size_t first = bender::CollectTriangles(Triangulated(a)).size() / 3;
  std::size_t count = 0;
  const auto labels = bender::TriangleComponents(tris, count);
  EXPECT_EQ(count, 2u);
  for (std::size_t t = 0; t < labels.size(); ++t)
  {
    ASSERT_EQ(labels[t], t < first ? 0 : 1) << t;
  }
}

// Two triangles touching at one vertex: the boundary passes that vertex twice, so the walk
// cannot tell the loops apart there and reports what it followed as not closed.
TEST(MeshTopology, BowTieBoundaryIsNotAClosedLoop)
{
  const std::vector<std::int64_t> tris{ 0, 1, 2, 2, 3, 4 };
  const auto chains = bender::BoundaryLoops(tris);
  std::size_t edges = 0;
  for (const auto& c : chains)
  {
    edges += c.edges;
  }
  EXPECT_EQ(edges, 6u);
  EXPECT_TRUE(std::any_of(chains.begin(), chains.end(), [](const auto& c) { return !c.closed; }));
  // An inconsistently oriented pair: the shared edge is not a boundary, and it runs the
  // same way in both triangles.
  const bender::TriangleEdges edgesOf({ 0, 1, 2, 0, 1, 3 });
  const auto shared = std::find_if(edgesOf.Edges().begin(),
    edgesOf.Edges().end(),
    [](const bender::MeshEdge& e) { return e.uses == 2; });
  ASSERT_NE(shared, edgesOf.Edges().end());
  EXPECT_EQ(edgesOf.Uses()[shared->first].forward, edgesOf.Uses()[shared->first + 1].forward);
  // Ids outside the point range are left out when the range is given.
  EXPECT_EQ(bender::TriangleEdges({ 0, 1, 7 }, 3).Edges().size(), 0u);
}

} // namespace
