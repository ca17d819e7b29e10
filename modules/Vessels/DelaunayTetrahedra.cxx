#include "DelaunayTetrahedra.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>

#ifdef BENDER_HAVE_QHULL
extern "C"
{
#include <libqhull_r/qhull_ra.h>
}
#endif

namespace bender
{
namespace
{

using Int128 = __int128;

// Coordinates on the grid are integers in [-GridHalf, GridHalf], held as doubles (exact) for
// the filtered predicates; differences stay within 2^22 so that 2 x 2 minors are exact in
// double and int64, and the in-sphere determinant is below 2^117 in absolute value.
constexpr double GridHalf = 2097152.0; // 2^21
// Relative error bound of the double evaluation of both determinants (a few units in the last
// place of their permanent; see Orient and InSphere), with a wide margin.
constexpr double FilterBound = 1e-14;

struct Tetra
{
  int v[4]; // positively oriented; V[0] < 0: the slot is free
  int n[4]; // N[k]: the tetrahedron across the face opposite V[k], -1 outside
};

class Triangulator
{
public:
  Triangulator(const std::vector<std::array<double, 3>>& grid, DelaunayStatistics& statistics)
    : Grid(grid)
    , Stats(statistics)
  {
  }

  // Sign of det[b - a, c - a, d - a]: positive when d lies on the side of plane abc to which
  // (b - a) x (c - a) points.
  int Orient(int a, int b, int c, int d)
  {
    const auto& pa = Grid[a];
    const auto& pb = Grid[b];
    const auto& pc = Grid[c];
    const auto& pd = Grid[d];
    const double bx = pb[0] - pa[0], by = pb[1] - pa[1], bz = pb[2] - pa[2];
    const double cx = pc[0] - pa[0], cy = pc[1] - pa[1], cz = pc[2] - pa[2];
    const double dx = pd[0] - pa[0], dy = pd[1] - pa[1], dz = pd[2] - pa[2];
    // The 2 x 2 minors are exact (integers below 2^45); three products and two sums round.
    const double m1 = cy * dz - cz * dy;
    const double m2 = cz * dx - cx * dz;
    const double m3 = cx * dy - cy * dx;
    const double det = bx * m1 + by * m2 + bz * m3;
    const double permanent =
      std::abs(bx) * std::abs(m1) + std::abs(by) * std::abs(m2) + std::abs(bz) * std::abs(m3);
    if (det > FilterBound * permanent)
    {
      return 1;
    }
    if (-det > FilterBound * permanent)
    {
      return -1;
    }
    ++Stats.exactTests;
    auto i64 = [](double v) { return static_cast<std::int64_t>(v); };
    const std::int64_t e1 = i64(cy) * i64(dz) - i64(cz) * i64(dy);
    const std::int64_t e2 = i64(cz) * i64(dx) - i64(cx) * i64(dz);
    const std::int64_t e3 = i64(cx) * i64(dy) - i64(cy) * i64(dx);
    const Int128 exact = static_cast<Int128>(i64(bx)) * e1 + static_cast<Int128>(i64(by)) * e2 +
      static_cast<Int128>(i64(bz)) * e3;
    return exact > 0 ? 1 : (exact < 0 ? -1 : 0);
  }

  // Whether point e lies inside the circumsphere of the positively oriented tetrahedron
  // (a, b, c, d), exact ties broken by the symbolic perturbation.
  bool InSphere(const int* v, int e)
  {
    const int sign = InSphereSign(v[0], v[1], v[2], v[3], e);
    if (sign != 0)
    {
      return sign > 0;
    }
    // Tie: lift each point by epsilon^(rank), the largest index dominating. Raising the
    // query's lift puts it outside; raising vertex k's puts the query inside exactly when the
    // query lies on vertex k's side of the opposite face.
    ++Stats.perturbations;
    int order[5] = { v[0], v[1], v[2], v[3], e };
    std::sort(order, order + 5, [](int x, int y) { return x > y; });
    for (int id : order)
    {
      if (id == e)
      {
        return false;
      }
      int w[4] = { v[0], v[1], v[2], v[3] };
      for (int k = 0; k < 4; ++k)
      {
        if (w[k] == id)
        {
          w[k] = e;
        }
      }
      const int o = Orient(w[0], w[1], w[2], w[3]);
      if (o != 0)
      {
        return o > 0;
      }
    }
    return false; // not reached: the query comes up in the order
  }

