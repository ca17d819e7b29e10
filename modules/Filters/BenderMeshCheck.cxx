#include "BenderMeshCheck.h"

#include "Vec3.h"

#include <nlohmann/json.hpp>

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkMath.h>
#include <vtkPolyData.h>
#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>

namespace bender
{
namespace
{
Vec3 PointOf(vtkPolyData* mesh, vtkIdType i)
{
  double x[3];
  mesh->GetPoint(i, x);
  return { x[0], x[1], x[2] };
}
Vec3 Min(const Vec3& a, const Vec3& b)
{
  return { std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z) };
}
Vec3 Max(const Vec3& a, const Vec3& b)
{
  return { std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z) };
}
int Sign(double v)
{
  return (v > 0) - (v < 0);
}

// Sign of the volume of (a, b, c, d), > 0 when d is above the plane of (a, b, c), and 0 when d
// is within a relative 1e-6 of that plane: the volume compared with the product of the three edge
// lengths from a (the sine of the angles involved). Coordinates stored as floats (STL, most VTP
// files) put points that are coplanar by construction (the facets of a cylinder, a flat cap) up to
// about 1e-7 off each other's planes, with random signs; without the tolerance two disjoint
// triangles of one flat strip were reported as crossing. A genuine crossing at an angle of more
// than about 1e-6 rad is still found.
int OrientSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double volume = Dot(Cross(u, v), w);
  const double scale = std::sqrt(Dot(u, u) * Dot(v, v) * Dot(w, w));
  return std::abs(volume) <= 1e-6 * scale ? 0 : Sign(volume);
}

// Segment pq properly crosses triangle abc (strictly: touching and coplanar cases are not
// counted, so that triangles meeting along a shared border are never reported).
bool SegmentCrossesTriangle(const Vec3& p,
  const Vec3& q,
  const Vec3& a,
  const Vec3& b,
  const Vec3& c)
{
  const int sp = OrientSign(a, b, c, p);
  const int sq = OrientSign(a, b, c, q);
  if (sp == 0 || sq == 0 || sp == sq)
  {
    return false;
  }
  const int s1 = OrientSign(p, q, a, b);
  const int s2 = OrientSign(p, q, b, c);
  const int s3 = OrientSign(p, q, c, a);
  return s1 != 0 && s1 == s2 && s2 == s3;
}

// Two non-coplanar triangles intersect iff an edge of one crosses the other: each end of
// their intersection segment lies on the border of one of them.
bool TrianglesIntersect(const std::array<Vec3, 3>& t, const std::array<Vec3, 3>& u)
{
  for (int e = 0; e < 3; ++e)
  {
    if (SegmentCrossesTriangle(t[e], t[(e + 1) % 3], u[0], u[1], u[2]) ||
      SegmentCrossesTriangle(u[e], u[(e + 1) % 3], t[0], t[1], t[2]))
    {
      return true;
    }
  }
  return false;
}

