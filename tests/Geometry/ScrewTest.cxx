// Property tests of the screws between frames and their continuity lift along s (spec 4,
// section 8 items 15-19, the reverseScrews twin and the 340 degree rule).

#include "Screw.h"
#include "GeometryErrors.h"
#include "GeometryTestUtilities.h"
#include "Quaternion.h"
#include "RibbonWarp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
using bender::Cross;
using bender::Distance;
using bender::Dot;
using bender::DualQuaternion;
using bender::Frame;
using bender::Norm;
using bender::Quaternion;
using bender::Vec3;
using bendertest::Pi;

Frame RandomFrame(std::mt19937_64& rng, double scale = 10.0)
{
  Frame f;
  f.origin = bendertest::RandomPoint(rng, scale);
  f.t = bendertest::RandomUnit(rng);
  f.n = bendertest::RandomPerpendicular(rng, f.t);
  f.b = Cross(f.t, f.n);
  return f;
}

// The minimal (w >= 0) quaternion of M' M^T.
Quaternion Relative(const Frame& c, const Frame& cp)
{
  Quaternion q = bender::QuaternionOfFrame(cp) * bender::Conjugate(bender::QuaternionOfFrame(c));
  return q.w < 0 ? -q : q;
}

// Frame c moved by the fraction f of the screw of m: origin by SCREW_F, axes by the
// differences of SCREW_F (a rigid motion maps O + v to O' + R v).
Frame MoveFrame(const DualQuaternion& m, const Frame& c, double f)
{
  Frame o;
  o.origin = bender::ApplyScrewFraction(m, c.origin, f);
  o.t = bender::ApplyScrewFraction(m, c.origin + c.t, f) - o.origin;
  o.n = bender::ApplyScrewFraction(m, c.origin + c.n, f) - o.origin;
  o.b = bender::ApplyScrewFraction(m, c.origin + c.b, f) - o.origin;
  return o;
}

// Random frame pairs, sometimes with a small or near-half-turn relative rotation.
struct FramePair
{
  Frame c, cp;
};
std::vector<FramePair> RandomPairs(std::uint64_t seed, int count)
{
  std::mt19937_64 rng(seed);
  std::vector<FramePair> out;
  for (int i = 0; i < count; ++i)
  {
    FramePair p;
    p.c = RandomFrame(rng);
    const int kind = i % 4;
    if (kind < 2)
    {
      p.cp = RandomFrame(rng);
    }
    else
    {
      // A rotation of a chosen angle about a random axis through a random point.
      const double angle =
        kind == 2 ? bendertest::Uniform(rng, 1e-3, 0.1) : Pi - bendertest::Uniform(rng, 1e-4, 0.1);
      bendertest::Rigid g;
      g.axis = bendertest::RandomUnit(rng);
      g.angle = angle;
      g.t = bendertest::RandomPoint(rng, 10);
      p.cp = { g.Point(p.c.origin), g.Vector(p.c.t), g.Vector(p.c.n), g.Vector(p.c.b) };
    }
    out.push_back(p);
  }
  return out;
}

TEST(Screw, FullScrewMapsTheFrameAndZeroIsTheIdentity)
{
  std::mt19937_64 rng(61);
  for (const FramePair& fp : RandomPairs(62, 4000))
  {
    const Quaternion q = Relative(fp.c, fp.cp);
    for (const Quaternion& qq : { q, -q })
    {
      const DualQuaternion m = bender::MotionBetween(fp.c, fp.cp, qq);
      const Frame moved = MoveFrame(m, fp.c, 1.0);
      EXPECT_LT(Distance(moved.origin, fp.cp.origin), 1e-9 * 10);
      EXPECT_LT(Distance(moved.t, fp.cp.t), 1e-9);
      EXPECT_LT(Distance(moved.n, fp.cp.n), 1e-9);
      EXPECT_LT(Distance(moved.b, fp.cp.b), 1e-9);
      EXPECT_LT(
        Distance(bender::ApplyMotion(m, fp.c.origin + fp.c.n * 2.0), fp.cp.origin + fp.cp.n * 2.0),
        1e-9 * 10);
      const Vec3 p = bendertest::RandomPoint(rng, 20);
      const Vec3 same = bender::ApplyScrewFraction(m, p, 0.0);
      EXPECT_EQ(same.x, p.x);
      EXPECT_EQ(same.y, p.y);
      EXPECT_EQ(same.z, p.z);
      if (qq.w >= 0)
      {
        // The minimal screw moves points by at most f (|d| + pi |P - axis|) ~ 1e-12 * 100.
        EXPECT_LT(Distance(bender::ApplyScrewFraction(m, p, 1e-12), p), 1e-9);
      }
    }
  }
}

