#include "BenderMeshCheck.h"

#include "MeshCheckPasses.h"
#include "UnionFind.h"
#include "Vec3.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkMath.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace bender
{
namespace
{
using mesh_check::PointOf;

Vec3 Min(const Vec3& a, const Vec3& b)
{
  return { std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z) };
}
Vec3 Max(const Vec3& a, const Vec3& b)
{
  return { std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z) };
}

void Accumulate(MeshStatistic& s, double v, vtkIdType& n)
{
  if (n == 0)
  {
    s.min = s.max = v;
  }
  s.min = std::min(s.min, v);
  s.max = std::max(s.max, v);
  s.mean += v;
  ++n;
}

std::string Plural(vtkIdType n, const char* word)
{
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}
} // namespace

namespace
{
// The points of a mesh and which triangles the geometric measures can use.
struct MeshSamples
{
  std::vector<Vec3> points;
  std::vector<std::uint8_t> finite; // per point
  std::vector<std::uint8_t> usable; // per triangle: valid ids, finite, not degenerate
  vtkIdType badIds = 0;             // triangles with point ids out of range
};

// Points, non-finite points and the bounding box diagonal.
MeshSamples ReadPoints(vtkPolyData* mesh, MeshCheckReport& report, double& diagonal)
{
  const vtkIdType np = mesh->GetNumberOfPoints();
  MeshSamples samples;
  samples.points.resize(static_cast<std::size_t>(np));
  samples.finite.assign(static_cast<std::size_t>(np), 1);
  Vec3 lo(HUGE_VAL, HUGE_VAL, HUGE_VAL), hi(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
  for (vtkIdType i = 0; i < np; ++i)
  {
    samples.points[i] = PointOf(mesh, i);
    if (!IsFinite(samples.points[i]))
    {
      samples.finite[i] = 0;
      ++report.nonFinitePoints;
      continue;
    }
    lo = Min(lo, samples.points[i]);
    hi = Max(hi, samples.points[i]);
  }
  diagonal = report.nonFinitePoints == np ? 0.0 : Norm(hi - lo);
  return samples;
}

// Area, volume, edge lengths, minimum angles, degenerate triangles and unused points; marks
// the triangles the other measures can use.
void MeasureTriangles(const std::vector<std::int64_t>& tris,
  double diagonal,
  MeshSamples& samples,
  MeshCheckReport& report)
{
  const vtkIdType nt = static_cast<vtkIdType>(tris.size() / 3);
  const auto np = static_cast<std::int64_t>(samples.points.size());
  const std::vector<Vec3>& pts = samples.points;
  samples.usable.assign(static_cast<std::size_t>(nt), 1);
  std::vector<std::uint8_t> used(static_cast<std::size_t>(np), 0);
  vtkIdType lengthCount = 0, angleCount = 0;
  double volume6 = 0.0;
  for (vtkIdType t = 0; t < nt; ++t)
  {
    const std::int64_t* v = &tris[3 * t];
    if (!(v[0] >= 0 && v[0] < np && v[1] >= 0 && v[1] < np && v[2] >= 0 && v[2] < np))
    {
      samples.usable[t] = 0;
      ++samples.badIds;
      continue;
    }
    used[v[0]] = used[v[1]] = used[v[2]] = 1;
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
    {
      ++report.degenerateTriangles;
      samples.usable[t] = 0;
      continue;
    }
    if (!samples.finite[v[0]] || !samples.finite[v[1]] || !samples.finite[v[2]])
    {
      samples.usable[t] = 0;
      continue;
    }
    const Vec3 &a = pts[v[0]], &b = pts[v[1]], &c = pts[v[2]];
    const double area2 = Norm(Cross(b - a, c - a));
    report.area += 0.5 * area2;
    volume6 += Dot(a, Cross(b, c));
    if (area2 <= 2e-14 * diagonal * diagonal)
    {
      ++report.degenerateTriangles;
      samples.usable[t] = 0;
    }
    for (double l : { Norm(b - a), Norm(c - b), Norm(a - c) })
    {
      Accumulate(report.edgeLength, l, lengthCount);
    }
    if (samples.usable[t])
    {
      double minAngle = 180.0;
      const std::array<const Vec3*, 3> p{ &a, &b, &c };
      for (int k = 0; k < 3; ++k)
      {
        const Vec3 u = *p[(k + 1) % 3] - *p[k];
        const Vec3 w = *p[(k + 2) % 3] - *p[k];
        minAngle = std::min(minAngle, std::atan2(Norm(Cross(u, w)), Dot(u, w)) * 180.0 / M_PI);
      }
      Accumulate(report.minimumAngle, minAngle, angleCount);
    }
  }
  report.edgeLength.mean = lengthCount ? report.edgeLength.mean / lengthCount : 0.0;
  report.minimumAngle.mean = angleCount ? report.minimumAngle.mean / angleCount : 0.0;
  report.volume = volume6 / 6.0;
  report.unusedPoints = std::count(used.begin(), used.end(), 0);
}

// Boundary, non-manifold and inconsistently oriented edges, components and boundary loops.
// Returns the vertices on non-manifold edges.
std::vector<std::uint8_t> CheckEdges(const std::vector<std::int64_t>& tris,
  vtkIdType np,
  MeshCheckReport& report)
{
  const TriangleEdges edges(tris, np); // triangles with ids out of range left out
  UnionFind components(tris.size() / 3);
  std::vector<std::uint8_t> onNonManifoldEdge(static_cast<std::size_t>(np), 0);
  for (const MeshEdge& e : edges.Edges())
  {
    const EdgeUse* use = &edges.Uses()[e.first];
    for (std::size_t k = 1; k < e.uses; ++k)
    {
      // Triangles sharing an edge are in one component.
      components.Join(
        static_cast<std::size_t>(use[0].triangle), static_cast<std::size_t>(use[k].triangle));
    }
    if (e.uses == 1)
    {
      ++report.boundaryEdges;
    }
    else if (e.uses == 2)
    {
      report.inconsistentEdges += use[0].forward == use[1].forward ? 1 : 0;
    }
    else
    {
      ++report.nonManifoldEdges;
      onNonManifoldEdge[e.lo] = onNonManifoldEdge[e.hi] = 1;
    }
  }
  report.components = static_cast<vtkIdType>(components.Sets());
  report.closed = report.boundaryEdges == 0 && report.nonManifoldEdges == 0;

  // Boundary loops: follow the directed boundary edges (an open chain, from an inconsistent
  // orientation or a non-manifold vertex, counts as a loop too).
  for (const BoundaryChain& chain : FollowBoundary(edges.DirectedBoundary()))
  {
    report.boundaryLoops.push_back(static_cast<vtkIdType>(chain.edges));
  }
  std::sort(report.boundaryLoops.rbegin(), report.boundaryLoops.rend());
  return onNonManifoldEdge;
}

// Non-manifold vertices: those on non-manifold edges, and those whose triangles form more
// than one edge-connected fan (e.g. two cones touching at their tips).
vtkIdType CountNonManifoldVertices(const std::vector<std::int64_t>& tris,
  vtkIdType np,
  std::vector<std::uint8_t> nonManifold)
{
  const vtkIdType nt = static_cast<vtkIdType>(tris.size() / 3);
  const auto valid = [&](vtkIdType t)
  {
    return tris[3 * t] >= 0 && tris[3 * t] < np && tris[3 * t + 1] >= 0 && tris[3 * t + 1] < np &&
      tris[3 * t + 2] >= 0 && tris[3 * t + 2] < np;
  };
  // Triangles around each vertex (CSR).
  std::vector<vtkIdType> start(static_cast<std::size_t>(np + 1), 0);
  for (vtkIdType t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3 && valid(t); ++k)
    {
      ++start[tris[3 * t + k] + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<vtkIdType> fill(start.begin(), start.end() - 1);
  std::vector<vtkIdType> incident(static_cast<std::size_t>(start[np]));
  for (vtkIdType t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3 && valid(t); ++k)
    {
      incident[fill[tris[3 * t + k]]++] = t;
    }
  }
  for (vtkIdType v = 0; v < np; ++v)
  {
    const vtkIdType first = start[v];
    const auto k = static_cast<std::size_t>(start[v + 1] - first);
    if (k <= 1 || nonManifold[v])
    {
      continue;
    }
    // Fans: incident triangles sharing a second vertex are joined.
    UnionFind fans(k);
    for (std::size_t a = 0; a < k; ++a)
    {
      const std::int64_t* ta = &tris[3 * incident[first + a]];
      for (std::size_t b = a + 1; b < k; ++b)
      {
        const std::int64_t* tb = &tris[3 * incident[first + b]];
        bool share = false;
        for (int i = 0; i < 3 && !share; ++i)
        {
          share = ta[i] != v && (ta[i] == tb[0] || ta[i] == tb[1] || ta[i] == tb[2]);
        }
        if (share)
        {
          fans.Join(a, b);
        }
      }
    }
    nonManifold[v] = fans.Sets() > 1 ? 1 : 0;
  }
  return std::count(nonManifold.begin(), nonManifold.end(), 1);
}

// The problems of a report, one short sentence each.
std::vector<std::string> Problems(const MeshCheckReport& report,
  vtkIdType badIds,
  const MeshCheckOptions& options)
{
  std::vector<std::string> problems;
  const auto add = [&](vtkIdType n, const std::string& text)
  {
    if (n > 0)
    {
      problems.push_back(text);
    }
  };
  add(badIds, Plural(badIds, "triangle") + " with point ids out of range");
  add(report.nonFinitePoints, Plural(report.nonFinitePoints, "non-finite point"));
  add(report.nonManifoldEdges, Plural(report.nonManifoldEdges, "non-manifold edge"));
  add(report.nonManifoldVertices, Plural(report.nonManifoldVertices, "non-manifold vertex"));
  add(report.inconsistentEdges,
    Plural(report.inconsistentEdges, "edge") + " with inconsistent orientation");
  add(report.degenerateTriangles, Plural(report.degenerateTriangles, "degenerate triangle"));
  add(
    report.selfIntersections, Plural(report.selfIntersections, "self-intersecting triangle pair"));
  add(report.flippedTriangles,
    Plural(report.flippedTriangles, "flipped triangle") + " (space inverted by the warp)");
  const auto loops = static_cast<vtkIdType>(report.boundaryLoops.size());
  add(options.requireClosed ? loops : 0, "open: " + Plural(loops, "boundary loop"));
  return problems;
}
} // namespace

MeshCheckReport CheckMesh(vtkPolyData* mesh, vtkPolyData* before, const MeshCheckOptions& options)
{
  MeshCheckReport report;
  if (!mesh)
  {
    report.problems.push_back("no mesh");
    return report;
  }
  const vtkIdType np = mesh->GetNumberOfPoints();
  report.points = np;
  const std::vector<std::int64_t> tris = CollectTriangles(mesh);
  report.triangles = static_cast<vtkIdType>(tris.size() / 3);
  if (report.triangles == 0)
  {
    report.problems.push_back("the mesh has no triangles");
    return report;
  }

  double diagonal = 0.0;
  MeshSamples samples = ReadPoints(mesh, report, diagonal);
  MeasureTriangles(tris, diagonal, samples, report);
  report.nonManifoldVertices = CountNonManifoldVertices(tris, np, CheckEdges(tris, np, report));
  if (options.selfIntersections)
  {
    mesh_check::CheckSelfIntersections(
      tris, samples.points, samples.usable, options.maxExamples, report);
  }
  if (before)
  {
    if (before->GetNumberOfPoints() != np || CollectTriangles(before) != tris)
    {
      report.flipsNote = "the mesh before the warp has other points or triangles (e.g. after "
                         "subdivision): flips not checked";
    }
    else
    {
      report.flipsChecked = true;
      report.flippedTriangles =
        mesh_check::CountInvertedTriangles(tris, samples.usable, before, samples.points);
    }
  }
  report.problems = Problems(report, samples.badIds, options);
  return report;
}

} // namespace bender
