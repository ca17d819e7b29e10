// Property tests of the projection of points onto the wire (spec 3, section 8 items 11-14).

#include "Biarc.h"
#include "GeometryErrors.h"
#include "GeometryTestUtilities.h"
#include "RibbonWarp.h"
#include "WireProjection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
using bender::Biarc;
using bender::Distance;
using bender::Dot;
using bender::Norm;
using bender::Vec3;
using bender::WireProjections;
using bendertest::Pi;

const double Inf = std::numeric_limits<double>::infinity();

Biarc Make(const bender::RibbonSpec& r)
{
  return Biarc::FromEnds(r.start.position, r.start.tangent, r.end.position, r.end.tangent);
}

std::vector<Biarc> RandomWires(std::uint64_t seed, int count)
{
  std::mt19937_64 rng(seed);
  std::vector<Biarc> out;
  while (static_cast<int>(out.size()) < count)
  {
    const bender::RibbonSpec r =
      out.size() % 2 == 0 ? bendertest::RandomRibbon(rng) : bendertest::RandomWildRibbon(rng);
    try
    {
      const Biarc w = Make(r);
      if (w.MinimumRadius() > 0.05 && w.Length() < 100)
      {
        out.push_back(w);
      }
    }
    catch (const bender::InvalidRibbonError&)
    {
    }
  }
  return out;
}

struct Minimum
{
  double s;
  double d;
};

// Discrete local minima of d(s) = |P - X(s)| over the samples.
std::vector<Minimum> BruteForceMinima(const std::vector<Vec3>& samples, const Vec3& p)
{
  const int n = static_cast<int>(samples.size());
  std::vector<double> d(n);
  for (int k = 0; k < n; ++k)
  {
    d[k] = Distance(p, samples[k]);
  }
  std::vector<Minimum> out;
  for (int k = 0; k < n; ++k)
  {
    const bool leftOk = k == 0 || d[k] < d[k - 1];
    const bool rightOk = k == n - 1 || d[k] <= d[k + 1];
    if (leftOk && rightOk)
    {
      out.push_back({ static_cast<double>(k) / (n - 1), d[k] });
    }
  }
  return out;
}

std::vector<Vec3> Sample(const Biarc& w, int n)
{
  std::vector<Vec3> x(n);
  for (int k = 0; k < n; ++k)
  {
    x[k] = w.PointAt(static_cast<double>(k) / (n - 1));
  }
  return x;
}

// A random point near the wire: a point of the wire (or beyond an end) plus an offset.
Vec3 RandomNearPoint(std::mt19937_64& rng, const Biarc& w, double reach)
{
  const double s = bendertest::Uniform(rng, -0.1, 1.1);
  Vec3 base;
  if (s < 0)
  {
    base = w.Start() + w.StartTangent() * (s * w.Length());
  }
  else if (s > 1)
  {
    base = w.End() + w.EndTangent() * ((s - 1) * w.Length());
  }
  else
  {
    base = w.PointAt(s);
  }
  return base + bendertest::RandomUnit(rng) * bendertest::Uniform(rng, 0, reach);
}

