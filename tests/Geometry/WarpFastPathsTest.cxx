// The fast paths of issue 14 against their references: the closed-form frames of RibbonWarp
// against Ribbon::FrameAt, every SIMD level of FastWarpKernel against the exact warp and each
// other, and the exact evaluation's independence of how a range is split (thread counts).

#include "FastWarpKernel.h"
#include "GeometryErrors.h"
#include "GeometryTestUtilities.h"
#include "Screw.h"
#include "WarpBinding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>

namespace
{
using bender::Vec3;

// The relative motion at s built the long way: both frames from Ribbon::FrameAt, their
// quaternions, the sign of `reference`.
bender::DualQuaternion MotionFromFrames(const bender::RibbonWarp& warp,
  double s,
  const bender::Quaternion& reference)
{
  const bender::Frame c = warp.Initial().FrameAt(s);
  const bender::Frame cp = warp.Final().FrameAt(s);
  bender::Quaternion q =
    bender::QuaternionOfFrame(cp) * bender::Conjugate(bender::QuaternionOfFrame(c));
  if (bender::Dot4(q, reference) < 0.0)
  {
    q = -q;
  }
  return bender::MotionBetween(c, cp, q);
}

double QuaternionGap(const bender::Quaternion& a, const bender::Quaternion& b)
{
  return std::max(
    { std::abs(a.w - b.w), std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z) });
}

std::unique_ptr<bender::RibbonWarp> TryWarp(const bender::WarpSpec& spec)
{
  try
  {
    return std::make_unique<bender::RibbonWarp>(spec);
  }
  catch (const bender::GeometryError&)
  {
    return nullptr; // e.g. a random pair turning more than 340 degrees
  }
}

TEST(RibbonWarpClosedForm, MotionsMatchTheFramesOfTheRibbons)
{
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int warps = 0;
  for (int trial = 0; trial < 80; ++trial)
  {
    bender::WarpSpec spec;
    spec.initial = bendertest::RandomRibbon(rng, 10.0);
    spec.final = bendertest::RandomRibbon(rng, 10.0);
    if (trial % 4 == 1)
    {
      // Extra turns on both (the twist change stays below 340 degrees).
      spec.initial.extraTurns = 2;
      spec.final.extraTurns = 2;
    }
    if (trial % 4 == 2)
    {
      // A straight initial wire (line arcs) and a nearly straight final one.
      spec.initial.end.position = spec.initial.start.position + spec.initial.start.tangent * 12.0;
      spec.initial.end.tangent = spec.initial.start.tangent;
      spec.final.end.tangent = bender::Normalized(
        spec.final.end.position - spec.final.start.position + bendertest::RandomUnit(rng) * 1e-7);
      spec.final.start.tangent = spec.final.end.tangent;
      spec.final.start.normal = bendertest::RandomPerpendicular(rng, spec.final.start.tangent);
      spec.final.end.normal = bendertest::RandomPerpendicular(rng, spec.final.end.tangent);
    }
    spec.radius = 4.0;
    const auto warp = TryWarp(spec);
    if (!warp)
    {
      continue;
    }
    ++warps;
    const double sJ[2] = { warp->Initial().Wire().JunctionParameter(),
      warp->Final().Wire().JunctionParameter() };
    for (int i = 0; i < 200; ++i)
    {
      double s = u(rng);
      if (i < 8)
      {
        s = i < 2 ? static_cast<double>(i) : std::clamp(sJ[i % 2] + (i - 5) * 1e-12, 0.0, 1.0);
      }
      const bender::DualQuaternion fast = warp->MotionAt(s);
      const bender::DualQuaternion slow = MotionFromFrames(*warp, s, fast.real);
      EXPECT_LT(QuaternionGap(fast.real, slow.real), 1e-12) << "trial " << trial << " s " << s;
      EXPECT_LT(QuaternionGap(fast.dual, slow.dual), 1e-11) << "trial " << trial << " s " << s;
    }
    // The sign table is the lifted motion at its samples, built the long way too.
    const auto& grid = warp->Grid();
    const auto& table = warp->MotionTable();
    for (std::size_t j = 0; j < table.size(); j += 97)
    {
      const bender::DualQuaternion slow = MotionFromFrames(*warp, grid.s[j], table[j].real);
      EXPECT_LT(QuaternionGap(table[j].real, slow.real), 1e-12) << "trial " << trial;
      EXPECT_LT(QuaternionGap(table[j].dual, slow.dual), 1e-11) << "trial " << trial;
    }
  }
  EXPECT_GT(warps, 40);
}

