// The centerlines' 3D Delaunay (DelaunayTetrahedra.h) against the definition: on small point
// sets every empty-circumsphere tetrahedron is found by brute force over all quadruples and
// compared with the triangulation, in general position (random points, a tube's wall) and on
// an exactly co-spherical lattice, where the symbolic perturbation must still give a
// triangulation (no flat tetrahedra, volumes adding up to the lattice's cube).

#include "DelaunayTetrahedra.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace
{
using Point = std::array<double, 3>;
using Tet = std::array<vtkIdType, 4>;

long double Orient(const Point& a, const Point& b, const Point& c, const Point& d)
{
  const long double b0 = b[0] - a[0], b1 = b[1] - a[1], b2 = b[2] - a[2];
  const long double c0 = c[0] - a[0], c1 = c[1] - a[1], c2 = c[2] - a[2];
  const long double d0 = d[0] - a[0], d1 = d[1] - a[1], d2 = d[2] - a[2];
  return b0 * (c1 * d2 - c2 * d1) + b1 * (c2 * d0 - c0 * d2) + b2 * (c0 * d1 - c1 * d0);
}

// Circumcentre and squared radius in long double; false for a flat quadruple.
bool Circumsphere(const Point& a,
  const Point& b,
  const Point& c,
  const Point& d,
  std::array<long double, 3>& centre,
  long double& radius2)
{
  long double m[3][3], r[3];
  const Point* q[3] = { &b, &c, &d };
  for (int i = 0; i < 3; ++i)
  {
    r[i] = 0;
    for (int k = 0; k < 3; ++k)
    {
      m[i][k] = (*q[i])[k] - a[k];
      r[i] += 0.5L * m[i][k] * m[i][k];
    }
  }
  const long double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  long double scale = 0;
  for (int i = 0; i < 3; ++i)
  {
    scale = std::max(scale, std::sqrt(m[i][0] * m[i][0] + m[i][1] * m[i][1] + m[i][2] * m[i][2]));
  }
  if (std::fabs(det) < 1e-12L * scale * scale * scale)
  {
    return false;
  }
  long double x[3];
  for (int k = 0; k < 3; ++k)
  {
    long double mk[3][3];
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        mk[i][j] = j == k ? r[i] : m[i][j];
      }
    }
    x[k] = (mk[0][0] * (mk[1][1] * mk[2][2] - mk[1][2] * mk[2][1]) -
             mk[0][1] * (mk[1][0] * mk[2][2] - mk[1][2] * mk[2][0]) +
             mk[0][2] * (mk[1][0] * mk[2][1] - mk[1][1] * mk[2][0])) /
      det;
  }
  radius2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = a[k] + x[k];
  }
  return true;
}

long double Distance2(const Point& p, const std::array<long double, 3>& c)
{
  return (p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) +
    (p[2] - c[2]) * (p[2] - c[2]);
}

// The least squared distance to the circumcentre minus the squared circumradius over all the
// points: negative when a point lies inside the tetrahedron's circumsphere.
long double EmptinessMargin(const std::vector<Point>& points, const Tet& t)
{
  std::array<long double, 3> centre{};
  long double r2 = 0;
  if (!Circumsphere(points[t[0]], points[t[1]], points[t[2]], points[t[3]], centre, r2))
  {
    ADD_FAILURE() << "a flat tetrahedron";
    return -std::numeric_limits<long double>::infinity();
  }
  long double margin = std::numeric_limits<long double>::infinity();
  for (const auto& p : points)
  {
    margin = std::min(margin, Distance2(p, centre) - r2);
  }
  return margin;
}