TEST(Projection, AgreesWithBruteForceWithinTheRegionOfInfluence)
{
  std::mt19937_64 rng(51);
  auto wires = RandomWires(52, 100);
  // Wires whose ends come close (nearly closed circles with gaps up to 1 rad): points near
  // the gap have two projections.
  for (int i = 0; i < 30; ++i)
  {
    const double g = bendertest::Uniform(rng, 0.05, 1.0);
    const double rho = bendertest::Uniform(rng, 0.5, 5);
    const bendertest::Rigid G = bendertest::RandomRigid(rng, 5);
    wires.push_back(Biarc::FromEnds(G.Point({ rho * std::cos(g / 2), rho * std::sin(g / 2), 0 }),
      G.Vector({ -std::sin(g / 2), std::cos(g / 2), 0 }),
      G.Point({ rho * std::cos(g / 2), -rho * std::sin(g / 2), 0 }),
      G.Vector({ std::sin(g / 2), std::cos(g / 2), 0 })));
  }
  int compared = 0, withTwo = 0;
  for (const Biarc& w : wires)
  {
    const auto samples = Sample(w, 10000);
    const double R = w.MinimumRadius() < 1e6
      ? bendertest::Uniform(rng, 0.2, 0.9) * w.MinimumRadius()
      : bendertest::Uniform(rng, 0.05, 0.5) * w.Length();
    for (int i = 0; i < 40; ++i)
    {
      const Vec3 p = RandomNearPoint(rng, w, 1.2 * R);
      auto brute = BruteForceMinima(samples, p);
      // Points whose minimum lies near the RoI boundary are ambiguous for the sampling.
      bool ambiguous = false;
      std::vector<Minimum> inside;
      for (const Minimum& m : brute)
      {
        ambiguous = ambiguous || std::abs(m.d - R) < 1e-3 * R;
        if (m.d < R)
        {
          inside.push_back(m);
        }
      }
      if (ambiguous)
      {
        continue;
      }
      ++compared;
      const WireProjections pr = bender::ProjectOntoWire(w, p, R);
      ASSERT_EQ(pr.count, static_cast<int>(inside.size()))
        << "R=" << R << " r_min=" << w.MinimumRadius();
      withTwo += pr.count == 2;
      std::vector<double> got;
      for (int k = 0; k < pr.count; ++k)
      {
        got.push_back(pr.items[k].s);
        EXPECT_LT(pr.items[k].distance, R);
      }
      std::sort(got.begin(), got.end());
      for (int k = 0; k < pr.count; ++k)
      {
        EXPECT_NEAR(got[k], inside[k].s, 1e-3);
      }
      if (pr.count == 2)
      {
        // Nearest first; ties by the smaller s.
        EXPECT_TRUE(pr.items[0].distance < pr.items[1].distance ||
          (pr.items[0].distance == pr.items[1].distance && pr.items[0].s <= pr.items[1].s));
      }
    }
  }
  EXPECT_GT(compared, 4000);
  EXPECT_GT(withTwo, 20);
}

TEST(Projection, AtMostTwoLocalMinimaCloserThanTheSmallestRadius)
{
  std::mt19937_64 rng(53);
  const auto wires = RandomWires(54, 80);
  int tested = 0;
  for (const Biarc& w : wires)
  {
    if (!(w.MinimumRadius() < 1e6))
    {
      continue;
    }
    const auto samples = Sample(w, 10000);
    const double rmin = w.MinimumRadius();
    for (int i = 0; i < 50; ++i)
    {
      const Vec3 p = RandomNearPoint(rng, w, rmin);
      const auto brute = BruteForceMinima(samples, p);
      double dist = Inf;
      for (const Minimum& m : brute)
      {
        dist = std::min(dist, m.d);
      }
      if (!(dist < 0.999 * rmin))
      {
        continue;
      }
      ++tested;
      int count = 0;
      for (const Minimum& m : brute)
      {
        count += m.d < rmin;
      }
      EXPECT_LE(count, 2);
      const WireProjections all = bender::ProjectOntoWire(w, p, Inf);
      EXPECT_GE(all.count, 1);
      // The samples are 1e-4 L apart: the sampled minimum exceeds the true one by less
      // than half a spacing.
      EXPECT_LE(all.items[0].distance, dist + 1e-9 * w.Length());
      EXPECT_GT(all.items[0].distance, dist - 0.5e-4 * w.Length());
    }
  }
  EXPECT_GT(tested, 1000);
}