// Space inversion (paper 3.8) turns a piece of surface inside out: the warp is locally
// orientation-reversing, while a rigid motion, however large its rotation, is not. A triangle
// counts as flipped when
// - it lies on a fold: across one of its edges the two normals were within 60 degrees of each
//   other before the warp and more than 120 degrees apart after it; a continuous warp that
//   inverts space folds the surface along the border of the inverted region; or
// - its normal after the warp opposes the image of its normal before under the local
//   rotation, the best-fitting proper rotation (Kabsch) carrying the triangle and its
//   edge-neighbours' opposite vertices from before to after (a mirrored, curved neighbourhood
//   has no proper rotation fitting it). On a flat neighbourhood a mirror cannot be told from
//   a half turn, so this second test only adds what the first misses on curved surfaces.
vtkIdType CountInvertedTriangles(const std::vector<std::int64_t>& tris,
  const std::vector<std::uint8_t>& usable,
  vtkPolyData* before,
  const std::vector<Vec3>& after)
{
  const vtkIdType nt = static_cast<vtkIdType>(tris.size() / 3);
  // Across each edge of each usable triangle: the triangle on its other side (-1: none), from
  // the edges of the usable triangles (the others masked out of the edge list).
  std::vector<std::int64_t> masked(tris);
  for (vtkIdType t = 0; t < nt; ++t)
  {
    if (!usable[t])
    {
      masked[3 * t] = masked[3 * t + 1] = masked[3 * t + 2] = -1;
    }
  }
  const TriangleEdges edges(masked, static_cast<std::int64_t>(after.size()));
  std::vector<std::array<vtkIdType, 3>> across(static_cast<std::size_t>(nt), { { -1, -1, -1 } });
  const auto localEdge = [&](vtkIdType t, const MeshEdge& e)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = tris[3 * t + k], b = tris[3 * t + (k + 1) % 3];
      if (std::min(a, b) == e.lo && std::max(a, b) == e.hi)
      {
        return k;
      }
    }
    return 0;
  };
  std::vector<std::array<vtkIdType, 2>> pairs; // triangles sharing a manifold-like edge
  for (const MeshEdge& e : edges.Edges())
  {
    if (e.uses < 2)
    {
      continue;
    }
    const vtkIdType t = edges.Uses()[e.first].triangle;
    const vtkIdType u = edges.Uses()[e.first + 1].triangle;
    across[t][localEdge(t, e)] = u;
    across[u][localEdge(u, e)] = t;
    pairs.push_back({ { t, u } });
  }
  std::vector<Vec3> pre(static_cast<std::size_t>(before->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < before->GetNumberOfPoints(); ++i)
  {
    pre[i] = PointOf(before, i);
  }
  auto normal = [&](const std::vector<Vec3>& x, vtkIdType t)
  {
    const std::int64_t* v = &tris[3 * t];
    return Cross(x[v[1]] - x[v[0]], x[v[2]] - x[v[0]]);
  };
  std::vector<std::uint8_t> folded(static_cast<std::size_t>(nt), 0);
  for (const auto& [t, u] : pairs)
  {
    // A fold turns the angle between neighbouring normals from small to nearly 180 degrees;
    // a sharp but genuine bend of the surface does not come near that.
    const Vec3 bt = normal(pre, t), bu = normal(pre, u), at = normal(after, t),
               au = normal(after, u);
    const double nb = std::sqrt(Dot(bt, bt) * Dot(bu, bu));
    const double na = std::sqrt(Dot(at, at) * Dot(au, au));
    if (nb > 0.0 && na > 0.0 && Dot(bt, bu) > 0.5 * nb && Dot(at, au) < -0.5 * na)
    {
      folded[t] = folded[u] = 1;
    }
  }
  vtkIdType flipped = 0;
  for (vtkIdType t = 0; t < nt; ++t)
  {
    if (!usable[t])
    {
      continue;
    }
    if (folded[t])
    {
      ++flipped;
      continue;
    }
    std::vector<std::int64_t> ids(tris.begin() + 3 * t, tris.begin() + 3 * t + 3);
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = tris[3 * t + e], b = tris[3 * t + (e + 1) % 3];
      const vtkIdType u = across[t][e];
      if (u < 0)
      {
        continue;
      }
      for (int k = 0; k < 3; ++k)
      {
        const std::int64_t v = tris[3 * u + k];
        if (v != a && v != b)
        {
          ids.push_back(v);
        }
      }
    }
    // Kabsch: H = sum (p - cp)(q - cq)^T, R = V diag(1, 1, det) U^T.
    Vec3 cp, cq;
    for (std::int64_t v : ids)
    {
      cp += pre[v];
      cq += after[v];
    }
    cp = cp / static_cast<double>(ids.size());
    cq = cq / static_cast<double>(ids.size());
    double h[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
    for (std::int64_t v : ids)
    {
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          h[r][c] += (pre[v][r] - cp[r]) * (after[v][c] - cq[c]);
        }
      }
    }
    double u[3][3], w[3], vt[3][3];
    vtkMath::SingularValueDecomposition3x3(h, u, w, vt);
    // vtkMath gives H = U W VT with proper rotations U and VT; when det H < 0 all of w are
    // negative. Then H = (-U) |W| VT, and the best proper rotation (Kabsch) is
    // V D (-U)^T with D = diag(1, 1, -1) on the smallest singular value.
    double sign[3] = { 1.0, 1.0, 1.0 };
    if (w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0)
    {
      int smallest = 0;
      for (int k = 1; k < 3; ++k)
      {
        if (std::abs(w[k]) < std::abs(w[smallest]))
        {
          smallest = k;
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        sign[k] = k == smallest ? 1.0 : -1.0; // D times the -1 of -U
      }
    }
    double rot[3][3]; // R = V S U^T maps before to after
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        rot[r][c] = vt[0][r] * sign[0] * u[c][0] + vt[1][r] * sign[1] * u[c][1] +
          vt[2][r] * sign[2] * u[c][2];
      }
    }
    const std::int64_t* tv = &tris[3 * t];
    const Vec3 n0 = Cross(pre[tv[1]] - pre[tv[0]], pre[tv[2]] - pre[tv[0]]);
    const Vec3 n1 = Cross(after[tv[1]] - after[tv[0]], after[tv[2]] - after[tv[0]]);
    const auto row = [&](int r) { return rot[r][0] * n0.x + rot[r][1] * n0.y + rot[r][2] * n0.z; };
    const Vec3 rn0(row(0), row(1), row(2));
    if (Dot(rn0, n1) < 0)
    {
      ++flipped;
    }
  }
  return flipped;
}