double Diagonal(const std::vector<Point>& points)
{
  Point lo = points[0], hi = points[0];
  for (const auto& p : points)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
    (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

Tet Sorted(Tet t)
{
  std::sort(t.begin(), t.end());
  return t;
}

// Points in general position: the Delaunay tetrahedra are unique. Every returned tetrahedron
// must have an empty circumsphere, and every empty-circumsphere quadruple with a radius below
// 1.25 diagonals (the header's promise) must be returned.
void ExpectDelaunay(std::vector<Point> points)
{
  std::vector<Tet> tets;
  std::string error;
  bender::DelaunayStatistics stats;
  ASSERT_TRUE(bender::DelaunayTetrahedra(points, tets, error, &stats)) << error;
  EXPECT_EQ(stats.duplicates, 0);
  const double diagonal = Diagonal(points);
  const long double tolerance = 1e-9L * diagonal * diagonal;
  std::set<Tet> found;
  for (const Tet& t : tets)
  {
    EXPECT_GT(Orient(points[t[0]], points[t[1]], points[t[2]], points[t[3]]), 0)
      << "tetrahedra are positively oriented";
    ASSERT_GE(EmptinessMargin(points, t), -tolerance)
      << "a point lies inside a returned tetrahedron's sphere";
    EXPECT_TRUE(found.insert(Sorted(t)).second) << "a tetrahedron is returned twice";
  }
  const std::size_t n = points.size();
  std::size_t expected = 0;
  for (std::size_t a = 0; a < n; ++a)
  {
    for (std::size_t b = a + 1; b < n; ++b)
    {
      for (std::size_t c = b + 1; c < n; ++c)
      {
        for (std::size_t d = c + 1; d < n; ++d)
        {
          std::array<long double, 3> centre;
          long double r2 = 0;
          if (!Circumsphere(points[a], points[b], points[c], points[d], centre, r2) ||
            r2 >= 1.25L * 1.25L * diagonal * diagonal)
          {
            continue;
          }
          bool empty = true;
          for (std::size_t i = 0; i < n && empty; ++i)
          {
            empty = i == a || i == b || i == c || i == d || Distance2(points[i], centre) > r2;
          }
          if (empty)
          {
            ++expected;
            const Tet t{ { static_cast<vtkIdType>(a),
              static_cast<vtkIdType>(b),
              static_cast<vtkIdType>(c),
              static_cast<vtkIdType>(d) } };
            EXPECT_TRUE(found.count(t))
              << "a Delaunay tetrahedron is missing: " << a << " " << b << " " << c << " " << d;
          }
        }
      }
    }
  }
  EXPECT_GT(expected, n) << "the brute force found too few tetrahedra to compare";
}

TEST(DelaunayTetrahedra, RandomPointsMatchTheEmptySphereDefinition)
{
  for (unsigned seed = 1; seed <= 5; ++seed)
  {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(-20.0, 30.0);
    std::vector<Point> points(40);
    for (auto& p : points)
    {
      p = { { u(random), u(random) * 0.5 + 100.0, u(random) * 2.0 - 300.0 } };
    }
    SCOPED_TRACE(seed);
    ExpectDelaunay(points);
  }
}

TEST(DelaunayTetrahedra, TubeWallMatchesTheEmptySphereDefinition)
{
  // Rings of a 3 mm tube, slightly jittered as the centerlines jitter a vessel's wall: the
  // long, thin empty spheres inside are the internal Voronoi diagram's.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  std::vector<Point> points;
  const double pi = std::acos(-1.0);
  for (int ring = 0; ring < 8; ++ring)
  {
    for (int k = 0; k < 9; ++k)
    {
      const double a = 2 * pi * (k + 0.5 * (ring % 2)) / 9;
      points.push_back({ { 3 * std::cos(a) + jitter(random),
        3 * std::sin(a) + jitter(random),
        1.2 * ring + jitter(random) } });
    }
  }
  ExpectDelaunay(points);
}

TEST(DelaunayTetrahedra, ThousandsOfPointsMatchQhull)
{
  // At scale, against Qhull (installed by scripts/setup): 6,000 random points in a ball, where
  // the Delaunay tetrahedra are unique. Both sets, restricted to circumspheres below 1.25
  // diagonals, must be the same.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Point> points;
  while (points.size() < 6000)
  {
    const Point p{ { u(random), u(random), u(random) } };
    if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= 1.0)
    {
      points.push_back({ { 40 * p[0] - 12, 40 * p[1] + 210, 40 * p[2] + 95 } });
    }
  }
  std::vector<Tet> ours, qhull;
  std::string error;
  ASSERT_TRUE(bender::DelaunayTetrahedra(points, ours, error)) << error;
  ASSERT_TRUE(bender::QhullTetrahedra(points, qhull, error)) << error;
  const long double limit = 1.25L * Diagonal(points);
  auto small = [&](const std::vector<Tet>& tets)
  {
    std::set<Tet> kept;
    for (const Tet& t : tets)
    {
      std::array<long double, 3> centre;
      long double r2 = 0;
      if (Circumsphere(points[t[0]], points[t[1]], points[t[2]], points[t[3]], centre, r2) &&
        r2 < limit * limit)
      {
        kept.insert(Sorted(t));
      }
    }
    return kept;
  };
  const std::set<Tet> a = small(ours), b = small(qhull);
  EXPECT_GT(a.size(), 5 * points.size());
  EXPECT_EQ(a.size(), b.size());
  std::size_t missing = 0;
  for (const Tet& t : b)
  {
    missing += a.count(t) ? 0 : 1;
  }
  EXPECT_EQ(missing, 0u) << "Qhull's tetrahedra missing from ours";
}

// Neighbours: across the face opposite vertex k of t lies u, which holds that face and points
// back; a face shared by two tetrahedra is always linked, a face of one only never.
void ExpectConsistentNeighbours(const std::vector<Tet>& tets,
  const std::vector<std::array<vtkIdType, 4>>& neighbours)
{
  ASSERT_EQ(neighbours.size(), tets.size());
  std::map<std::array<vtkIdType, 3>, int> uses;
  auto face = [&tets](std::size_t t, int k)
  {
    std::array<vtkIdType, 3> f{};
    int m = 0;
    for (int j = 0; j < 4; ++j)
    {
      if (j != k)
      {
        f[m++] = tets[t][j];
      }
    }
    std::sort(f.begin(), f.end());
    return f;
  };
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    for (int k = 0; k < 4; ++k)
    {
      ++uses[face(t, k)];
    }
  }
  for (std::size_t t = 0; t < tets.size(); ++t)
  {
    for (int k = 0; k < 4; ++k)
    {
      const vtkIdType u = neighbours[t][k];
      if (u < 0)
      {
        EXPECT_EQ(uses[face(t, k)], 1) << "a shared face is not linked";
        continue;
      }
      ASSERT_LT(u, static_cast<vtkIdType>(tets.size()));
      int back = -1;
      for (int j = 0; j < 4; ++j)
      {
        back = neighbours[u][j] == static_cast<vtkIdType>(t) ? j : back;
      }
      ASSERT_GE(back, 0) << "the neighbour does not point back";
      EXPECT_EQ(face(static_cast<std::size_t>(u), back), face(t, k));
    }
  }
}