  // Sign of the in-sphere determinant: positive when e is strictly inside the circumsphere of
  // the positively oriented (a, b, c, d).
  int InSphereSign(int a, int b, int c, int d, int e)
  {
    const auto& pe = Grid[e];
    double A[3], B[3], C[3], D[3];
    for (int k = 0; k < 3; ++k)
    {
      A[k] = Grid[a][k] - pe[k];
      B[k] = Grid[b][k] - pe[k];
      C[k] = Grid[c][k] - pe[k];
      D[k] = Grid[d][k] - pe[k];
    }
    // 2 x 2 minors of the x, y columns (exact).
    const double ab = A[0] * B[1] - B[0] * A[1];
    const double ac = A[0] * C[1] - C[0] * A[1];
    const double ad = A[0] * D[1] - D[0] * A[1];
    const double bc = B[0] * C[1] - C[0] * B[1];
    const double bd = B[0] * D[1] - D[0] * B[1];
    const double cd = C[0] * D[1] - D[0] * C[1];
    // 3 x 3 minors of x, y, z (expanded along z).
    const double bcd = B[2] * cd - C[2] * bd + D[2] * bc;
    const double acd = A[2] * cd - C[2] * ad + D[2] * ac;
    const double abd = A[2] * bd - B[2] * ad + D[2] * ab;
    const double abc = A[2] * bc - B[2] * ac + C[2] * ab;
    // Lifts (exact: below 3 * 2^44).
    const double wa = A[0] * A[0] + A[1] * A[1] + A[2] * A[2];
    const double wb = B[0] * B[0] + B[1] * B[1] + B[2] * B[2];
    const double wc = C[0] * C[0] + C[1] * C[1] + C[2] * C[2];
    const double wd = D[0] * D[0] + D[1] * D[1] + D[2] * D[2];
    // -det[[A, wa], [B, wb], [C, wc], [D, wd]] expanded along the lifts: positive inside.
    const double det = wa * bcd - wb * acd + wc * abd - wd * abc;
    const double pbcd =
      std::abs(B[2]) * std::abs(cd) + std::abs(C[2]) * std::abs(bd) + std::abs(D[2]) * std::abs(bc);
    const double pacd =
      std::abs(A[2]) * std::abs(cd) + std::abs(C[2]) * std::abs(ad) + std::abs(D[2]) * std::abs(ac);
    const double pabd =
      std::abs(A[2]) * std::abs(bd) + std::abs(B[2]) * std::abs(ad) + std::abs(D[2]) * std::abs(ab);
    const double pabc =
      std::abs(A[2]) * std::abs(bc) + std::abs(B[2]) * std::abs(ac) + std::abs(C[2]) * std::abs(ab);
    const double permanent = wa * pbcd + wb * pacd + wc * pabd + wd * pabc;
    if (det > FilterBound * permanent)
    {
      return 1;
    }
    if (-det > FilterBound * permanent)
    {
      return -1;
    }
    ++Stats.exactTests;
    std::int64_t I[4][3];
    for (int k = 0; k < 3; ++k)
    {
      I[0][k] = static_cast<std::int64_t>(A[k]);
      I[1][k] = static_cast<std::int64_t>(B[k]);
      I[2][k] = static_cast<std::int64_t>(C[k]);
      I[3][k] = static_cast<std::int64_t>(D[k]);
    }
    auto minor2 = [&I](int p, int q) { return I[p][0] * I[q][1] - I[q][0] * I[p][1]; };
    const std::int64_t eab = minor2(0, 1), eac = minor2(0, 2), ead = minor2(0, 3);
    const std::int64_t ebc = minor2(1, 2), ebd = minor2(1, 3), ecd = minor2(2, 3);
    auto z = [&I](int p) { return static_cast<Int128>(I[p][2]); };
    const Int128 ebcd = z(1) * ecd - z(2) * ebd + z(3) * ebc;
    const Int128 eacd = z(0) * ecd - z(2) * ead + z(3) * eac;
    const Int128 eabd = z(0) * ebd - z(1) * ead + z(3) * eab;
    const Int128 eabc = z(0) * ebc - z(1) * eac + z(2) * eab;
    auto lift = [&I](int p)
    { return static_cast<Int128>(I[p][0] * I[p][0] + I[p][1] * I[p][1] + I[p][2] * I[p][2]); };
    const Int128 exact = lift(0) * ebcd - lift(1) * eacd + lift(2) * eabd - lift(3) * eabc;
    return exact > 0 ? 1 : (exact < 0 ? -1 : 0);
  }

