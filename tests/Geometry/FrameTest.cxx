// Property tests of the ribbon frames and twist (spec 2, section 8 items 8-10).

#include "GeometryErrors.h"
#include "GeometryTestUtilities.h"
#include "Ribbon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
using bender::Cross;
using bender::Distance;
using bender::Dot;
using bender::Frame;
using bender::Norm;
using bender::Ribbon;
using bender::Vec3;
using bendertest::Pi;

// Valid random ribbons whose given tangents are not unit and whose given normals are not
// orthogonal to the tangents (the core normalises them).
std::vector<bender::RibbonSpec> RandomRibbons(std::uint64_t seed, int count)
{
  std::mt19937_64 rng(seed);
  std::vector<bender::RibbonSpec> out;
  while (static_cast<int>(out.size()) < count)
  {
    bender::RibbonSpec r =
      out.size() % 2 == 0 ? bendertest::RandomRibbon(rng) : bendertest::RandomWildRibbon(rng);
    for (bender::RibbonEnd* e : { &r.start, &r.end })
    {
      e->normal =
        e->normal * bendertest::Uniform(rng, 0.2, 5) + e->tangent * bendertest::Uniform(rng, -2, 2);
      e->tangent = e->tangent * bendertest::Uniform(rng, 0.2, 5);
    }
    try
    {
      Ribbon rib(r);
      if (rib.Wire().MinimumRadius() > 1e-3)
      {
        out.push_back(r);
      }
    }
    catch (const bender::InvalidRibbonError&)
    {
    }
  }
  return out;
}

Frame TrackerFrame(const bender::RibbonEnd& e)
{
  Frame f;
  f.origin = e.position;
  f.t = bender::Normalized(e.tangent);
  f.n = bender::Normalized(e.normal - f.t * Dot(e.normal, f.t));
  f.b = Cross(f.t, f.n);
  return f;
}

TEST(Frame, EndFramesAreTheNormalisedTrackerFrames)
{
  for (const auto& r : RandomRibbons(31, 2000))
  {
    const Ribbon rib(r);
    const double h = bendertest::Scale(r);
    const Frame c0 = rib.FrameAt(0.0);
    const Frame c1 = rib.FrameAt(1.0);
    const Frame e0 = TrackerFrame(r.start);
    const Frame e1 = TrackerFrame(r.end);
    EXPECT_LT(Distance(c0.origin, e0.origin), 1e-9 * h);
    EXPECT_LT(Distance(c1.origin, e1.origin), 1e-9 * h);
    EXPECT_LT(Distance(c0.t, e0.t), 1e-9);
    EXPECT_LT(Distance(c0.n, e0.n), 1e-9);
    EXPECT_LT(Distance(c0.b, e0.b), 1e-9);
    EXPECT_LT(Distance(c1.t, e1.t), 1e-9);
    EXPECT_LT(Distance(c1.n, e1.n), 1e-9) << "tau=" << rib.Twist();
    EXPECT_LT(Distance(c1.b, e1.b), 1e-9);
    EXPECT_LT(Distance(rib.StartNormal(), e0.n), 1e-12);
    EXPECT_LT(Distance(rib.EndNormal(), e1.n), 1e-12);
  }
}

TEST(Frame, OrthonormalRightHandedAndOnTheWire)
{
  std::mt19937_64 rng(32);
  for (const auto& r : RandomRibbons(33, 1000))
  {
    const Ribbon rib(r);
    const double h = bendertest::Scale(r);
    for (int k = 0; k < 30; ++k)
    {
      const double s = bendertest::Uniform(rng, 0.0, 1.0);
      const Frame f = rib.FrameAt(s);
      EXPECT_TRUE(bendertest::FrameIsOrthonormalRightHanded(f, 1e-12)) << "s=" << s;
      EXPECT_LT(Distance(f.origin, rib.Wire().PointAt(s)), 1e-12 * h);
      EXPECT_LT(Distance(f.t, rib.Wire().TangentAt(s)), 1e-12);
    }
  }
}

