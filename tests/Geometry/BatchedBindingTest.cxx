// The batched projection and binding (issue 14): vectorised blocks against the single-point
// paths, at every instruction set this machine has; against the projection as it was written
// before (std::atan2, divisions); the capsule pre-filter against the region of influence.

#include "Decay.h"
#include "FastWarpKernel.h"
#include "GeometryTestUtilities.h"
#include "Ribbon.h"
#include "WarpBinding.h"
#include "WireProjection.h"
#include "WireProjectionLane.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace
{
using bender::Vec3;
using bendertest::Uniform;

// The projection as written before the batched paths (std::atan2, divisions by rho, L and
// theta): the reference the new arithmetic must stay within rounding of.
bool ReferenceNearestOnArc(const bender::Arc& arc, const Vec3& p, double& u, Vec3& q)
{
  const Vec3 rel = p - arc.start;
  if (arc.line)
  {
    const double t = std::clamp(Dot(rel, arc.tangent), 0.0, arc.length);
    u = arc.length > 0.0 ? t / arc.length : 0.0;
    q = arc.start + arc.tangent * t;
    return true;
  }
  const double y = Dot(rel, arc.tangent);
  const double x = arc.radius - Dot(rel, arc.toCentre);
  const double rho = std::sqrt(x * x + y * y);
  if (rho <= 1e-12 * arc.radius)
  {
    return false;
  }
  const double raw = std::atan2(y, x);
  const double phi = std::clamp(raw, 0.0, arc.angle);
  u = arc.angle > 0.0 ? phi / arc.angle : 0.0;
  if (phi != raw)
  {
    q = arc.PointAt(u);
    return true;
  }
  const double c = x / rho;
  const double sn = y / rho;
  const double r = arc.radius;
  const double lift = c > 0.0 ? r * sn * sn / (1.0 + c) : r * (1.0 - c);
  q = arc.start + arc.tangent * (r * sn) + arc.toCentre * lift;
  return true;
}

// Every candidate of the signed-plane partition (no radius, no selection): (s, distance).
std::vector<std::pair<double, double>> ReferenceCandidates(const bender::Biarc& wire, const Vec3& p)
{
  std::vector<std::pair<double, double>> out;
  const double sJ = wire.JunctionParameter();
  const double h0 = Dot(p - wire.Start(), wire.StartTangent());
  const double hJ = Dot(p - wire.Junction(), wire.JunctionTangent());
  const double h1 = Dot(p - wire.End(), wire.EndTangent());
  double u = 0.0;
  Vec3 q;
  if (h0 >= 0.0 && hJ < 0.0 && ReferenceNearestOnArc(wire.FirstArc(), p, u, q))
  {
    out.emplace_back(sJ * u, Distance(p, q));
  }
  if (hJ >= 0.0 && h1 <= 0.0 && ReferenceNearestOnArc(wire.SecondArc(), p, u, q))
  {
    out.emplace_back(sJ + (1.0 - sJ) * u, Distance(p, q));
  }
  if (h0 < 0.0)
  {
    out.emplace_back(0.0, Distance(p, wire.Start()));
  }
  if (h1 > 0.0)
  {
    out.emplace_back(1.0, Distance(p, wire.End()));
  }
  return out;
}

// Wires of every kind: random, straight, two semicircles, nearly straight arcs.
std::vector<bender::RibbonSpec> Wires(std::mt19937_64& rng)
{
  std::vector<bender::RibbonSpec> wires;
  for (int i = 0; i < 40; ++i)
  {
    wires.push_back(bendertest::RandomRibbon(rng, 4.0));
  }
  bender::RibbonSpec straight;
  straight.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  straight.end = { { 40, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  wires.push_back(straight);
  bender::RibbonSpec semicircles;
  semicircles.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  semicircles.end = { { 0, 4, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  wires.push_back(semicircles);
  bender::RibbonSpec gentle = straight;
  gentle.end.tangent = { 1, 1e-7, 0 };
  wires.push_back(gentle);
  bender::RibbonSpec half = straight; // one straight arc, one curved
  half.end.position = { 40, 3, 0 };
  half.start.tangent = bender::Normalized(Vec3{ 40, 3, 0 } - Vec3{ 0, 0, 0 });
  half.end.tangent = half.start.tangent;
  wires.push_back(half);
  return wires;
}

// Points that stress the projection: on the wire, near it, on and near the arcs' axes and
// centres, on the normal planes at the ends and the junction, beyond the ends, far away.
std::vector<Vec3> HardPoints(std::mt19937_64& rng, const bender::Biarc& wire, double scale)
{
  std::vector<Vec3> pts;
  for (int k = 0; k <= 64; ++k)
  {
    const double s = k / 64.0;
    const Vec3 on = wire.PointAt(s);
    pts.push_back(on);
    pts.push_back(on + bendertest::RandomUnit(rng) * Uniform(rng, 0.0, 0.5 * scale));
  }
  for (int a = 0; a < 2; ++a)
  {
    const bender::Arc& arc = wire.GetArc(a);
    if (arc.line)
    {
      continue;
    }
    pts.push_back(arc.centre);
    for (int k = 0; k < 8; ++k)
    {
      pts.push_back(arc.centre + arc.axis * Uniform(rng, -scale, scale));
      pts.push_back(arc.centre + bendertest::RandomUnit(rng) * (1e-13 * arc.radius));
      pts.push_back(arc.centre + bendertest::RandomUnit(rng) * (1e-9 * arc.radius));
    }
  }
  const Vec3 ends[3][2] = { { wire.Start(), wire.StartTangent() },
    { wire.Junction(), wire.JunctionTangent() },
    { wire.End(), wire.EndTangent() } };
  for (const auto& e : ends)
  {
    for (int k = 0; k < 12; ++k)
    {
      const Vec3 in = bendertest::RandomPerpendicular(rng, e[1]) * Uniform(rng, 0.0, scale);
      pts.push_back(e[0] + in);
      pts.push_back(e[0] + in + e[1] * 1e-12);
      pts.push_back(e[0] + in - e[1] * 1e-12);
      pts.push_back(e[0] + e[1] * Uniform(rng, -scale, scale));
    }
  }
  for (int k = 0; k < 100; ++k)
  {
    pts.push_back(wire.PointAt(0.5) + bendertest::RandomPoint(rng, 3.0 * scale));
  }
  pts.push_back(wire.PointAt(0.5) + Vec3{ 1e4, -2e4, 3e4 });
  return pts;
}

bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

const bender::SimdLevel Levels[] = { bender::SimdLevel::Baseline,
  bender::SimdLevel::Avx2,
  bender::SimdLevel::Avx512 };

TEST(BatchedProjection, EverySimdLevelGivesTheSinglePointResultBitForBit)
{
  std::mt19937_64 rng(1401);
  long long compared = 0;
  for (const bender::RibbonSpec& spec : Wires(rng))
  {
    const bender::Ribbon ribbon(spec);
    const bender::Biarc& wire = ribbon.Wire();
    const double scale = wire.Length();
    const std::vector<Vec3> pts = HardPoints(rng, wire, scale);
    std::vector<double> xyz;
    for (const Vec3& p : pts)
    {
      xyz.insert(xyz.end(), { p.x, p.y, p.z });
    }
    for (const double radius : { 0.3 * scale, std::numeric_limits<double>::infinity() })
    {
      for (const bender::SimdLevel level : Levels)
      {
        std::vector<bender::WireProjections> batch(pts.size());
        if (!bender::ProjectOntoWire(wire, xyz.data(), pts.size(), radius, batch.data(), level))
        {
          EXPECT_FALSE(bender::FastWarpKernel::Supports(level));
          continue;
        }
        for (std::size_t k = 0; k < pts.size(); ++k)
        {
          const bender::WireProjections one = bender::ProjectOntoWire(wire, pts[k], radius);
          ASSERT_EQ(batch[k].count, one.count) << "point " << k;
          for (int i = 0; i < one.count; ++i)
          {
            const bender::WireProjection& a = batch[k].items[i];
            const bender::WireProjection& b = one.items[i];
            ASSERT_TRUE(std::isfinite(a.s) && std::isfinite(a.distance) && IsFinite(a.foot));
            EXPECT_TRUE(SameBits(a.s, b.s) && SameBits(a.distance, b.distance) &&
              SameBits(a.foot.x, b.foot.x) && SameBits(a.foot.y, b.foot.y) &&
              SameBits(a.foot.z, b.foot.z))
              << "point " << k << " projection " << i << ": s " << a.s << " vs " << b.s;
            ++compared;
          }
        }
      }
    }
  }
  EXPECT_GT(compared, 10000);
}

TEST(BatchedProjection, StaysWithinRoundingOfTheLibmProjection)
{
  // Every projection found is a candidate of the reference (std::atan2, divisions) with the
  // same s and distance within 1e-12 (relative to the wire), and the two nearest reference
  // candidates within R are the ones kept.
  std::mt19937_64 rng(1402);
  long long compared = 0;
  for (const bender::RibbonSpec& spec : Wires(rng))
  {
    const bender::Ribbon ribbon(spec);
    const bender::Biarc& wire = ribbon.Wire();
    const double scale = wire.Length();
    const double radius = 0.3 * scale;
    for (const Vec3& p : HardPoints(rng, wire, scale))
    {
      auto ref = ReferenceCandidates(wire, p);
      const double tol = 1e-12 * std::max(1.0, scale);
      // A candidate within rounding of R may be kept by one projection and dropped by the
      // other (compilers contract and vectorise differently): such points are not clear cases.
      if (std::any_of(ref.begin(),
            ref.end(),
            [radius, tol](const std::pair<double, double>& c)
            { return std::abs(c.second - radius) <= tol; }))
      {
        continue;
      }
      ref.erase(std::remove_if(ref.begin(),
                  ref.end(),
                  [radius](const std::pair<double, double>& c) { return !(c.second < radius); }),
        ref.end());
      std::stable_sort(ref.begin(),
        ref.end(),
        [](const std::pair<double, double>& a, const std::pair<double, double>& b)
        { return a.second < b.second || (a.second == b.second && a.first < b.first); });
      const bender::WireProjections got = bender::ProjectOntoWire(wire, p, radius);
      // Near-ties (two candidates within rounding of each other, or of R) may order or count
      // differently: compare only clear cases.
      bool clear = true;
      for (std::size_t i = 0; i < ref.size(); ++i)
      {
        clear = clear && std::abs(ref[i].second - radius) > tol;
        if (i > 0)
        {
          clear = clear && std::abs(ref[i].second - ref[i - 1].second) > tol;
        }
      }
      if (!clear)
      {
        continue;
      }
      ASSERT_EQ(got.count, static_cast<int>(std::min<std::size_t>(2, ref.size())));
      for (int i = 0; i < got.count; ++i)
      {
        EXPECT_NEAR(got.items[i].s, ref[i].first, 1e-12);
        EXPECT_NEAR(got.items[i].distance, ref[i].second, tol);
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 3000);
}

std::vector<bender::WarpSpec> Specs(std::mt19937_64& rng)
{
  std::vector<bender::WarpSpec> specs;
  int i = 0;
  for (const bender::RibbonSpec& r : Wires(rng))
  {
    bender::WarpSpec w;
    w.initial = r;
    w.final = bendertest::Perturbed(rng, r, 0.3, 0.4);
    w.radius = 0.25 * bender::Ribbon(r).Wire().Length();
    w.decay = i % 2 ? bender::DecaySpec{ bender::DecayShape::Bell, 0.5 }
                    : bender::DecaySpec{ bender::DecayShape::Plateau, 0.95 * (i % 5) / 4.0 };
    specs.push_back(w);
    ++i;
  }
  return specs;
}

TEST(BatchedBinding, RecordsEqualTheSinglePointBindingBitForBit)
{
  std::mt19937_64 rng(1403);
  long long bound = 0, pairs = 0;
  for (const bender::WarpSpec& spec : Specs(rng))
  {
    for (const bender::BlendMode blend :
      { bender::BlendMode::TwoProjections, bender::BlendMode::SingleProjection })
    {
      const bender::WarpBinding binding(spec, blend);
      const bender::Biarc& wire = binding.InitialRibbon().Wire();
      const std::vector<Vec3> pts = HardPoints(rng, wire, wire.Length());
      std::vector<double> xyz;
      for (const Vec3& p : pts)
      {
        xyz.insert(xyz.end(), { p.x, p.y, p.z });
      }
      const std::size_t n = pts.size();
      std::vector<bender::BoundPoint> whole(n), split(n);
      std::vector<std::uint8_t> flags(n, 7), splitFlags(n, 7);
      binding.BindRange(xyz.data(), 0, n, whole.data(), flags.data());
      // Another split of the range: the same records.
      for (std::size_t b = 0; b < n; b += 37)
      {
        binding.BindRange(xyz.data(), b, std::min(n, b + 37), split.data(), splitFlags.data());
      }
      for (std::size_t k = 0; k < n; ++k)
      {
        bender::BoundPoint one;
        const bool isBound = binding.Bind(pts[k], one);
        ASSERT_EQ(flags[k] != 0, isBound) << "point " << k;
        ASSERT_EQ(flags[k], splitFlags[k]);
        ASSERT_LE(flags[k], 2);
        if (!isBound)
        {
          continue;
        }
        ++bound;
        EXPECT_EQ(flags[k] == 2, one.lambda0 < 1.0);
        pairs += flags[k] == 2 ? 1 : 0;
        for (const bender::BoundPoint* r : { &whole[k], &split[k] })
        {
          EXPECT_TRUE(SameBits(r->s0, one.s0) && SameBits(r->s1, one.s1) && SameBits(r->f, one.f) &&
            SameBits(r->lambda0, one.lambda0))
            << "point " << k;
        }
        EXPECT_TRUE(std::isfinite(one.s0) && std::isfinite(one.s1) && one.f > 0.0 && one.f <= 1.0 &&
          one.lambda0 > 0.0 && one.lambda0 <= 1.0);
        // The weights of the nearest projection, as the decay gives them from its distance.
        const bender::WireProjections pr = bender::ProjectOntoWire(wire, pts[k], spec.radius);
        ASSERT_GE(pr.count, 1);
        EXPECT_EQ(one.s0, pr.items[0].s);
        const double f0 = bender::EvaluateDecay(spec.decay, pr.items[0].distance / spec.radius);
        if (flags[k] == 1)
        {
          EXPECT_NEAR(one.f, f0, 1e-13); // the plateau amplifies rounding by 1 / (1 - p)
        }
      }
      // The float interface binds the float-rounded points alike.
      std::vector<float> xyzf(xyz.begin(), xyz.end());
      std::vector<bender::BoundPoint> recf(n);
      std::vector<std::uint8_t> flagsf(n);
      binding.BindRange(xyzf.data(), 0, n, recf.data(), flagsf.data());
      for (std::size_t k = 0; k < n; ++k)
      {
        bender::BoundPoint one;
        const Vec3 p{ xyzf[3 * k], xyzf[3 * k + 1], xyzf[3 * k + 2] };
        ASSERT_EQ(flagsf[k] != 0, binding.Bind(p, one));
        if (flagsf[k])
        {
          EXPECT_TRUE(SameBits(recf[k].s0, one.s0) && SameBits(recf[k].f, one.f));
        }
      }
    }
  }
  EXPECT_GT(bound, 5000);
  EXPECT_GT(pairs, 10);
}

TEST(BatchedBinding, CapsulePreFilterNeverDropsAPointWithinR)
{
  // Points within R of the wire, each in a block whose other points lie in the box but far
  // from the wire (so that the capsule test stays on), must all be bound: the bell weight is
  // positive everywhere inside R.
  std::mt19937_64 rng(1404);
  long long checked = 0;
  for (bender::WarpSpec spec : Specs(rng))
  {
    spec.decay = { bender::DecayShape::Bell, 0.5 };
    const bender::WarpBinding binding(spec, bender::BlendMode::TwoProjections);
    const bender::Biarc& wire = binding.InitialRibbon().Wire();
    const double R = spec.radius;
    Vec3 lo = wire.Start(), hi = wire.Start();
    for (int k = 0; k <= 64; ++k)
    {
      const Vec3 q = wire.PointAt(k / 64.0);
      lo = { std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z) };
      hi = { std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z) };
    }
    std::vector<double> xyz;
    std::vector<bool> inside;
    for (int k = 0; k < 4096; ++k)
    {
      Vec3 p;
      const bool near = k % 5 == 0;
      if (near)
      {
        // Within R of a point of the wire, up to 0.999 R (also just inside R).
        const double reach = R * (k % 3 == 0 ? 0.999 : Uniform(rng, 0.0, 0.999));
        p = wire.PointAt(Uniform(rng, 0.0, 1.0)) + bendertest::RandomUnit(rng) * reach;
      }
      else
      {
        p = { Uniform(rng, lo.x - R, hi.x + R),
          Uniform(rng, lo.y - R, hi.y + R),
          Uniform(rng, lo.z - R, hi.z + R) };
      }
      xyz.insert(xyz.end(), { p.x, p.y, p.z });
      inside.push_back(near);
    }
    const std::size_t n = inside.size();
    std::vector<bender::BoundPoint> rec(n);
    std::vector<std::uint8_t> flags(n);
    binding.BindRange(xyz.data(), 0, n, rec.data(), flags.data());
    for (std::size_t k = 0; k < n; ++k)
    {
      if (inside[k])
      {
        ++checked;
        EXPECT_NE(flags[k], 0) << "a point within R was dropped";
      }
    }
  }
  EXPECT_GT(checked, 30000);
}

TEST(BatchedBinding, LaneDecayIsTheDecay)
{
  // The decay on a lane (products by 1 / (1 - p)) against EvaluateDecay: the bell bit for
  // bit, the plateau within rounding; both zero from x = 1 on.
  std::mt19937_64 rng(1405);
  for (int k = 0; k < 20000; ++k)
  {
    const double x = k < 100 ? k / 99.0 * 1.01 : Uniform(rng, 0.0, 1.2);
    const double p = Uniform(rng, 0.0, 0.95);
    const double bell = bender::lane::Decay(true, p, 1.0 / (1.0 - p), x);
    EXPECT_TRUE(SameBits(bell, bender::EvaluateDecay({ bender::DecayShape::Bell, p }, x)));
    const double plateau = bender::lane::Decay(false, p, 1.0 / (1.0 - p), x);
    EXPECT_NEAR(plateau, bender::EvaluateDecay({ bender::DecayShape::Plateau, p }, x), 1e-14);
    EXPECT_GE(plateau, 0.0);
    EXPECT_LE(plateau, 1.0);
    if (x >= 1.0)
    {
      EXPECT_EQ(bell, 0.0);
      EXPECT_EQ(plateau, 0.0);
    }
  }
  EXPECT_EQ(bender::lane::Decay(true, 0.5, 2.0, std::numeric_limits<double>::infinity()), 0.0);
}

} // namespace