TEST(Screw, LiftedScrewsOfRibbonWarpsMapInitialFramesToFinalFrames)
{
  std::mt19937_64 rng(63);
  int built = 0;
  while (built < 150)
  {
    bender::WarpSpec w;
    w.initial = bendertest::RandomRibbon(rng);
    w.final = bendertest::Perturbed(rng, w.initial, 5.0, 1.5);
    w.final.extraTurns = std::uniform_int_distribution<int>(-1, 1)(rng);
    w.reverseScrews = built % 5 == 0;
    try
    {
      const bender::RibbonWarp warp(w);
      ++built;
      for (int k = 0; k <= 50; ++k)
      {
        const double s = k / 50.0;
        const DualQuaternion m = warp.MotionAt(s);
        const Frame c = warp.Initial().FrameAt(s);
        const Frame cp = warp.Final().FrameAt(s);
        const Frame moved = MoveFrame(m, c, 1.0);
        EXPECT_LT(bendertest::MaxDeviation(moved, cp), 1e-9 * 20) << "s=" << s;
        const bender::Screw sc = warp.ScrewAt(s);
        EXPECT_LE(sc.beta, 2 * Pi - 20 * Pi / 180 + 1e-9);
        EXPECT_EQ(sc.flipped, m.real.w < 0);
      }
    }
    catch (const bender::GeometryError&)
    {
    }
  }
}

TEST(Screw, GroupProperty)
{
  std::mt19937_64 rng(64);
  for (const FramePair& fp : RandomPairs(65, 3000))
  {
    const Quaternion q = Relative(fp.c, fp.cp);
    for (const Quaternion& qq : { q, -q })
    {
      const DualQuaternion m = bender::MotionBetween(fp.c, fp.cp, qq);
      const double f1 = bendertest::Uniform(rng, 0, 1);
      const double f2 = bendertest::Uniform(rng, 0, 1);
      const Vec3 p = bendertest::RandomPoint(rng, 20);
      const Vec3 twice = bender::ApplyScrewFraction(m, bender::ApplyScrewFraction(m, p, f1), f2);
      const Vec3 once = bender::ApplyScrewFraction(m, p, f1 + f2);
      EXPECT_LT(Distance(twice, once), 1e-9 * 40) << "f1=" << f1 << " f2=" << f2;
    }
  }
}

TEST(Screw, AxisDistancePreservedAndAxialDisplacement)
{
  std::mt19937_64 rng(66);
  int tested = 0;
  for (const FramePair& fp : RandomPairs(67, 3000))
  {
    const Quaternion q = Relative(fp.c, fp.cp);
    for (const Quaternion& qq : { q, -q })
    {
      const DualQuaternion m = bender::MotionBetween(fp.c, fp.cp, qq);
      const bender::Screw sc = bender::ScrewOf(m);
      if (sc.beta < 1e-2)
      {
        continue; // the axis point is ill-conditioned
      }
      ++tested;
      EXPECT_NEAR(Norm(sc.k), 1.0, 1e-12);
      const double tol = 1e-9 * std::max(10.0, Norm(sc.a));
      for (int k = 0; k < 5; ++k)
      {
        const double f = bendertest::Uniform(rng, 0, 1);
        const Vec3 p = bendertest::RandomPoint(rng, 20);
        const Vec3 pp = bender::ApplyScrewFraction(m, p, f);
        EXPECT_NEAR(bendertest::DistanceToLine(pp, sc.a, sc.k),
          bendertest::DistanceToLine(p, sc.a, sc.k),
          tol);
        EXPECT_NEAR(Dot(pp - p, sc.k), f * sc.d, tol);
        // The angle turned about the axis is f beta (mod 2 pi).
        const Vec3 a = (p - sc.a) - sc.k * Dot(p - sc.a, sc.k);
        const Vec3 b = (pp - sc.a) - sc.k * Dot(pp - sc.a, sc.k);
        if (Norm(a) > 0.1)
        {
          EXPECT_NEAR(
            bendertest::WrapAngle(bender::SignedAngle(a, b, sc.k) - f * sc.beta), 0.0, 1e-8);
        }
      }
    }
  }
  EXPECT_GT(tested, 5000);
}