TEST(DelaunayTetrahedra, NeighboursAreTheTetrahedraAcrossEachFace)
{
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::vector<Point> points(800);
  for (auto& p : points)
  {
    p = { { u(random), u(random), u(random) } };
  }
  std::vector<Tet> tets, qhull;
  std::vector<std::array<vtkIdType, 4>> neighbours, qhullNeighbours;
  std::string error;
  ASSERT_TRUE(bender::DelaunayTetrahedra(points, tets, error, nullptr, &neighbours)) << error;
  ExpectConsistentNeighbours(tets, neighbours);
  // Qhull's neighbours (the fallback's) come from matching faces.
  ASSERT_TRUE(bender::QhullTetrahedra(points, qhull, error, &qhullNeighbours)) << error;
  ExpectConsistentNeighbours(qhull, qhullNeighbours);
}

TEST(DelaunayTetrahedra, CoSphericalLatticeIsTriangulatedWithoutFlatTetrahedra)
{
  // A 3 x 3 x 3 lattice, symmetric about its centre, so that it stays an exact lattice on the
  // triangulation's grid: every unit cube's eight corners are exactly co-spherical, and only
  // the symbolic perturbation decides. The result must still tile the cube.
  std::vector<Point> points;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      for (int k = 0; k < 3; ++k)
      {
        points.push_back({ { 10.0 + 2.5 * i, -4.0 + 2.5 * j, 7.0 + 2.5 * k } });
      }
    }
  }
  std::vector<Tet> tets;
  std::string error;
  bender::DelaunayStatistics stats;
  ASSERT_TRUE(bender::DelaunayTetrahedra(points, tets, error, &stats)) << error;
  EXPECT_GT(stats.perturbations, 0) << "the lattice's ties were broken by the perturbation";
  EXPECT_GT(stats.exactTests, 0);
  long double volume = 0;
  for (const Tet& t : tets)
  {
    const long double v = Orient(points[t[0]], points[t[1]], points[t[2]], points[t[3]]) / 6;
    EXPECT_GT(v, 1e-6L) << "a flat or inverted tetrahedron";
    volume += v;
    // Non-strictly empty: lattice points may lie on the sphere, none inside.
    EXPECT_GE(EmptinessMargin(points, t), -1e-6L);
  }
  const double side = points.back()[0] - points.front()[0];
  EXPECT_NEAR(static_cast<double>(volume), side * side * side, 1e-6 * side * side * side)
    << "the tetrahedra tile the lattice's cube";
}

