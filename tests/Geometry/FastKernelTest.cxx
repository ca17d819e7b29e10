// The interactive kernel (float, vectorised, table-interpolated) against the exact warp, and
// the live twist unwrapping.

#include "FastWarpKernel.h"
#include "GeometryErrors.h"
#include "GeometryTestUtilities.h"
#include "WarpBinding.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using bender::Vec3;

TEST(FastWarpKernel, AgreesWithTheExactWarpWithinOneHundredThousandthOfTheScene)
{
  std::mt19937_64 rng(20261122);
  int warps = 0;
  for (int trial = 0; trial < 60; ++trial)
  {
    bender::WarpSpec spec;
    spec.initial = bendertest::RandomRibbon(rng, 10.0);
    spec.final = bendertest::RandomRibbon(rng, 10.0);
    spec.radius = 4.0;
    spec.decay.shape = trial % 2 ? bender::DecayShape::Bell : bender::DecayShape::Plateau;
    std::unique_ptr<bender::RibbonWarp> warp;
    try
    {
      warp.reset(new bender::RibbonWarp(spec));
    }
    catch (const bender::GeometryError&)
    {
      continue; // e.g. a random pair turning more than 340 degrees
    }
    ++warps;
    const bender::WarpBinding binding(spec, bender::BlendMode::TwoProjections);
    const bender::WarpEvaluator exact(*warp, bender::WarpPrecision::Exact);
    const bender::WarpEvaluator table(*warp, bender::WarpPrecision::Table);
    const Vec3 origin = spec.initial.start.position;
    bender::FastWarpKernel kernel;
    kernel.SetMotion(*table.GetMotionTable(), origin);
    // Points around the initial wire, at s covering both junctions.
    std::vector<float> px, py, pz, s, f;
    std::vector<Vec3> points;
    std::vector<bender::BoundPoint> records;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto& wire = warp->Initial().Wire();
    const double sJ[2] = { wire.JunctionParameter(), warp->Final().Wire().JunctionParameter() };
    for (int i = 0; i < 400; ++i)
    {
      double si = u(rng);
      if (i < 40)
      {
        si = std::clamp(sJ[i % 2] + (u(rng) - 0.5) * 1e-3, 0.0, 1.0);
      }
      const Vec3 p = wire.PointAt(si) + bendertest::RandomUnit(rng) * (3.0 * u(rng));
      bender::BoundPoint rec;
      if (!binding.Bind(p, rec) || rec.lambda0 < 1.0)
      {
        continue;
      }
      points.push_back(p);
      records.push_back(rec);
      px.push_back(static_cast<float>(p.x - origin.x));
      py.push_back(static_cast<float>(p.y - origin.y));
      pz.push_back(static_cast<float>(p.z - origin.z));
      s.push_back(static_cast<float>(rec.s0));
      f.push_back(static_cast<float>(rec.f));
    }
    const std::size_t n = points.size();
    ASSERT_GT(n, 100u);
    std::vector<float> ox(n), oy(n), oz(n);
    kernel.Evaluate({ px.data(), py.data(), pz.data(), s.data(), f.data() },
      { ox.data(), oy.data(), oz.data() },
      0,
      n);
    double scene = 0.0;
    double worstKernel = 0.0, worstTable = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const Vec3 e = exact.Apply(points[i], records[i]);
      scene = std::max(scene, bender::Norm(e - origin) + bender::Norm(points[i] - origin));
      const Vec3 k{ origin.x + ox[i], origin.y + oy[i], origin.z + oz[i] };
      ASSERT_TRUE(bender::IsFinite(k));
      worstKernel = std::max(worstKernel, bender::Distance(e, k));
      worstTable = std::max(worstTable, bender::Distance(e, table.Apply(points[i], records[i])));
    }
    EXPECT_LT(worstKernel, 1e-5 * scene) << "trial " << trial;
    EXPECT_LT(worstTable, 1e-6 * scene) << "trial " << trial;
  }
  EXPECT_GT(warps, 30);
}

TEST(Ribbon, LiveUnwrappingKeepsTheTwistContinuousPastHalfATurn)
{
  // Twist the end of a straight ribbon in steps of 20 degrees through two full turns: the
  // unwrapped total twist follows the rotation without jumping by 2 pi.
  bender::RibbonSpec r;
  r.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  r.end = { { 10, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  double previous = bender::Ribbon(r).Twist();
  const double pi = 3.14159265358979323846;
  for (int step = 1; step <= 36; ++step)
  {
    const double angle = step * 20.0 * pi / 180.0;
    r.end.normal = { 0.0, -std::sin(angle), std::cos(angle) };
    r.extraTurns = bender::Ribbon::UnwrappedExtraTurns(r, previous);
    const double tau = bender::Ribbon(r).Twist();
    EXPECT_NEAR(tau, angle, 1e-9) << "step " << step;
    previous = tau;
  }
  EXPECT_EQ(r.extraTurns, 2); // 720 degrees: the principal twist is 0 again
}

} // namespace