TEST(Screw, AgreesWithConstructionQAndTheAForm)
{
  std::mt19937_64 rng(68);
  for (const FramePair& fp : RandomPairs(69, 4000))
  {
    const Quaternion q = Relative(fp.c, fp.cp);
    const Vec3 v = q.Vector();
    const double beta = 2.0 * std::atan2(Norm(v), q.w);
    if (beta < 1e-3)
    {
      continue;
    }
    // Construction Q, independently.
    const Vec3 K = v / Norm(v);
    const Vec3 D = fp.cp.origin - fp.c.origin;
    const double d = Dot(K, D);
    const Vec3 A = (fp.c.origin + fp.cp.origin) * 0.5 + Cross(K, D) / (2.0 * std::tan(beta / 2));
    const double scale = std::max(20.0, Norm(A));
    const DualQuaternion m = bender::MotionBetween(fp.c, fp.cp, q);
    const bender::Screw sc = bender::ScrewOf(m);
    EXPECT_NEAR(sc.beta, beta, 1e-9);
    EXPECT_LT(Distance(sc.k, K), 1e-9);
    EXPECT_NEAR(sc.d, d, 1e-9 * scale);
    EXPECT_LT(bendertest::DistanceToLine(A, sc.a, sc.k), 1e-9 * scale);
    EXPECT_FALSE(sc.flipped);
    // The twin: (K, beta, d) -> (-K, 2 pi - beta, -d), same axis line.
    const DualQuaternion tw = bender::MotionBetween(fp.c, fp.cp, -q);
    const bender::Screw st = bender::ScrewOf(tw);
    EXPECT_NEAR(st.beta, 2 * Pi - beta, 1e-9);
    EXPECT_LT(Distance(st.k, -K), 1e-9);
    EXPECT_NEAR(st.d, -d, 1e-9 * scale);
    EXPECT_LT(bendertest::DistanceToLine(A, st.a, st.k), 1e-9 * scale);
    EXPECT_TRUE(st.flipped);
    for (int k = 0; k < 5; ++k)
    {
      const double f = bendertest::Uniform(rng, 0, 1);
      const Vec3 p = bendertest::RandomPoint(rng, 20);
      const Vec3 aForm = A + bender::Rotate(K, f * beta, p - A) + K * (f * d);
      EXPECT_LT(Distance(bender::ApplyScrewFraction(m, p, f), aForm), 1e-9 * scale) << "f=" << f;
      // (-K, 2 pi - beta, -d): the translation f d' K' = f d K is unchanged.
      const Vec3 twinForm = A + bender::Rotate(-K, f * (2 * Pi - beta), p - A) + (-K) * (f * -d);
      EXPECT_LT(Distance(bender::ApplyScrewFraction(tw, p, f), twinForm), 1e-9 * scale)
        << "f=" << f;
      // The fractional motion is rigid with rotation Rot(K, f beta): it moves frames to
      // frames (ScLERP of the frame C).
      const Frame mf = MoveFrame(m, fp.c, f);
      EXPECT_TRUE(bendertest::FrameIsOrthonormalRightHanded(mf, 1e-9));
      EXPECT_LT(Distance(mf.n, bender::Rotate(K, f * beta, fp.c.n)), 1e-9);
      const Vec3 x = fp.c.origin + fp.c.t * 0.3 - fp.c.n * 1.7 + fp.c.b * 2.2;
      EXPECT_LT(Distance(bender::ApplyScrewFraction(m, x, f),
                  mf.origin + mf.t * 0.3 - mf.n * 1.7 + mf.b * 2.2),
        1e-9 * scale);
    }
  }
}