  const std::vector<std::array<double, 3>>& Grid;
  DelaunayStatistics& Stats;
};

// Morton code of a grid point (21 bits per axis).
std::uint64_t Morton(const std::array<double, 3>& g)
{
  auto spread = [](std::uint64_t x)
  {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  };
  auto key = [](double v) { return static_cast<std::uint64_t>(v + GridHalf) >> 1; };
  return spread(key(g[0])) | spread(key(g[1])) << 1 | spread(key(g[2])) << 2;
}

#ifdef BENDER_HAVE_QHULL
// Neighbours of tetrahedra given without them (Qhull's): faces matched by sorting.
std::vector<std::array<vtkIdType, 4>> FaceNeighbours(
  const std::vector<std::array<vtkIdType, 4>>& tetras)
{
  struct Face
  {
    std::array<vtkIdType, 3> ids;
    vtkIdType tet;
    int opposite;
  };
  std::vector<Face> faces;
  faces.reserve(4 * tetras.size());
  for (std::size_t t = 0; t < tetras.size(); ++t)
  {
    for (int k = 0; k < 4; ++k)
    {
      Face f{ {}, static_cast<vtkIdType>(t), k };
      int m = 0;
      for (int j = 0; j < 4; ++j)
      {
        if (j != k)
        {
          f.ids[m++] = tetras[t][j];
        }
      }
      std::sort(f.ids.begin(), f.ids.end());
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.ids < b.ids; });
  std::vector<std::array<vtkIdType, 4>> neighbours(
    tetras.size(), std::array<vtkIdType, 4>{ { -1, -1, -1, -1 } });
  for (std::size_t i = 0; i + 1 < faces.size(); ++i)
  {
    if (faces[i].ids == faces[i + 1].ids)
    {
      neighbours[faces[i].tet][faces[i].opposite] = faces[i + 1].tet;
      neighbours[faces[i + 1].tet][faces[i + 1].opposite] = faces[i].tet;
      ++i;
    }
  }
  return neighbours;
}
#endif

} // namespace

bool DelaunayTetrahedra(std::vector<std::array<double, 3>>& points,
  std::vector<std::array<vtkIdType, 4>>& tetras,
  std::string& error,
  DelaunayStatistics* statistics,
  std::vector<std::array<vtkIdType, 4>>* neighbours)
{
  tetras.clear();
  if (neighbours)
  {
    neighbours->clear();
  }
  DelaunayStatistics localStats;
  DelaunayStatistics& stats = statistics ? *statistics : localStats;
  stats = DelaunayStatistics();
  const std::size_t n = points.size();
  if (n < 4)
  {
    error = "fewer than four points (" + std::to_string(n) + ")";
    return false;
  }
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max() / 8))
  {
    error = "too many points (" + std::to_string(n) + ")";
    return false;
  }
  double lo[3] = { points[0][0], points[0][1], points[0][2] };
  double hi[3] = { lo[0], lo[1], lo[2] };
  for (const auto& p : points)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (!std::isfinite(p[c]))
      {
        error = "a point has a non-finite coordinate";
        return false;
      }
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  }
  const double centre[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (!(diagonal > 0) || !std::isfinite(diagonal))
  {
    error = diagonal > 0 ? "the points' extent is not finite" : "all points coincide";
    return false;
  }
  // The enclosing tetrahedron: regular, in-radius one diagonal (so its faces clear the points'
  // bounding sphere by half a diagonal), corners three diagonals from the centre. The grid
  // spans its corners with a 2 % margin.
  const double circumradius = 3.0 * diagonal;
  const double step = 1.02 * circumradius / GridHalf;
  stats.gridStep = step;
  std::vector<std::array<double, 3>> grid(n + 4);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      grid[i][c] = std::nearbyint((points[i][c] - centre[c]) / step);
      points[i][c] = centre[c] + grid[i][c] * step;
    }
  }
  {
    const double s = circumradius / step / std::sqrt(3.0);
    const double corners[4][3] = { { 1, 1, 1 }, { 1, -1, -1 }, { -1, 1, -1 }, { -1, -1, 1 } };
    for (int k = 0; k < 4; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        grid[n + k][c] = std::nearbyint(corners[k][c] * s);
      }
    }
  }
  Triangulator predicates(grid, stats);

  std::vector<Tetra> tets;
  tets.reserve(7 * n + 16);
  std::vector<int> freeSlots;
  {
    const int a = static_cast<int>(n), b = a + 1, c = a + 2, d = a + 3;
    Tetra t{ { a, b, c, d }, { -1, -1, -1, -1 } };
    if (predicates.Orient(a, b, c, d) < 0)
    {
      std::swap(t.v[0], t.v[1]);
    }
    tets.push_back(t);
  }

  // Insertion order: a biased randomised order (Amenta, Choi and Rote's BRIO): rounds of
  // doubling size, each along a Morton curve, so that consecutive points are close and the
  // walk from the last insertion is short, while the rounds keep the expected cost of a
  // random order.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 random(20041);
  std::shuffle(order.begin(), order.end(), random);
  {
    std::vector<std::uint64_t> keys(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      keys[i] = Morton(grid[i]);
    }
    std::size_t end = n;
    while (end > 0)
    {
      const std::size_t begin = end > 64 ? end / 2 : 0;
      std::sort(order.begin() + static_cast<std::ptrdiff_t>(begin),
        order.begin() + static_cast<std::ptrdiff_t>(end),
        [&keys](int x, int y) { return keys[x] < keys[y]; });
      end = begin;
    }
  }

  std::vector<std::uint32_t> mark(tets.capacity(), 0);
  std::uint32_t stamp = 0;
  std::vector<int> cavity, stack;
  struct BoundaryFace
  {
    int v[4];    // the cavity tetrahedron's vertices, the new point at face
    int face;    // which slot holds the new point
    int outside; // the tetrahedron beyond the face, -1 on the hull
    int back;    // the face of outside that looks back
  };
  std::vector<BoundaryFace> boundary;
  // The new tetrahedra are linked across the cavity boundary's edges through a small hash
  // table (open addressing, emptied by bumping its generation).
  struct EdgeSlot
  {
    std::uint64_t key = 0;
    int tet = -1; // -1: matched already
    int face = 0;
    std::uint32_t generation = 0;
  };
  std::vector<EdgeSlot> edgeTable(64); // grows with the largest cavity (often, so it is exercised)
  std::uint32_t generation = 0;
  std::uint32_t walkState = 0x9e3779b9u;
  int hint = 0;

  for (int p : order)
  {
    // 1. Locate: a visibility walk, faces tried from a random one so that it cannot cycle.
    int t = hint;
    bool located = false;
    for (std::size_t steps = 0; steps < 4 * tets.size() + 64; ++steps)
    {
      walkState ^= walkState << 13;
      walkState ^= walkState >> 17;
      walkState ^= walkState << 5;
      const int first = static_cast<int>(walkState & 3u);
      const Tetra& T = tets[t];
      int next = -1;
      for (int j = 0; j < 4 && next < 0; ++j)
      {
        const int f = (first + j) & 3;
        int w[4] = { T.v[0], T.v[1], T.v[2], T.v[3] };
        w[f] = p;
        if (predicates.Orient(w[0], w[1], w[2], w[3]) < 0)
        {
          next = T.n[f];
          if (next < 0)
          {
            error = "internal error: a point walked out of the enclosing tetrahedron";
            return false;
          }
        }
      }
      if (next < 0)
      {
        located = true;
        break;
      }
      t = next;
    }
    if (!located)
    {
      error = "internal error: the point location walk did not end";
      return false;
    }
    {
      const Tetra& T = tets[t];
      bool duplicate = false;
      for (int k = 0; k < 4; ++k)
      {
        duplicate = duplicate || grid[T.v[k]] == grid[p];
      }
      if (duplicate)
      {
        ++stats.duplicates;
        continue;
      }
    }

    // 2. The cavity: tetrahedra whose circumsphere holds p, grown from the one containing it.
    if (stamp >= 0xfffffff0u)
    {
      std::fill(mark.begin(), mark.end(), 0);
      stamp = 0;
    }
    const std::uint32_t in = ++stamp;
    const std::uint32_t out = ++stamp;
    cavity.clear();
    boundary.clear();
    stack.clear();
    mark[t] = in;
    stack.push_back(t);
    while (!stack.empty())
    {
      const int c = stack.back();
      stack.pop_back();
      cavity.push_back(c);
      for (int f = 0; f < 4; ++f)
      {
        const int u = tets[c].n[f];
        bool isBoundary = u < 0;
        if (u >= 0 && mark[u] != in)
        {
          if (mark[u] != out && predicates.InSphere(tets[u].v, p))
          {
            mark[u] = in;
            stack.push_back(u);
          }
          else
          {
            mark[u] = out;
            isBoundary = true;
          }
        }
        if (isBoundary)
        {
          BoundaryFace b;
          std::copy(tets[c].v, tets[c].v + 4, b.v);
          b.v[f] = p;
          b.face = f;
          b.outside = u;
          b.back = -1;
          if (u >= 0)
          {
            for (int g = 0; g < 4; ++g)
            {
              if (tets[u].n[g] == c)
              {
                b.back = g;
              }
            }
            if (b.back < 0)
            {
              error = "internal error: inconsistent neighbours";
              return false;
            }
          }
          boundary.push_back(b);
        }
      }
    }

    // 3. Replace the cavity by the boundary faces joined to p.
    for (int c : cavity)
    {
      tets[c].v[0] = -1;
      freeSlots.push_back(c);
    }
    if (edgeTable.size() < 4 * boundary.size())
    {
      std::size_t size = edgeTable.size();
      while (size < 4 * boundary.size())
      {
        size *= 2; // a power of two, for the mask
      }
      edgeTable.assign(size, EdgeSlot());
    }
    if (++generation == 0)
    {
      std::fill(edgeTable.begin(), edgeTable.end(), EdgeSlot());
      generation = 1;
    }
    const std::size_t mask = edgeTable.size() - 1;
    std::ptrdiff_t pending = 0;
    bool consistent = true;
    for (const BoundaryFace& b : boundary)
    {
      int id;
      if (!freeSlots.empty())
      {
        id = freeSlots.back();
        freeSlots.pop_back();
      }
      else
      {
        id = static_cast<int>(tets.size());
        tets.emplace_back();
        if (mark.size() < tets.size())
        {
          mark.resize(2 * tets.size(), 0);
        }
      }
      Tetra& T = tets[id];
      std::copy(b.v, b.v + 4, T.v);
      T.n[b.face] = b.outside;
      if (b.outside >= 0)
      {
        tets[b.outside].n[b.back] = id;
      }
      for (int k = 0; k < 4; ++k)
      {
        if (k == b.face)
        {
          continue;
        }
        // The face opposite V[k] holds p and the edge of the other two boundary vertices.
        int e[2], m = 0;
        for (int j = 0; j < 4; ++j)
        {
          if (j != k && j != b.face)
          {
            e[m++] = b.v[j];
          }
        }
        const auto x = static_cast<std::uint64_t>(std::min(e[0], e[1]));
        const auto y = static_cast<std::uint64_t>(std::max(e[0], e[1]));
        const std::uint64_t key = (x << 32) | y;
        std::size_t h = static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ULL) >> 40) & mask;
        while (edgeTable[h].generation == generation && edgeTable[h].key != key)
        {
          h = (h + 1) & mask;
        }
        EdgeSlot& slot = edgeTable[h];
        if (slot.generation != generation)
        {
          slot = { key, id, k, generation };
          ++pending;
        }
        else if (slot.tet >= 0)
        {
          T.n[k] = slot.tet;
          tets[slot.tet].n[slot.face] = id;
          slot.tet = -1;
          --pending;
        }
        else
        {
          consistent = false; // an edge shared by three boundary faces
        }
      }
      hint = id;
    }
    if (!consistent || pending != 0)
    {
      error = "internal error: the cavity's boundary is not a closed surface";
      return false;
    }
  }

  const int limit = static_cast<int>(n);
  std::vector<vtkIdType> index(tets.size(), -1);
  for (std::size_t i = 0; i < tets.size(); ++i)
  {
    const Tetra& T = tets[i];
    if (T.v[0] >= 0 && T.v[0] < limit && T.v[1] < limit && T.v[2] < limit && T.v[3] < limit)
    {
      index[i] = static_cast<vtkIdType>(tetras.size());
      tetras.push_back({ { T.v[0], T.v[1], T.v[2], T.v[3] } });
    }
  }
  if (neighbours)
  {
    neighbours->reserve(tetras.size());
    for (std::size_t i = 0; i < tets.size(); ++i)
    {
      if (index[i] >= 0)
      {
        std::array<vtkIdType, 4> across;
        for (int k = 0; k < 4; ++k)
        {
          across[k] = tets[i].n[k] >= 0 ? index[tets[i].n[k]] : -1;
        }
        neighbours->push_back(across);
      }
    }
  }
  if (tetras.empty())
  {
    error = "the points are co-planar (no tetrahedra)";
    return false;
  }
  return true;
}