TEST(Projection, FootPointsLieOnTheWireAndAreOrthogonal)
{
  std::mt19937_64 rng(55);
  int interior = 0, ends = 0;
  for (const Biarc& w : RandomWires(56, 500))
  {
    const double h = std::max({ 1.0, Norm(w.Start()), Norm(w.End()) });
    for (int i = 0; i < 40; ++i)
    {
      const Vec3 p = RandomNearPoint(rng, w, 0.5 * std::min(w.MinimumRadius(), w.Length()));
      const WireProjections pr = bender::ProjectOntoWire(w, p, Inf);
      for (int k = 0; k < pr.count; ++k)
      {
        const auto& it = pr.items[k];
        ASSERT_GE(it.s, 0.0);
        ASSERT_LE(it.s, 1.0);
        EXPECT_LT(Distance(it.foot, w.PointAt(it.s)), 1e-9 * h);
        EXPECT_NEAR(it.distance, Distance(p, it.foot), 1e-12 * h);
        if (it.s > 0.0 && it.s < 1.0)
        {
          ++interior;
          EXPECT_NEAR(Dot(p - it.foot, w.TangentAt(it.s)), 0.0, 1e-9 * h) << "s=" << it.s;
        }
        else if (it.s == 0.0)
        {
          ++ends;
          EXPECT_LT(Distance(it.foot, w.Start()), 1e-12 * h);
          // A free end counts only when the wire moves away from P there (or the interior
          // foot point is exactly the end).
          EXPECT_LE(Dot(p - w.Start(), w.StartTangent()), 1e-9 * h);
        }
        else
        {
          ++ends;
          EXPECT_LT(Distance(it.foot, w.End()), 1e-12 * h);
          EXPECT_GE(Dot(p - w.End(), w.EndTangent()), -1e-9 * h);
        }
      }
    }
  }
  EXPECT_GT(interior, 5000);
  EXPECT_GT(ends, 500);
}

TEST(Projection, EndRule)
{
  std::mt19937_64 rng(57);
  for (const Biarc& w : RandomWires(58, 500))
  {
    for (int i = 0; i < 20; ++i)
    {
      const Vec3 p = RandomNearPoint(rng, w, w.Length());
      const WireProjections pr = bender::ProjectOntoWire(w, p, Inf);
      bool has0 = false, has1 = false;
      for (int k = 0; k < pr.count; ++k)
      {
        has0 = has0 || (pr.items[k].s == 0.0 && Distance(pr.items[k].foot, w.Start()) == 0.0);
        has1 = has1 || (pr.items[k].s == 1.0 && Distance(pr.items[k].foot, w.End()) == 0.0);
      }
      if (Dot(p - w.Start(), w.StartTangent()) < 0)
      {
        EXPECT_TRUE(has0);
      }
      if (Dot(p - w.End(), w.EndTangent()) > 0)
      {
        EXPECT_TRUE(has1);
      }
      // With a finite R the end counts only when closer than R.
      const double R = 0.5 * Distance(p, w.Start());
      const WireProjections near = bender::ProjectOntoWire(w, p, R);
      for (int k = 0; k < near.count; ++k)
      {
        EXPECT_LT(near.items[k].distance, R);
      }
    }
  }
}

// Points exactly on the normal planes at P0, J and P1 of symmetric wires (exact arithmetic
// puts them on the planes): exactly one candidate, no gaps and no duplicates.
TEST(Projection, NormalPlanesArePartitionedWithoutGapsOrDuplicates)
{
  // U-turn: P0 = 0, T0 = x, P1 = (0, 2, 0), T1 = -x. The planes at P0 and P1 are both x = 0,
  // J = (1, 1, 0) with U = y: the plane at J is y = 1.
  const Vec3 x{ 1, 0, 0 };
  const Biarc u = Biarc::FromEnds({ 0, 0, 0 }, x, { 0, 2, 0 }, -x);
  ASSERT_EQ(u.Junction().y, 1.0);
  ASSERT_EQ(u.JunctionTangent().x, 0.0);
  ASSERT_EQ(u.JunctionTangent().z, 0.0);
  const double R = 0.75; // < r_min = 1
  int onPlanes = 0;
  for (int i = -16; i <= 16; ++i)
  {
    for (int j = -16; j <= 48; ++j)
    {
      for (int k = -8; k <= 8; ++k)
      {
        const Vec3 p{ i / 16.0, j / 16.0, k / 16.0 };
        const WireProjections pr = bender::ProjectOntoWire(u, p, R);
        // Distance to the wire, in closed form: the wire is the half circle of radius 1 about
        // (0, 1, 0) in the plane z = 0, on the side x >= 0.
        double best = std::min(Distance(p, u.Start()), Distance(p, u.End()));
        if (p.x >= 0)
        {
          const double inPlane = std::hypot(p.x, p.y - 1.0);
          best = std::min(best, std::hypot(inPlane - 1.0, p.z));
        }
        if (best < 0.98 * R)
        {
          ASSERT_GE(pr.count, 1) << "gap at " << p.x << "," << p.y << "," << p.z;
          EXPECT_NEAR(pr.items[0].distance, best, 1e-12);
        }
        if (pr.count == 2)
        {
          EXPECT_NE(pr.items[0].s, pr.items[1].s)
            << "duplicate at " << p.x << "," << p.y << "," << p.z;
          EXPECT_GT(Distance(pr.items[0].foot, pr.items[1].foot), 1e-6);
        }
        const bool onPlane = i == 0 || j == 16;
        if (onPlane && best < 0.98 * R)
        {
          ++onPlanes;
          EXPECT_EQ(pr.count, 1) << "at " << p.x << "," << p.y << "," << p.z;
          if (i == 0 && j < 16)
          {
            EXPECT_NEAR(pr.items[0].s, 0.0, 1e-15);
          }
          if (i == 0 && j > 16)
          {
            EXPECT_NEAR(pr.items[0].s, 1.0, 1e-15);
          }
          if (j == 16)
          {
            EXPECT_NEAR(pr.items[0].s, 0.5, 1e-12);
          }
        }
      }
    }
  }
  EXPECT_GT(onPlanes, 50);
}