TEST(Screw, PureAndNearPureTranslations)
{
  std::mt19937_64 rng(70);
  for (int i = 0; i < 500; ++i)
  {
    Frame c = RandomFrame(rng);
    Frame cp = c;
    const Vec3 D = bendertest::RandomPoint(rng, 5);
    cp.origin = c.origin + D;
    const DualQuaternion m = bender::MotionBetween(c, cp, Relative(c, cp));
    const bender::Screw sc = bender::ScrewOf(m);
    EXPECT_NEAR(sc.beta, 0.0, 1e-12);
    const Vec3 p = bendertest::RandomPoint(rng, 20);
    const double f = bendertest::Uniform(rng, 0, 1);
    EXPECT_LT(Distance(bender::ApplyScrewFraction(m, p, f), p + D * f), 1e-9 * 20);
    // A tiny rotation is continuous with the pure translation (the A-free evaluation).
    for (double angle : { 1e-12, 1e-9, 1e-6 })
    {
      bendertest::Rigid g;
      g.axis = bendertest::RandomUnit(rng);
      g.angle = angle;
      g.t = D;
      const Frame cq{ g.Point(c.origin), g.Vector(c.t), g.Vector(c.n), g.Vector(c.b) };
      const DualQuaternion mq = bender::MotionBetween(c, cq, Relative(c, cq));
      const Vec3 r = bender::ApplyScrewFraction(mq, p, f);
      EXPECT_TRUE(bender::IsFinite(r));
      EXPECT_LT(Distance(r, p + (cq.origin - c.origin) * f),
        100 * angle * (Norm(p) + Norm(c.origin) + 20) + 1e-9 * 20);
    }
  }
}

// Spec 4.1 Construction Q: "if |v| < eps_rot: pure translation: K = nrm(D), d = |D|, beta = 0".
// Two frames with the same axes and different origins have a relative quaternion whose vector
// part is rounding noise (~1e-17), not exactly zero.
TEST(Screw, ScrewOfANumericallyPureTranslationReportsTheTranslation)
{
  std::mt19937_64 rng(77);
  int wrong = 0;
  for (int i = 0; i < 500; ++i)
  {
    Frame c = RandomFrame(rng);
    Frame cp = c;
    const Vec3 D = bendertest::RandomPoint(rng, 5);
    cp.origin = c.origin + D;
    const bender::Screw sc = bender::ScrewOf(bender::MotionBetween(c, cp, Relative(c, cp)));
    const bool ok = std::abs(sc.d - Norm(D)) < 1e-9 && Distance(sc.k, bender::Normalized(D)) < 1e-9;
    wrong += !ok;
    if (!ok && wrong <= 3)
    {
      ADD_FAILURE() << "pure translation D = (" << D.x << ", " << D.y << ", " << D.z << "): K = ("
                    << sc.k.x << ", " << sc.k.y << ", " << sc.k.z << "), d = " << sc.d
                    << ", beta = " << sc.beta
                    << "; spec 4.1 expects K = nrm(D), d = |D| = " << Norm(D);
    }
  }
  EXPECT_EQ(wrong, 0) << "of 500 numerically pure translations";
}

// --- The continuity lift through RibbonWarp (item 19) ---------------------------------

// A straight ribbon from p0 along dir (length len) with both normals n rotated about dir by
// a0 (start) and a1 (end), moved by `shift` along dir.
bender::RibbonSpec StraightRibbon(const Vec3& p0,
  const Vec3& dir,
  double len,
  const Vec3& n,
  double a0,
  double a1,
  double shift = 0.0)
{
  bender::RibbonSpec r;
  r.start = { p0 + dir * shift, dir, bender::Rotate(dir, a0, n) };
  r.end = { p0 + dir * (len + shift), dir, bender::Rotate(dir, a1, n) };
  return r;
}

