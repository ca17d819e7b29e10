#include "MeshTopology.h"

#include "UnionFind.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <tuple>

namespace bender
{

std::vector<std::int64_t> CollectTriangles(vtkPolyData* mesh)
{
  std::vector<std::int64_t> tris;
  if (!mesh)
  {
    return tris;
  }
  if (mesh->GetPolys())
  {
    auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType npts;
      const vtkIdType* pts;
      it->GetCurrentCell(npts, pts);
      for (vtkIdType k = 1; k + 1 < npts; ++k)
      {
        tris.insert(tris.end(), { pts[0], pts[k], pts[k + 1] });
      }
    }
  }
  if (mesh->GetStrips())
  {
    auto it = vtk::TakeSmartPointer(mesh->GetStrips()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType npts;
      const vtkIdType* pts;
      it->GetCurrentCell(npts, pts);
      for (vtkIdType k = 0; k + 2 < npts; ++k)
      {
        if (k % 2 == 0)
        {
          tris.insert(tris.end(), { pts[k], pts[k + 1], pts[k + 2] });
        }
        else
        {
          tris.insert(tris.end(), { pts[k + 1], pts[k], pts[k + 2] });
        }
      }
    }
  }
  return tris;
}

namespace
{
bool Usable(const std::int64_t* v, std::int64_t points)
{
  return points < 0 ||
    (v[0] >= 0 && v[0] < points && v[1] >= 0 && v[1] < points && v[2] >= 0 && v[2] < points);
}
} // namespace

TriangleEdges::TriangleEdges(const std::vector<std::int64_t>& triangles, std::int64_t points)
{
  struct Record
  {
    std::int64_t lo, hi, triangle;
    bool forward;
  };
  std::vector<Record> records;
  records.reserve(triangles.size());
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
  {
    const std::int64_t* v = &triangles[t];
    if (!Usable(v, points))
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = v[k], b = v[(k + 1) % 3];
      if (a != b)
      {
        records.push_back(
          { std::min(a, b), std::max(a, b), static_cast<std::int64_t>(t / 3), a < b });
      }
    }
  }
  std::sort(records.begin(),
    records.end(),
    [](const Record& x, const Record& y)
    { return std::tie(x.lo, x.hi, x.triangle) < std::tie(y.lo, y.hi, y.triangle); });
  this->UseList.reserve(records.size());
  for (std::size_t i = 0; i < records.size(); ++i)
  {
    if (i == 0 || records[i].lo != records[i - 1].lo || records[i].hi != records[i - 1].hi)
    {
      this->EdgeList.push_back({ records[i].lo, records[i].hi, i, 0 });
    }
    ++this->EdgeList.back().uses;
    this->UseList.push_back({ records[i].triangle, records[i].forward });
  }
}

std::vector<std::array<std::int64_t, 2>> TriangleEdges::DirectedBoundary() const
{
  std::vector<std::array<std::int64_t, 2>> directed;
  for (const MeshEdge& e : this->EdgeList)
  {
    if (e.uses == 1)
    {
      directed.push_back(this->UseList[e.first].forward
          ? std::array<std::int64_t, 2>{ e.lo, e.hi }
          : std::array<std::int64_t, 2>{ e.hi, e.lo });
    }
  }
  return directed;
}

std::vector<BoundaryChain> FollowBoundary(std::vector<std::array<std::int64_t, 2>> directed)
{
  std::multimap<std::int64_t, std::int64_t> next;
  for (const auto& e : directed)
  {
    next.emplace(e[0], e[1]);
  }
  std::vector<BoundaryChain> chains;
  while (!next.empty())
  {
    auto it = next.begin();
    const std::int64_t start = it->first;
    BoundaryChain chain;
    chain.vertices.push_back(start);
    std::int64_t current = it->second;
    next.erase(it);
    chain.edges = 1;
    chain.closed = true;
    while (current != start)
    {
      if (next.count(current) != 1)
      {
        chain.closed = false; // the boundary branches (touching loops) or stops here
      }
      const auto step = next.find(current);
      if (step == next.end())
      {
        chain.vertices.push_back(current);
        break;
      }
      chain.vertices.push_back(current);
      current = step->second;
      next.erase(step);
      ++chain.edges;
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

std::vector<BoundaryChain> BoundaryLoops(const std::vector<std::int64_t>& triangles,
  std::int64_t points)
{
  return FollowBoundary(TriangleEdges(triangles, points).DirectedBoundary());
}

std::vector<std::int64_t> TriangleComponents(const std::vector<std::int64_t>& triangles,
  std::size_t& count,
  std::int64_t points)
{
  const std::size_t n = triangles.size() / 3;
  UnionFind sets(n);
  const TriangleEdges edges(triangles, points);
  for (const MeshEdge& e : edges.Edges())
  {
    for (std::size_t k = 1; k < e.uses; ++k)
    {
      sets.Join(static_cast<std::size_t>(edges.Uses()[e.first].triangle),
        static_cast<std::size_t>(edges.Uses()[e.first + k].triangle));
    }
  }
  std::vector<std::int64_t> label(n, -1);
  count = 0;
  std::vector<std::int64_t> rootLabel(n, -1);
  for (std::size_t t = 0; t < n; ++t)
  {
    const std::size_t root = sets.Find(t);
    if (rootLabel[root] < 0)
    {
      rootLabel[root] = static_cast<std::int64_t>(count++);
    }
    label[t] = rootLabel[root];
  }
  return label;
}

} // namespace bender