// The self-intersection search over a uniform grid of triangle bounding boxes, each pair of
// overlapping boxes tested once, cells in parallel. Kept instead of vtkStaticCellLocator:
// MeshCheck.SelfIntersectionPairsMatchAnAllPairsSearch proves it finds exactly the pairs of
// an all-pairs search, and on the million-triangle sphere of MeshCheck.MillionTrianglesInSeconds
// one FindCellsWithinBounds query per triangle took 338 s against 6 s for this grid
// (measured once on the shared, loaded build machine; VTK 9.1).
struct IntersectionWorker
{
  const std::vector<std::int64_t>& Tris;
  const std::vector<Vec3>& Pts;
  const std::vector<std::uint8_t>& Usable;
  const std::vector<std::array<double, 6>>& Boxes;
  const std::vector<vtkIdType>& CellStart;
  const std::vector<vtkIdType>& CellTris;
  std::array<int, 3> Dims;
  Vec3 Origin;
  double Size;
  std::size_t MaxExamples;
  vtkSMPThreadLocal<vtkIdType> Count;
  vtkSMPThreadLocal<std::vector<std::pair<vtkIdType, vtkIdType>>> Examples;

  int CellOf(double v, int axis) const
  {
    const int c = static_cast<int>((v - this->Origin[axis]) / this->Size);
    return std::clamp(c, 0, this->Dims[axis] - 1);
  }
  void operator()(vtkIdType begin, vtkIdType end)
  {
    vtkIdType& count = this->Count.Local();
    auto& examples = this->Examples.Local();
    for (vtkIdType cell = begin; cell < end; ++cell)
    {
      const vtkIdType first = this->CellStart[cell];
      const vtkIdType last = this->CellStart[cell + 1];
      const int cx = static_cast<int>(cell % this->Dims[0]);
      const int cy = static_cast<int>((cell / this->Dims[0]) % this->Dims[1]);
      const int cz =
        static_cast<int>(cell / (static_cast<vtkIdType>(this->Dims[0]) * this->Dims[1]));
      for (vtkIdType i = first; i < last; ++i)
      {
        const vtkIdType ti = this->CellTris[i];
        const auto& bi = this->Boxes[ti];
        const std::int64_t* vi = &this->Tris[3 * ti];
        for (vtkIdType j = i + 1; j < last; ++j)
        {
          const vtkIdType tj = this->CellTris[j];
          const auto& bj = this->Boxes[tj];
          bool overlap = true;
          for (int a = 0; a < 3; ++a)
          {
            overlap = overlap && bi[a] <= bj[3 + a] && bj[a] <= bi[3 + a];
          }
          if (!overlap)
          {
            continue;
          }
          // Test each pair once: in the cell holding the low corner of the boxes' overlap.
          if (this->CellOf(std::max(bi[0], bj[0]), 0) != cx ||
            this->CellOf(std::max(bi[1], bj[1]), 1) != cy ||
            this->CellOf(std::max(bi[2], bj[2]), 2) != cz)
          {
            continue;
          }
          const std::int64_t* vj = &this->Tris[3 * tj];
          bool shared = false;
          for (int a = 0; a < 3 && !shared; ++a)
          {
            shared = vi[a] == vj[0] || vi[a] == vj[1] || vi[a] == vj[2];
          }
          if (shared)
          {
            continue;
          }
          const std::array<Vec3, 3> t{ this->Pts[vi[0]], this->Pts[vi[1]], this->Pts[vi[2]] };
          const std::array<Vec3, 3> u{ this->Pts[vj[0]], this->Pts[vj[1]], this->Pts[vj[2]] };
          if (TrianglesIntersect(t, u))
          {
            ++count;
            if (examples.size() < this->MaxExamples)
            {
              examples.emplace_back(std::min(ti, tj), std::max(ti, tj));
            }
          }
        }
      }
    }
  }
};