TEST(ScrewLift, RotationSweepingThroughHalfATurnStaysContinuous)
{
  std::mt19937_64 rng(71);
  for (int i = 0; i < 30; ++i)
  {
    const Vec3 p0 = bendertest::RandomPoint(rng, 10);
    const Vec3 dir = bendertest::RandomUnit(rng);
    const Vec3 n = bendertest::RandomPerpendicular(rng, dir);
    const double len = bendertest::Uniform(rng, 1, 10);
    const double shift = i % 2 == 0 ? 0.0 : bendertest::Uniform(rng, -3, 3);
    bender::WarpSpec w;
    w.initial = StraightRibbon(p0, dir, len, n, 0.0, 0.0);
    // C'_s = C_s rotated about the wire by 0.9 pi + 0.2 pi s (and moved along it).
    w.final = StraightRibbon(p0, dir, len, n, 0.9 * Pi, 1.1 * Pi, shift);
    w.radius = 1.0;
    const bender::RibbonWarp warp(w);
    ASSERT_NEAR(warp.Final().Twist(), 0.2 * Pi, 1e-12);
    EXPECT_TRUE(warp.FlipOccurred());
    double maxBeta = 0;
    for (int k = 0; k <= 1000; ++k)
    {
      const double s = k / 1000.0;
      const bender::Screw sc = warp.ScrewAt(s);
      EXPECT_NEAR(sc.beta, 0.9 * Pi + 0.2 * Pi * s, 1e-9) << "s=" << s;
      EXPECT_LT(Distance(sc.k, dir), 1e-9) << "s=" << s;
      EXPECT_NEAR(sc.d, shift, 1e-9 * 10) << "s=" << s;
      EXPECT_LT(bendertest::DistanceToLine(sc.a, p0, dir), 1e-9 * 10) << "s=" << s;
      if (s > 0.5 + 1e-6)
      {
        EXPECT_TRUE(sc.flipped) << "s=" << s;
      }
      if (s < 0.5 - 1e-6)
      {
        EXPECT_FALSE(sc.flipped) << "s=" << s;
      }
      maxBeta = std::max(maxBeta, sc.beta);
    }
    EXPECT_GT(maxBeta, Pi + 0.1);
  }
}

TEST(ScrewLift, RotationSweepingThroughZeroIsNotCorrected)
{
  std::mt19937_64 rng(72);
  for (int i = 0; i < 30; ++i)
  {
    const Vec3 p0 = bendertest::RandomPoint(rng, 10);
    const Vec3 dir = bendertest::RandomUnit(rng);
    const Vec3 n = bendertest::RandomPerpendicular(rng, dir);
    const double len = bendertest::Uniform(rng, 1, 10);
    bender::WarpSpec w;
    w.initial = StraightRibbon(p0, dir, len, n, 0.0, 0.0);
    w.final = StraightRibbon(p0, dir, len, n, -0.1, 0.1);
    w.radius = 1.0;
    const bender::RibbonWarp warp(w);
    EXPECT_FALSE(warp.FlipOccurred());
    for (int k = 0; k <= 1000; ++k)
    {
      const double s = k / 1000.0;
      const bender::Screw sc = warp.ScrewAt(s);
      EXPECT_LE(sc.beta, 0.1 + 1e-12) << "s=" << s;
      EXPECT_NEAR(sc.beta, std::abs(-0.1 + 0.2 * s), 1e-9) << "s=" << s;
      EXPECT_FALSE(sc.flipped);
      // The points of a disc about the wire turn by -0.1 + 0.2 s: continuous through 0.
      const Frame c = warp.Initial().FrameAt(s);
      const Vec3 p = c.origin + c.n * 0.5;
      const Vec3 expect = c.origin + bender::Rotate(dir, -0.1 + 0.2 * s, c.n) * 0.5;
      EXPECT_LT(Distance(bender::ApplyMotion(warp.MotionAt(s), p), expect), 1e-9 * 10);
    }
  }
}

TEST(ScrewLift, CurvedRibbonsCrossingHalfATurnStayContinuous)
{
  std::mt19937_64 rng(73);
  int flips = 0, built = 0;
  while (built < 40)
  {
    bender::WarpSpec w;
    w.initial = bendertest::RandomRibbon(rng);
    // Final: the initial ribbon turned rigidly by about 0.9 pi, its end turned a further
    // 0.2 pi about its tangent (so the relative rotation crosses pi along s).
    bendertest::Rigid g = bendertest::RandomRigid(rng, 5.0);
    g.angle = 0.9 * Pi;
    w.final = bendertest::Transformed(w.initial, g);
    w.final.end.normal =
      bender::Rotate(bender::Normalized(w.final.end.tangent), 0.2 * Pi, w.final.end.normal);
    try
    {
      const bender::RibbonWarp warp(w);
      ++built;
      flips += warp.FlipOccurred();
      bender::Screw prev = warp.ScrewAt(0.0);
      EXPECT_NEAR(prev.beta, 0.9 * Pi, 1e-9);
      for (int k = 1; k <= 2000; ++k)
      {
        const double s = k / 2000.0;
        const bender::Screw sc = warp.ScrewAt(s);
        EXPECT_LT(std::abs(sc.beta - prev.beta), 0.01) << "s=" << s;
        EXPECT_LT(Distance(sc.k, prev.k), 0.01) << "s=" << s;
        prev = sc;
      }
    }
    catch (const bender::GeometryError&)
    {
    }
  }
  EXPECT_GT(flips, 5);
}