// Qhull's Delaunay: the lower hull of the points lifted to a paraboloid, triangulated output
// ('Qt'), with a point at infinity for co-spherical input ('Qz').
bool QhullTetrahedra(const std::vector<std::array<double, 3>>& points,
  std::vector<std::array<vtkIdType, 4>>& tetras,
  std::string& error,
  std::vector<std::array<vtkIdType, 4>>* neighbours)
{
  tetras.clear();
  if (neighbours)
  {
    neighbours->clear();
  }
#ifndef BENDER_HAVE_QHULL
  (void)points;
  error = "this build has no Qhull";
  return false;
#else
  std::vector<coordT> coords(points.size() * 3);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      coords[3 * i + c] = points[i][c];
    }
  }
  char* buffer = nullptr;
  std::size_t bufferSize = 0;
  FILE* errors = open_memstream(&buffer, &bufferSize);
  qhT qhStorage;
  qhT* qh = &qhStorage;
  QHULL_LIB_CHECK
  qh_zero(qh, errors);
  char flags[] = "qhull d Qt Qbb Qz";
  const int exitCode = qh_new_qhull(
    qh, 3, static_cast<int>(points.size()), coords.data(), False, flags, nullptr, errors);
  if (exitCode == 0)
  {
    facetT* facet = nullptr;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FORALLfacets
    {
      if (facet->upperdelaunay)
      {
        continue;
      }
      std::array<vtkIdType, 4> t{ { -1, -1, -1, -1 } };
      int k = 0;
      FOREACHvertex_(facet->vertices)
      {
        if (k < 4)
        {
          t[k] = qh_pointid(qh, vertex->point);
        }
        ++k;
      }
      if (k == 4)
      {
        tetras.push_back(t);
      }
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (errors)
  {
    std::fclose(errors);
  }
  if (exitCode != 0)
  {
    std::string message = buffer ? std::string(buffer) : std::string();
    const auto newline = message.find('\n', message.find_first_not_of('\n'));
    error = "Delaunay failed: " + message.substr(0, std::min<std::size_t>(newline, 200));
  }
  std::free(buffer);
  if (exitCode == 0 && neighbours)
  {
    *neighbours = FaceNeighbours(tetras);
  }
  return exitCode == 0;
#endif
}

} // namespace bender