struct KernelCase
{
  std::unique_ptr<bender::RibbonWarp> warp;
  bender::WarpSpec spec;
  std::vector<float> px, py, pz, s, f;
  std::vector<Vec3> points;
  std::vector<bender::BoundPoint> records;
};

// Points around the initial wire with one projection, as FastWarpLayout lays them out.
bool MakeKernelCase(std::mt19937_64& rng, int trial, KernelCase& c)
{
  c.spec = {};
  c.spec.initial = bendertest::RandomRibbon(rng, 10.0);
  c.spec.final = bendertest::RandomRibbon(rng, 10.0);
  c.spec.radius = 4.0;
  c.spec.decay.shape = trial % 2 ? bender::DecayShape::Bell : bender::DecayShape::Plateau;
  c.warp = TryWarp(c.spec);
  if (!c.warp)
  {
    return false;
  }
  const bender::WarpBinding binding(c.spec, bender::BlendMode::TwoProjections);
  const Vec3 origin = c.spec.initial.start.position;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto& wire = c.warp->Initial().Wire();
  // 1001 candidates: an odd count, so that every level's remainder handling is exercised.
  for (int i = 0; i < 1001; ++i)
  {
    const Vec3 p = wire.PointAt(u(rng)) + bendertest::RandomUnit(rng) * (3.5 * u(rng));
    bender::BoundPoint rec;
    if (!binding.Bind(p, rec) || rec.lambda0 < 1.0)
    {
      continue;
    }
    c.points.push_back(p);
    c.records.push_back(rec);
    c.px.push_back(static_cast<float>(p.x - origin.x));
    c.py.push_back(static_cast<float>(p.y - origin.y));
    c.pz.push_back(static_cast<float>(p.z - origin.z));
    c.s.push_back(static_cast<float>(rec.s0));
    c.f.push_back(static_cast<float>(rec.f));
  }
  return c.points.size() > 100;
}

TEST(FastWarpKernel, EverySimdLevelAgreesWithTheExactWarp)
{
  using Level = bender::FastWarpKernel::SimdLevel;
  EXPECT_TRUE(bender::FastWarpKernel::Supports(Level::Baseline));
  EXPECT_TRUE(bender::FastWarpKernel::Supports(bender::FastWarpKernel::BestLevel()));
  std::mt19937_64 rng(7001);
  int cases = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    KernelCase c;
    if (!MakeKernelCase(rng, trial, c))
    {
      continue;
    }
    ++cases;
    const bender::WarpEvaluator exact(*c.warp, bender::WarpPrecision::Exact);
    const bender::WarpEvaluator table(*c.warp, bender::WarpPrecision::Table);
    const Vec3 origin = c.spec.initial.start.position;
    const std::size_t n = c.points.size();
    double scene = 0.0;
    std::vector<Vec3> reference(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      reference[i] = exact.Apply(c.points[i], c.records[i]);
      scene =
        std::max(scene, bender::Norm(reference[i] - origin) + bender::Norm(c.points[i] - origin));
    }
    std::vector<std::vector<float>> results;
    for (Level level : { Level::Baseline, Level::Avx2, Level::Avx512 })
    {
      bender::FastWarpKernel kernel;
      if (!kernel.SetLevel(level))
      {
        EXPECT_FALSE(bender::FastWarpKernel::Supports(level));
        continue;
      }
      EXPECT_EQ(kernel.Level(), level);
      kernel.SetMotion(*table.GetMotionTable(), origin);
      std::vector<float> ox(n), oy(n), oz(n);
      const bender::FastWarpPoints points{
        c.px.data(), c.py.data(), c.pz.data(), c.s.data(), c.f.data()
      };
      kernel.Evaluate(points, { ox.data(), oy.data(), oz.data() }, 0, n);
      double worst = 0.0;
      for (std::size_t i = 0; i < n; ++i)
      {
        const Vec3 k{ origin.x + ox[i], origin.y + oy[i], origin.z + oz[i] };
        ASSERT_TRUE(bender::IsFinite(k)) << bender::FastWarpKernel::LevelName(level);
        worst = std::max(worst, bender::Distance(reference[i], k));
      }
      EXPECT_LT(worst, 1e-5 * scene)
        << "trial " << trial << ", " << bender::FastWarpKernel::LevelName(level);
      // A range split anywhere gives the same floats: no point depends on its neighbours.
      std::vector<float> sx(n), sy(n), sz(n);
      for (std::size_t b = 0; b < n; b += 37)
      {
        kernel.Evaluate(points, { sx.data(), sy.data(), sz.data() }, b, std::min(n, b + 37));
      }
      EXPECT_EQ(0, std::memcmp(sx.data(), ox.data(), n * sizeof(float)));
      EXPECT_EQ(0, std::memcmp(sz.data(), oz.data(), n * sizeof(float)));
    }
  }
  EXPECT_GT(cases, 20);
}