TEST(ScrewLift, HalfTurnAtTheStartIsDecidedInTheStartFrame)
{
  std::mt19937_64 rng(74);
  int built = 0;
  while (built < 100)
  {
    bender::WarpSpec w;
    w.initial = bendertest::RandomRibbon(rng);
    bendertest::Rigid g = bendertest::RandomRigid(rng, 5.0);
    g.angle = Pi;
    w.final = bendertest::Transformed(w.initial, g);
    w.radius = 1.0;
    try
    {
      const bender::RibbonWarp warp(w);
      ++built;
      const Frame c0 = warp.Initial().FrameAt(0.0);
      const bender::Screw s0 = warp.ScrewAt(0.0);
      EXPECT_NEAR(s0.beta, Pi, 1e-9);
      // The first component of K in C_0's coordinates that exceeds 1e-9 is positive.
      const double comps[3] = { Dot(s0.k, c0.t), Dot(s0.k, c0.n), Dot(s0.k, c0.b) };
      for (double comp : comps)
      {
        if (std::abs(comp) > 1e-6)
        {
          EXPECT_GT(comp, 0.0);
          break;
        }
      }
      EXPECT_LT(Norm(Cross(s0.k, g.axis)), 1e-9);
      // The whole warp is the same rigid half-turn.
      for (int k = 0; k <= 20; ++k)
      {
        const double s = k / 20.0;
        const bender::Screw sc = warp.ScrewAt(s);
        EXPECT_NEAR(sc.beta, Pi, 1e-9) << "s=" << s;
        EXPECT_LT(Distance(sc.k, s0.k), 1e-9) << "s=" << s;
        const Vec3 p = bendertest::RandomPoint(rng, 10);
        EXPECT_LT(Distance(bender::ApplyMotion(warp.MotionAt(s), p), g.Point(p)), 1e-9 * 20);
        // Half of it: a quarter turn about K.
        EXPECT_LT(Distance(bender::ApplyScrewFraction(warp.MotionAt(s), p, 0.5),
                    bender::ApplyScrewFraction(warp.MotionAt(0.0), p, 0.5)),
          1e-9 * 20);
      }
    }
    catch (const bender::GeometryError&)
    {
    }
  }
}

TEST(ScrewLift, ReverseScrewsGivesTheTwin)
{
  std::mt19937_64 rng(75);
  int built = 0;
  while (built < 60)
  {
    bender::WarpSpec w;
    w.initial = bendertest::RandomRibbon(rng);
    bendertest::Rigid g = bendertest::RandomRigid(rng, 5.0);
    g.angle = bendertest::Uniform(rng, 0.4 * Pi, 0.7 * Pi);
    w.final = bendertest::Perturbed(rng, bendertest::Transformed(w.initial, g), 0.5, 0.2);
    w.radius = 1.0;
    bender::WarpSpec wr = w;
    wr.reverseScrews = true;
    try
    {
      const bender::RibbonWarp fwd(w);
      const bender::RibbonWarp rev(wr);
      ++built;
      EXPECT_TRUE(rev.FlipOccurred());
      double differ = 0;
      for (int k = 0; k <= 100; ++k)
      {
        const double s = k / 100.0;
        const bender::Screw a = fwd.ScrewAt(s);
        const bender::Screw b = rev.ScrewAt(s);
        ASSERT_GT(a.beta, 0.1);
        EXPECT_LT(Distance(b.k, -a.k), 1e-9) << "s=" << s;
        EXPECT_NEAR(b.beta, 2 * Pi - a.beta, 1e-9) << "s=" << s;
        EXPECT_NEAR(b.d, -a.d, 1e-9 * 20) << "s=" << s;
        EXPECT_LT(bendertest::DistanceToLine(b.a, a.a, a.k), 1e-9 * std::max(20.0, Norm(a.a)));
        EXPECT_NE(a.flipped, b.flipped);
        // Same motion at f = 1, a different path in between.
        const Vec3 p = bendertest::RandomPoint(rng, 10);
        EXPECT_LT(Distance(bender::ApplyMotion(rev.MotionAt(s), p),
                    bender::ApplyMotion(fwd.MotionAt(s), p)),
          1e-9 * 20);
        differ = std::max(differ,
          Distance(bender::ApplyScrewFraction(rev.MotionAt(s), p, 0.5),
            bender::ApplyScrewFraction(fwd.MotionAt(s), p, 0.5)));
      }
      EXPECT_GT(differ, 0.1);
    }
    catch (const bender::GeometryError&)
    {
    }
  }
}