TEST(Frame, ContinuousAtTheJunction)
{
  for (const auto& r : RandomRibbons(34, 2000))
  {
    const Ribbon rib(r);
    const double h = bendertest::Scale(r);
    const double sJ = rib.Wire().JunctionParameter();
    // The two branches agree at J (sJ is computed by branch 1, the next double by branch 2).
    const Frame a = rib.FrameAt(sJ);
    const Frame b = rib.FrameAt(std::nextafter(sJ, 2.0));
    EXPECT_LT(bendertest::MaxDeviation(a, b), 1e-9 * h) << "sJ=" << sJ;
    // Both sides within 1e-9 in s: the frame turns at most |tau| + L / r_min per unit s.
    const double e = 1e-9;
    const double rate = std::abs(rib.Twist()) + rib.Wire().Length() / rib.Wire().MinimumRadius() +
      rib.Wire().Length();
    const Frame lo = rib.FrameAt(std::max(0.0, sJ - e));
    const Frame hi = rib.FrameAt(std::min(1.0, sJ + e));
    EXPECT_LT(bendertest::MaxDeviation(lo, hi), 2.0 * e * rate * 1.01 + 1e-12 * h);
  }
}

TEST(Frame, TwistEquivalence)
{
  int tested = 0;
  for (const auto& r : RandomRibbons(35, 3000))
  {
    const Ribbon rib(r);
    const bender::Biarc& w = rib.Wire();
    if (w.FirstArc().line || w.SecondArc().line || w.FirstArc().angle < 1e-6 ||
      w.SecondArc().angle < 1e-6)
    {
      continue; // the arc-plane normals are undefined or ill-conditioned
    }
    ++tested;
    const Vec3 n1 = w.FirstArc().axis;
    const Vec3 n2 = w.SecondArc().axis;
    const double alpha0 = bender::SignedAngle(rib.StartNormal(), n1, w.StartTangent());
    const double alpha1 = bender::SignedAngle(n2, rib.EndNormal(), w.EndTangent());
    const double e = bender::SignedAngle(n1, n2, w.JunctionTangent());
    EXPECT_NEAR(bendertest::WrapAngle(rib.Twist() - (alpha0 + e + alpha1)), 0.0, 1e-9)
      << "tau=" << rib.Twist() << " alpha0=" << alpha0 << " e=" << e << " alpha1=" << alpha1;
    EXPECT_GT(rib.PrincipalTwist(), -Pi);
    EXPECT_LE(rib.PrincipalTwist(), Pi);
    EXPECT_EQ(rib.Twist(), rib.PrincipalTwist());
  }
  EXPECT_GT(tested, 2900);
}

TEST(Frame, ConstantTwistRateAlongTheBinormal)
{
  std::mt19937_64 rng(36);
  for (const auto& r0 : RandomRibbons(37, 300))
  {
    bender::RibbonSpec r = r0;
    r.extraTurns = std::uniform_int_distribution<int>(-2, 2)(rng);
    const Ribbon rib(r);
    const double sJ = rib.Wire().JunctionParameter();
    const double L = rib.Wire().Length();
    const double rate = std::abs(rib.Twist()) + L / rib.Wire().MinimumRadius();
    if (rate > 100)
    {
      continue; // keep the finite-difference truncation (rate^3 ds^2) negligible
    }
    const double ds = 1e-6;
    for (int k = 0; k < 40; ++k)
    {
      const double s = bendertest::Uniform(rng, 2 * ds, 1 - 2 * ds);
      if (std::abs(s - sJ) < 2 * ds)
      {
        continue;
      }
      const Frame f = rib.FrameAt(s);
      const Vec3 dN = (rib.FrameAt(s + ds).n - rib.FrameAt(s - ds).n) / (2 * ds);
      // dN/ds = (transport: a rotation about the arc axis, which is along T) + tau B.
      EXPECT_NEAR(Dot(dN, f.b), rib.Twist(), 1e-6 * std::max(1.0, rate)) << "s=" << s;
      // dB/ds . N = -tau likewise.
      const Vec3 dB = (rib.FrameAt(s + ds).b - rib.FrameAt(s - ds).b) / (2 * ds);
      EXPECT_NEAR(Dot(dB, f.n), -rib.Twist(), 1e-6 * std::max(1.0, rate)) << "s=" << s;
    }
  }
}