TEST(FastWarpKernel, OutOfRangeParametersStayInsideTheTable)
{
  // s outside [0, 1] (or NaN) must never read outside the table: results stay finite for
  // finite s and no crash for NaN.
  std::mt19937_64 rng(99);
  KernelCase c;
  int trial = 0;
  while (!MakeKernelCase(rng, trial++, c))
  {
  }
  const bender::WarpEvaluator table(*c.warp, bender::WarpPrecision::Table);
  bender::FastWarpKernel kernel;
  kernel.SetMotion(*table.GetMotionTable(), c.spec.initial.start.position);
  const float s[4] = { -3.0f, 7.0f, 1.0f, std::nanf("") };
  const float p[4] = { 0.5f, 0.5f, 0.5f, 0.5f };
  const float f[4] = { 0.5f, 0.5f, 0.5f, 0.5f };
  float o[3][4];
  kernel.Evaluate({ p, p, p, s, f }, { o[0], o[1], o[2] }, 0, 4);
  for (int k = 0; k < 3; ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      EXPECT_TRUE(std::isfinite(o[d][k])) << "s = " << s[k];
    }
  }
}

TEST(FastWarpLayout, ParallelBuildEqualsTheSerialOne)
{
  // Chunks run in any order and split anywhere must give the serial layout.
  bender::WarpSpec spec;
  spec.initial.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  // A U-turn: points between the legs have two projections.
  spec.initial.end = { { 0, 12, 0 }, { -1, 0, 0 }, { 0, 0, 1 } };
  spec.final = spec.initial;
  spec.final.end.position = { 2, 14, 1 };
  spec.radius = 9.0;
  const bender::WarpBinding binding(spec, bender::BlendMode::TwoProjections);
  std::mt19937_64 rng(5);
  std::vector<float> xyz;
  for (int i = 0; i < 30011; ++i)
  {
    const Vec3 p = bendertest::RandomPoint(rng, 1.0) * 20.0 + Vec3{ 5.0, 6.0, 0.0 };
    xyz.insert(
      xyz.end(), { static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z) });
  }
  const std::size_t n = xyz.size() / 3;
  std::vector<bender::BoundPoint> records(n);
  std::vector<std::uint8_t> bound(n);
  binding.BindRange(xyz.data(), 0, n, records.data(), bound.data());
  bender::FastWarpLayout serial, parallel;
  serial.Build(xyz.data(), n, records.data(), bound.data(), spec.initial.start.position);
  parallel.Build(xyz.data(),
    n,
    records.data(),
    bound.data(),
    spec.initial.start.position,
    [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
    {
      // Backwards, one chunk at a time.
      for (std::size_t c = count; c-- > 0;)
      {
        body(c, c + 1);
      }
    });
  ASSERT_GT(serial.SingleIds().size(), 1000u);
  ASSERT_GT(serial.PairIds().size(), 100u);
  EXPECT_EQ(serial.BoundIds(), parallel.BoundIds());
  EXPECT_EQ(serial.SingleIds(), parallel.SingleIds());
  EXPECT_EQ(serial.PairIds(), parallel.PairIds());
  // And the kernel's results from both layouts are the same floats.
  const auto warp = TryWarp(spec);
  ASSERT_TRUE(warp);
  const bender::WarpEvaluator table(*warp, bender::WarpPrecision::Table);
  bender::FastWarpKernel kernel;
  kernel.SetMotion(*table.GetMotionTable(), serial.Origin());
  std::vector<float> a(xyz), b(xyz);
  serial.EvaluateSingles(kernel, a.data(), 0, serial.SingleIds().size());
  parallel.EvaluateSingles(kernel, b.data(), 0, parallel.SingleIds().size());
  EXPECT_EQ(a, b);
}