void ExpectTurnRejected(const bender::WarpSpec& w, const std::string& words)
{
  try
  {
    bender::RibbonWarp warp(w);
    ADD_FAILURE() << "accepted; expected a 340 degree rejection";
  }
  catch (const bender::InvalidWarpError& e)
  {
    EXPECT_NE(std::string(e.what()).find("340"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
  catch (const bender::InvalidRibbonError& e)
  {
    ADD_FAILURE() << "rejected as an invalid ribbon: " << e.what();
  }
  EXPECT_THROW(bender::RibbonWarp::Validate(w), bender::InvalidWarpError);
}

TEST(ScrewLift, ThreeHundredFortyDegreeRule)
{
  std::mt19937_64 rng(76);
  for (int i = 0; i < 50; ++i)
  {
    bender::WarpSpec w;
    w.initial = bendertest::RandomRibbon(rng);
    w.radius = 1.0;
    // One extra turn relative to the grab, either way.
    w.final = w.initial;
    w.final.extraTurns = i % 2 == 0 ? 1 : -1;
    ExpectTurnRejected(w, "grab");
    // reverseScrews on an unchanged ribbon: the twin is a full turn.
    w.final = w.initial;
    w.reverseScrews = true;
    ExpectTurnRejected(w, "grab");
    w.reverseScrews = false;
    EXPECT_NO_THROW(bender::RibbonWarp::Validate(w));
    // A twist of 300 degrees relative to the grab is fine, 350 is not.
    const bender::Ribbon ini(w.initial);
    for (double extra : { 300.0, -300.0, 350.0, -350.0 })
    {
      const double want = ini.Twist() + extra * Pi / 180;
      w.final = w.initial;
      w.final.end.normal = bender::Rotate(
        bender::Normalized(w.initial.end.tangent), extra * Pi / 180, ini.EndNormal());
      const bender::Ribbon principal(w.final);
      w.final.extraTurns =
        static_cast<int>(std::lround((want - principal.PrincipalTwist()) / (2 * Pi)));
      ASSERT_NEAR(bender::Ribbon(w.final).Twist(), want, 1e-9);
      if (std::abs(extra) < 340)
      {
        const bender::RibbonWarp warp(w);
        // The lifted rotation at the end is the whole extra twist.
        EXPECT_NEAR(warp.ScrewAt(1.0).beta, std::abs(extra) * Pi / 180, 1e-6);
      }
      else
      {
        ExpectTurnRejected(w, "twists");
      }
    }
  }
  // A lifted rotation beyond 340 degrees with a twist change well under it: a straight
  // ribbon turned by 170 degrees at its start and 345 at its end (twist change 175).
  const Vec3 x{ 1, 0, 0 }, y{ 0, 1, 0 };
  bender::WarpSpec w;
  w.initial = StraightRibbon({ 0, 0, 0 }, x, 4, y, 0, 0);
  w.final = StraightRibbon({ 0, 0, 0 }, x, 4, y, 170 * Pi / 180, 345 * Pi / 180);
  ExpectTurnRejected(w, "at s = 0.9");
  // 330 degrees at the end is accepted, with beta continuous up to 330.
  w.final = StraightRibbon({ 0, 0, 0 }, x, 4, y, 170 * Pi / 180, 330 * Pi / 180);
  const bender::RibbonWarp ok(w);
  EXPECT_NEAR(ok.ScrewAt(1.0).beta, 330 * Pi / 180, 1e-9);
  EXPECT_NEAR(ok.ScrewAt(0.5).beta, 250 * Pi / 180, 1e-9);
  EXPECT_TRUE(ok.FlipOccurred());
}

} // namespace