void CheckSelfIntersections(const std::vector<std::int64_t>& tris,
  const std::vector<Vec3>& pts,
  const std::vector<std::uint8_t>& usable,
  std::size_t maxExamples,
  MeshCheckReport& report)
{
  const vtkIdType nt = static_cast<vtkIdType>(tris.size() / 3);
  std::vector<std::array<double, 6>> boxes(static_cast<std::size_t>(nt));
  std::array<double, 3> lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  double sumExtent = 0.0;
  vtkIdType counted = 0;
  for (vtkIdType t = 0; t < nt; ++t)
  {
    auto& b = boxes[t];
    b = { HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    if (!usable[t])
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const Vec3& p = pts[tris[3 * t + k]];
      for (int a = 0; a < 3; ++a)
      {
        b[a] = std::min(b[a], p[a]);
        b[3 + a] = std::max(b[3 + a], p[a]);
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], b[a]);
      hi[a] = std::max(hi[a], b[3 + a]);
      sumExtent += b[3 + a] - b[a];
    }
    ++counted;
  }
  if (counted < 2)
  {
    return;
  }
  // Cells about twice the mean box extent, at most ~4 cells per triangle.
  const double diag = Norm(Vec3(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
  double size = std::max(2.0 * sumExtent / (3.0 * counted), 1e-9 * diag);
  const double volume =
    std::max(hi[0] - lo[0], size) * std::max(hi[1] - lo[1], size) * std::max(hi[2] - lo[2], size);
  size = std::max(size, std::cbrt(volume / (4.0 * counted)));
  if (!(size > 0) || !std::isfinite(size))
  {
    return;
  }
  std::array<int, 3> dims;
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / size) + 1);
  }
  const vtkIdType ncells = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  auto cellRange = [&](const std::array<double, 6>& b, std::array<int, 6>& r)
  {
    for (int a = 0; a < 3; ++a)
    {
      r[a] = std::clamp(static_cast<int>((b[a] - lo[a]) / size), 0, dims[a] - 1);
      r[3 + a] = std::clamp(static_cast<int>((b[3 + a] - lo[a]) / size), 0, dims[a] - 1);
    }
  };
  std::vector<vtkIdType> start(static_cast<std::size_t>(ncells + 1), 0);
  std::array<int, 6> r;
  for (int pass = 0; pass < 2; ++pass)
  {
    std::vector<vtkIdType> fill;
    std::vector<vtkIdType> items;
    if (pass == 1)
    {
      for (vtkIdType c = 0; c < ncells; ++c)
      {
        start[c + 1] += start[c];
      }
      fill.assign(start.begin(), start.end() - 1);
      items.resize(static_cast<std::size_t>(start[ncells]));
    }
    for (vtkIdType t = 0; t < nt; ++t)
    {
      if (!usable[t])
      {
        continue;
      }
      cellRange(boxes[t], r);
      for (int z = r[2]; z <= r[5]; ++z)
      {
        for (int y = r[1]; y <= r[4]; ++y)
        {
          for (int x = r[0]; x <= r[3]; ++x)
          {
            const vtkIdType c = x + dims[0] * (y + static_cast<vtkIdType>(dims[1]) * z);
            if (pass == 0)
            {
              ++start[c + 1];
            }
            else
            {
              items[fill[c]++] = t;
            }
          }
        }
      }
    }
    if (pass == 1)
    {
      IntersectionWorker worker{ tris,
        pts,
        usable,
        boxes,
        start,
        items,
        dims,
        Vec3(lo[0], lo[1], lo[2]),
        size,
        maxExamples,
        {},
        {} };
      vtkSMPTools::For(0, ncells, worker);
      for (auto it = worker.Count.begin(); it != worker.Count.end(); ++it)
      {
        report.selfIntersections += *it;
      }
      for (auto it = worker.Examples.begin(); it != worker.Examples.end(); ++it)
      {
        report.intersectingPairs.insert(report.intersectingPairs.end(), it->begin(), it->end());
      }
      std::sort(report.intersectingPairs.begin(), report.intersectingPairs.end());
      if (report.intersectingPairs.size() > maxExamples)
      {
        report.intersectingPairs.resize(maxExamples);
      }
    }
  }
  report.selfIntersectionsChecked = true;
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
    CheckSelfIntersections(tris, samples.points, samples.usable, options.maxExamples, report);
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
        CountInvertedTriangles(tris, samples.usable, before, samples.points);
    }
  }
  report.problems = Problems(report, samples.badIds, options);
  return report;
}

