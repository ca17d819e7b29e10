// CheckSelfIntersections: crossing triangle pairs over a grid of bounding boxes
// (MeshCheckPasses.h).

#include "MeshCheckPasses.h"

#include "Vec3.h"

#include <vtkPolyData.h>
#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace bender
{
namespace mesh_check
{

namespace
{

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

// The self-intersection search over a uniform grid of triangle bounding boxes, each pair of
// overlapping boxes tested once, cells in parallel. Kept instead of vtkStaticCellLocator:
// MeshCheck.SelfIntersectionPairsMatchAnAllPairsSearch proves it finds exactly the pairs of
// an all-pairs search, and bench_mesh_check times both in the same run, with the same pairs
// found: the locator with one FindCellsWithinBounds query per triangle is 23-37x slower on the
// demo vessel (VTK 9.1; docs/performance.md).
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

} // namespace

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

} // namespace mesh_check
} // namespace bender