TEST(Frame, ExtraTurnsAddWholeTurnsOfTwist)
{
  std::mt19937_64 rng(38);
  for (const auto& r : RandomRibbons(39, 500))
  {
    const Ribbon base(r);
    for (int turns : { -2, -1, 1, 3 })
    {
      bender::RibbonSpec rt = r;
      rt.extraTurns = turns;
      const Ribbon rib(rt);
      EXPECT_EQ(rib.PrincipalTwist(), base.PrincipalTwist());
      EXPECT_NEAR(rib.Twist(), base.Twist() + 2 * Pi * turns, 1e-12);
      EXPECT_LT(bendertest::MaxDeviation(rib.FrameAt(0.0), base.FrameAt(0.0)), 1e-9);
      EXPECT_LT(bendertest::MaxDeviation(rib.FrameAt(1.0), base.FrameAt(1.0)), 1e-9);
      for (int k = 0; k < 5; ++k)
      {
        const double s = bendertest::Uniform(rng, 0, 1);
        const Frame a = base.FrameAt(s);
        const Frame b = rib.FrameAt(s);
        EXPECT_LT(Distance(a.origin, b.origin), 1e-12 * bendertest::Scale(r));
        EXPECT_LT(Distance(a.t, b.t), 1e-12);
        // Same frame turned about T_s by 2 pi turns s.
        EXPECT_LT(Distance(b.n, bender::Rotate(a.t, 2 * Pi * turns * s, a.n)), 1e-9) << "s=" << s;
      }
    }
  }
}

TEST(Frame, TwistTieRuleAtHalfATurn)
{
  const Vec3 x{ 1, 0, 0 }, y{ 0, 1, 0 }, z{ 0, 0, 1 };
  auto ribbonWithEndNormal = [&](const Vec3& n1)
  {
    bender::RibbonSpec r;
    r.start = { { 0, 0, 0 }, x, y };
    r.end = { { 2, 0, 0 }, x, n1 };
    return Ribbon(r);
  };
  // Exactly and nearly half a turn, from either side: tau = +pi.
  for (double a : { Pi, -Pi, Pi - 1e-10, -Pi + 1e-10, Pi - 5e-10, -Pi + 5e-10 })
  {
    const Ribbon rib = ribbonWithEndNormal(bender::Rotate(x, a, y));
    EXPECT_EQ(rib.PrincipalTwist(), Pi) << "a=" << a;
    // The middle frame is turned by +pi/2: N = z.
    EXPECT_LT(Distance(rib.FrameAt(0.5).n, z), 1e-9) << "a=" << a;
  }
  // Outside the tie band the sign is kept.
  for (double a : { Pi - 1e-8, -Pi + 1e-8, 3.0, -3.0, 0.5, -0.5 })
  {
    const Ribbon rib = ribbonWithEndNormal(bender::Rotate(x, a, y));
    EXPECT_NEAR(rib.PrincipalTwist(), a, 1e-12) << "a=" << a;
  }
  // The tie on a curved ribbon: transport N0 to the end and turn it by (almost) pi.
  std::mt19937_64 rng(40);
  for (const auto& r0 : RandomRibbons(41, 200))
  {
    const Ribbon base(r0);
    const Vec3 n0Star =
      bender::Rotate(base.Wire().EndTangent(), -base.PrincipalTwist(), base.EndNormal());
    for (double a : { -Pi + 2e-10, Pi - 2e-10 })
    {
      bender::RibbonSpec r = r0;
      r.end.normal = bender::Rotate(base.Wire().EndTangent(), a, n0Star);
      const Ribbon rib(r);
      EXPECT_EQ(rib.PrincipalTwist(), Pi);
      EXPECT_NEAR(rib.Twist(), Pi, 0);
    }
  }
}

} // namespace