TEST(Projection, SymmetricWireJunctionPlane)
{
  // Coplanar symmetric wire about x = 0: P0 = (-1, 0, 0), P1 = (1, 0, 0), tangents mirrored.
  // Then U = (1, 0, 0) and J.x = 0 exactly, so the plane at J is x = 0.
  for (double alpha : { 0.3, 0.9, 1.4, -0.7 })
  {
    const Biarc w = Biarc::FromEnds({ -1, 0, 0 },
      { std::cos(alpha), std::sin(alpha), 0 },
      { 1, 0, 0 },
      { std::cos(alpha), -std::sin(alpha), 0 });
    ASSERT_EQ(w.Junction().x, 0.0);
    ASSERT_EQ(w.JunctionTangent().y, 0.0);
    const double R = 0.5 * w.MinimumRadius();
    const Vec3 J = w.Junction();
    int tested = 0;
    for (int j = -20; j <= 20; ++j)
    {
      for (int k = -20; k <= 20; ++k)
      {
        const Vec3 p{ 0.0, J.y + j * R / 16, k * R / 16 };
        const WireProjections pr = bender::ProjectOntoWire(w, p, R);
        const double dist = Distance(p, J);
        if (dist < 0.98 * R)
        {
          ++tested;
          ASSERT_EQ(pr.count, 1) << "j=" << j << " k=" << k;
          EXPECT_NEAR(pr.items[0].s, w.JunctionParameter(), 1e-12);
          EXPECT_NEAR(pr.items[0].distance, dist, 1e-12);
          // Mirror points on both sides of the plane project symmetrically.
          const double e = 1e-13;
          const WireProjections a = bender::ProjectOntoWire(w, p + Vec3{ e, 0, 0 }, R);
          const WireProjections b = bender::ProjectOntoWire(w, p - Vec3{ e, 0, 0 }, R);
          ASSERT_EQ(a.count, 1);
          ASSERT_EQ(b.count, 1);
          EXPECT_NEAR(
            a.items[0].s - w.JunctionParameter(), w.JunctionParameter() - b.items[0].s, 1e-12);
        }
        else if (dist >= R)
        {
          EXPECT_EQ(pr.count, 0);
        }
      }
    }
    EXPECT_GT(tested, 500);
  }
}

TEST(Projection, PointsOnAnArcAxisGetNoInteriorCandidate)
{
  // U-turn: both arcs about the axis through (0, 1, 0) along z; points on that axis are at
  // distance >= 1 = r_min from every point of the wire.
  const Vec3 x{ 1, 0, 0 };
  const Biarc u = Biarc::FromEnds({ 0, 0, 0 }, x, { 0, 2, 0 }, -x);
  for (double z : { 0.0, 0.5, -2.0 })
  {
    const WireProjections pr = bender::ProjectOntoWire(u, { 0, 1, z }, 0.99);
    EXPECT_EQ(pr.count, 0);
    const WireProjections all = bender::ProjectOntoWire(u, { 0, 1, z }, Inf);
    for (int k = 0; k < all.count; ++k)
    {
      EXPECT_TRUE(std::isfinite(all.items[k].s));
      EXPECT_GE(all.items[k].distance, 1.0 - 1e-12);
    }
  }
}

} // namespace