TEST(DelaunayTetrahedra, ExactGridLatticeWithManyTiesTilesItsCube)
{
  // A 5 x 5 x 5 lattice placed exactly on the triangulation's grid (inside eight frame points
  // that fix the grid): 64 cubes of eight exactly co-spherical corners and many more ties
  // between them, all decided by the perturbation, which must be consistent for the cavities
  // to stay star-shaped.
  const double l = 40.0;
  std::vector<Point> frame;
  for (int c = 0; c < 8; ++c)
  {
    frame.push_back({ { c & 1 ? l : -l, c & 2 ? l : -l, c & 4 ? l : -l } });
  }
  std::vector<Point> probe = frame;
  std::vector<Tet> tets;
  std::string error;
  bender::DelaunayStatistics stats;
  ASSERT_TRUE(bender::DelaunayTetrahedra(probe, tets, error, &stats)) << error;
  const double spacing = 60000.0 * stats.gridStep;
  ASSERT_LT(2 * spacing, l);
  std::vector<Point> points = frame;
  for (int i = -2; i <= 2; ++i)
  {
    for (int j = -2; j <= 2; ++j)
    {
      for (int k = -2; k <= 2; ++k)
      {
        points.push_back({ { i * spacing, j * spacing, k * spacing } });
      }
    }
  }
  const std::vector<Point> original = points;
  ASSERT_TRUE(bender::DelaunayTetrahedra(points, tets, error, &stats)) << error;
  EXPECT_TRUE(std::equal(points.begin() + 8, points.end(), original.begin() + 8))
    << "the lattice lies on the grid already (the frame's corners need not)";
  EXPECT_GT(stats.perturbations, 100);
  EXPECT_EQ(stats.duplicates, 0);
  long double volume = 0;
  for (const Tet& t : tets)
  {
    const long double v = Orient(points[t[0]], points[t[1]], points[t[2]], points[t[3]]) / 6;
    EXPECT_GT(v, 0) << "a flat or inverted tetrahedron";
    volume += v;
    EXPECT_GE(EmptinessMargin(points, t), -1e-9L * l * l);
  }
  // The frame's cube (as snapped) is the convex hull; every tetrahedron inside has a small
  // circumsphere.
  const long double side = points[7][0] - points[0][0];
  EXPECT_NEAR(static_cast<double>(volume),
    static_cast<double>(side * side * side),
    1e-9 * static_cast<double>(side * side * side))
    << "the tetrahedra tile the frame's cube";
}

TEST(DelaunayTetrahedra, DuplicatesAreLeftOut)
{
  std::vector<Point> points = { { { 0, 0, 0 } },
    { { 1, 0, 0 } },
    { { 0, 1, 0 } },
    { { 0, 0, 1 } },
    { { 1, 0, 0 } },
    { { 0.2, 0.2, 0.2 } } };
  std::vector<Tet> tets;
  std::string error;
  bender::DelaunayStatistics stats;
  ASSERT_TRUE(bender::DelaunayTetrahedra(points, tets, error, &stats)) << error;
  EXPECT_EQ(stats.duplicates, 1);
  // Whichever of the two equal points comes later in the insertion order is left out.
  bool used[6] = { false, false, false, false, false, false };
  long double volume = 0;
  for (const Tet& t : tets)
  {
    for (vtkIdType id : t)
    {
      used[id] = true;
    }
    volume += Orient(points[t[0]], points[t[1]], points[t[2]], points[t[3]]) / 6;
  }
  EXPECT_NE(used[1], used[4]) << "exactly one of the two equal points is a vertex";
  EXPECT_TRUE(used[0] && used[2] && used[3] && used[5]);
  // The points moved onto the grid by up to half a step (about 1e-6 of this unit cube).
  EXPECT_NEAR(static_cast<double>(volume), 1.0 / 6.0, 1e-5);
  EXPECT_LT(stats.gridStep, 1e-5);
}

TEST(DelaunayTetrahedra, DegenerateInputGivesAReason)
{
  std::vector<Tet> tets;
  std::string error;
  std::vector<Point> three = { { { 0, 0, 0 } }, { { 1, 0, 0 } }, { { 0, 1, 0 } } };
  EXPECT_FALSE(bender::DelaunayTetrahedra(three, tets, error));
  EXPECT_NE(error.find("fewer than four"), std::string::npos) << error;

  std::vector<Point> same(5, Point{ { 3, 3, 3 } });
  EXPECT_FALSE(bender::DelaunayTetrahedra(same, tets, error));
  EXPECT_NE(error.find("coincide"), std::string::npos) << error;

  std::vector<Point> flat;
  for (int i = 0; i < 20; ++i)
  {
    flat.push_back({ { std::cos(i * 1.3) * i, std::sin(i * 0.7) * i, 5.0 } });
  }
  EXPECT_FALSE(bender::DelaunayTetrahedra(flat, tets, error));
  EXPECT_NE(error.find("co-planar"), std::string::npos) << error;

  std::vector<Point> nan = three;
  nan.push_back({ { 0, std::nan(""), 1 } });
  EXPECT_FALSE(bender::DelaunayTetrahedra(nan, tets, error));
  EXPECT_NE(error.find("non-finite"), std::string::npos) << error;
}

} // namespace