namespace
{
std::string Number(double v)
{
  if (!std::isfinite(v))
  {
    return "null";
  }
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", v);
  return buffer;
}

} // namespace

std::string FormatReportText(const MeshCheckReport& r, const std::string& name)
{
  std::ostringstream os;
  os << name << ": " << (r.Clean() ? "clean" : "PROBLEMS") << "\n";
  os << "  triangles " << r.triangles << ", points " << r.points;
  if (r.unusedPoints)
  {
    os << " (" << r.unusedPoints << " unused)";
  }
  os << ", components " << r.components << "\n";
  os << "  boundary loops " << r.boundaryLoops.size();
  if (!r.boundaryLoops.empty())
  {
    os << " (edges:";
    for (vtkIdType l : r.boundaryLoops)
    {
      os << " " << l;
    }
    os << ")";
  }
  os << (r.closed ? ", closed" : ", open") << "\n";
  os << "  non-manifold edges " << r.nonManifoldEdges << ", vertices " << r.nonManifoldVertices
     << "; inconsistently oriented edges " << r.inconsistentEdges << "\n";
  os << "  degenerate triangles " << r.degenerateTriangles << "; self-intersections "
     << (r.selfIntersectionsChecked ? std::to_string(r.selfIntersections) : "not checked");
  for (const auto& p : r.intersectingPairs)
  {
    os << " (" << p.first << "," << p.second << ")";
  }
  os << "\n";
  os << "  area " << Number(r.area);
  if (r.closed)
  {
    os << ", volume " << Number(std::abs(r.volume))
       << (r.volume < 0 ? " (triangles face inwards)" : "");
  }
  os << "\n";
  os << "  edge length min " << Number(r.edgeLength.min) << " mean " << Number(r.edgeLength.mean)
     << " max " << Number(r.edgeLength.max) << "\n";
  os << "  minimum angle (deg) min " << Number(r.minimumAngle.min) << " mean "
     << Number(r.minimumAngle.mean) << "\n";
  if (r.flipsChecked)
  {
    os << "  flipped triangles since before the warp " << r.flippedTriangles << "\n";
  }
  else if (!r.flipsNote.empty())
  {
    os << "  " << r.flipsNote << "\n";
  }
  for (const std::string& p : r.problems)
  {
    os << "  problem: " << p << "\n";
  }
  return os.str();
}

nlohmann::ordered_json ToJson(const MeshCheckReport& r, const std::string& name)
{
  using json = nlohmann::ordered_json;
  // Measures that could not be taken (not closed, flips or self-intersections not checked,
  // a non-finite value) are null.
  const auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json out;
  out["mesh"] = name;
  out["clean"] = r.Clean();
  out["triangles"] = r.triangles;
  out["points"] = r.points;
  out["unusedPoints"] = r.unusedPoints;
  out["components"] = r.components;
  out["boundaryEdges"] = r.boundaryEdges;
  out["boundaryLoops"] = r.boundaryLoops;
  out["closed"] = r.closed;
  out["nonManifoldEdges"] = r.nonManifoldEdges;
  out["nonManifoldVertices"] = r.nonManifoldVertices;
  out["inconsistentEdges"] = r.inconsistentEdges;
  out["degenerateTriangles"] = r.degenerateTriangles;
  out["selfIntersections"] = r.selfIntersectionsChecked ? json(r.selfIntersections) : json(nullptr);
  out["intersectingPairs"] = json::array();
  for (const auto& [a, b] : r.intersectingPairs)
  {
    out["intersectingPairs"].push_back({ a, b });
  }
  out["area"] = number(r.area);
  out["volume"] = r.closed ? number(std::abs(r.volume)) : json(nullptr);
  out["facesInward"] = r.closed && r.volume < 0;
  out["edgeLength"] = { { "min", number(r.edgeLength.min) },
    { "mean", number(r.edgeLength.mean) },
    { "max", number(r.edgeLength.max) } };
  out["minimumAngleDegrees"] = { { "min", number(r.minimumAngle.min) },
    { "mean", number(r.minimumAngle.mean) } };
  out["flippedTriangles"] = r.flipsChecked ? json(r.flippedTriangles) : json(nullptr);
  out["nonFinitePoints"] = r.nonFinitePoints;
  out["problems"] = r.problems;
  return out;
}

std::string FormatReportJson(const MeshCheckReport& r, const std::string& name)
{
  // Invalid UTF-8 in a file name is replaced rather than thrown on.
  return ToJson(r, name).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) +
    "\n";
}

} // namespace bender