TEST(WarpEvaluator, BatchedExactAgreesWithTheSinglePointWarp)
{
  // The batched exact kernel (closed-form frames, polynomial sin/cos/atan2, blocks of lanes)
  // against RibbonWarp's single-point path (MotionAt, ApplyScrewFraction), one and two
  // projections, both decays, extra turns.
  std::mt19937_64 rng(31337);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int cases = 0;
  std::size_t pairs = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    bender::WarpSpec spec;
    spec.initial = bendertest::RandomRibbon(rng, 10.0);
    spec.final = bendertest::RandomRibbon(rng, 10.0);
    if (trial % 3 == 1)
    {
      spec.initial.extraTurns = -1;
      spec.final.extraTurns = -1;
    }
    spec.radius = 6.0;
    spec.decay.shape = trial % 2 ? bender::DecayShape::Bell : bender::DecayShape::Plateau;
    spec.decay.plateau = 0.3;
    const auto warp = TryWarp(spec);
    if (!warp)
    {
      continue;
    }
    ++cases;
    const bender::WarpBinding binding(spec, bender::BlendMode::TwoProjections);
    const bender::WarpEvaluator exact(*warp, bender::WarpPrecision::Exact);
    std::vector<double> xyz;
    for (int i = 0; i < 301; ++i)
    {
      const Vec3 p =
        warp->Initial().Wire().PointAt(u(rng)) + bendertest::RandomUnit(rng) * (6.0 * u(rng));
      xyz.insert(xyz.end(), { p.x, p.y, p.z });
    }
    const std::size_t n = xyz.size() / 3;
    std::vector<bender::BoundPoint> records(n);
    std::vector<std::uint8_t> bound(n);
    binding.BindRange(xyz.data(), 0, n, records.data(), bound.data());
    std::vector<std::int64_t> ids;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (bound[i])
      {
        ids.push_back(static_cast<std::int64_t>(i));
      }
    }
    std::vector<double> out(xyz);
    exact.EvaluateRange(
      bender::WarpBatch<double>{ xyz.data(), out.data(), records.data(), ids.data() },
      0,
      ids.size());
    for (std::int64_t i : ids)
    {
      const bender::BoundPoint& rec = records[i];
      const Vec3 p{ xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
      Vec3 reference = bender::ApplyScrewFraction(warp->MotionAt(rec.s0), p, rec.f);
      if (rec.lambda0 < 1.0)
      {
        ++pairs;
        reference = reference * rec.lambda0 +
          bender::ApplyScrewFraction(warp->MotionAt(rec.s1), p, rec.f) * (1.0 - rec.lambda0);
      }
      const Vec3 got{ out[3 * i], out[3 * i + 1], out[3 * i + 2] };
      // The scene is about 30 mm across.
      EXPECT_LT(bender::Distance(got, reference), 1e-11) << "trial " << trial << " point " << i;
    }
  }
  EXPECT_GT(cases, 20);
  EXPECT_GT(pairs, 10u);
}

TEST(WarpEvaluator, ExactIdentityLeavesPointsBitForBit)
{
  // Where the two ribbons' frames are equal the motion is exactly the identity: the points
  // there must keep their coordinates bit for bit (the commit guard counts a point as moved on
  // any difference). Final = initial everywhere, and a bend whose start is shared (s = 0).
  std::mt19937_64 rng(77);
  for (int trial = 0; trial < 6; ++trial)
  {
    bender::WarpSpec spec;
    spec.initial = bendertest::RandomRibbon(rng, 10.0);
    spec.final = spec.initial;
    spec.radius = 5.0;
    const auto warp = TryWarp(spec);
    ASSERT_TRUE(warp);
    const bender::WarpBinding binding(spec, bender::BlendMode::TwoProjections);
    const bender::WarpEvaluator exact(*warp, bender::WarpPrecision::Exact);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> xyz;
    for (int i = 0; i < 257; ++i)
    {
      const Vec3 p =
        warp->Initial().Wire().PointAt(u(rng)) + bendertest::RandomUnit(rng) * (5.0 * u(rng));
      xyz.insert(xyz.end(), { p.x, p.y, p.z });
    }
    const std::size_t n = xyz.size() / 3;
    std::vector<bender::BoundPoint> records(n);
    std::vector<std::uint8_t> bound(n);
    binding.BindRange(xyz.data(), 0, n, records.data(), bound.data());
    std::vector<std::int64_t> ids;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (bound[i])
      {
        ids.push_back(static_cast<std::int64_t>(i));
      }
    }
    ASSERT_GT(ids.size(), 50u);
    std::vector<double> out(xyz.size(), 0.0);
    exact.EvaluateRange(
      bender::WarpBatch<double>{ xyz.data(), out.data(), records.data(), ids.data() },
      0,
      ids.size());
    for (std::int64_t i : ids)
    {
      for (int d = 0; d < 3; ++d)
      {
        ASSERT_EQ(out[3 * i + d], xyz[3 * i + d]) << "trial " << trial << " point " << i;
      }
    }
  }
}

TEST(WarpEvaluator, ExactResultsDoNotDependOnTheSplitOfTheRange)
{
  // Threads evaluate disjoint ranges; a thread count only changes where ranges split. Every
  // split must give bit-identical points.
  std::mt19937_64 rng(424242);
  int cases = 0;
  for (int trial = 0; trial < 10; ++trial)
  {
    bender::WarpSpec spec;
    spec.initial = bendertest::RandomRibbon(rng, 10.0);
    spec.final = bendertest::RandomRibbon(rng, 10.0);
    spec.radius = 5.0;
    const auto warp = TryWarp(spec);
    if (!warp)
    {
      continue;
    }
    ++cases;
    const bender::WarpBinding binding(spec, bender::BlendMode::TwoProjections);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> xyz;
    for (int i = 0; i < 1003; ++i)
    {
      const Vec3 p =
        warp->Initial().Wire().PointAt(u(rng)) + bendertest::RandomUnit(rng) * (5.0 * u(rng));
      xyz.insert(xyz.end(), { p.x, p.y, p.z });
    }
    const std::size_t n = xyz.size() / 3;
    std::vector<bender::BoundPoint> records(n);
    std::vector<std::uint8_t> bound(n);
    binding.BindRange(xyz.data(), 0, n, records.data(), bound.data());
    std::vector<std::int64_t> ids;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (bound[i])
      {
        ids.push_back(static_cast<std::int64_t>(i));
      }
    }
    ASSERT_GT(ids.size(), 100u);
    const bender::WarpEvaluator exact(*warp, bender::WarpPrecision::Exact);
    std::vector<double> whole(xyz), split(xyz);
    const bender::WarpBatch<double> wholeBatch{
      xyz.data(), whole.data(), records.data(), ids.data()
    };
    exact.EvaluateRange(wholeBatch, 0, ids.size());
    for (std::size_t chunk : { std::size_t(1), std::size_t(3), std::size_t(64), std::size_t(333) })
    {
      std::fill(split.begin(), split.end(), 0.0);
      for (std::size_t b = 0; b < ids.size(); b += chunk)
      {
        exact.EvaluateRange(
          bender::WarpBatch<double>{ xyz.data(), split.data(), records.data(), ids.data() },
          b,
          std::min(ids.size(), b + chunk));
      }
      for (std::int64_t i : ids)
      {
        for (int d = 0; d < 3; ++d)
        {
          ASSERT_EQ(whole[3 * i + d], split[3 * i + d]) << "chunk " << chunk;
        }
      }
    }
    // And each point equals the single-point exact warp.
    for (std::int64_t i : ids)
    {
      const Vec3 p{ xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
      const Vec3 r = exact.Apply(p, records[i]);
      EXPECT_EQ(r.x, whole[3 * i]);
      EXPECT_EQ(r.y, whole[3 * i + 1]);
      EXPECT_EQ(r.z, whole[3 * i + 2]);
    }
  }
  EXPECT_GT(cases, 5);
}

} // namespace
