// Property tests of the biarc wire (spec 1, section 8 items 1-7) and its rejections
// (normative convention 11).

#include "Biarc.h"
#include "GeometryErrors.h"
#include "GeometryTestUtilities.h"
#include "Ribbon.h"
#include "RibbonWarp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
using bender::Biarc;
using bender::Cross;
using bender::Distance;
using bender::Dot;
using bender::Norm;
using bender::Vec3;
using bendertest::Pi;

Biarc Make(const bender::RibbonSpec& r)
{
  return Biarc::FromEnds(r.start.position, r.start.tangent, r.end.position, r.end.tangent);
}

// Random biarcs: half well-conditioned, half with fully random tangents (the invalid ones
// skipped). Returns the specs that build.
std::vector<bender::RibbonSpec> RandomValidRibbons(std::uint64_t seed, int count)
{
  std::mt19937_64 rng(seed);
  std::vector<bender::RibbonSpec> out;
  while (static_cast<int>(out.size()) < count)
  {
    const bender::RibbonSpec r =
      out.size() % 2 == 0 ? bendertest::RandomRibbon(rng) : bendertest::RandomWildRibbon(rng);
    try
    {
      (void)Make(r);
      out.push_back(r);
    }
    catch (const bender::InvalidRibbonError&)
    {
    }
  }
  return out;
}

TEST(Biarc, EndConditionsAndContinuityAtTheJunction)
{
  for (const auto& r : RandomValidRibbons(11, 2000))
  {
    const Biarc w = Make(r);
    const double h = bendertest::Scale(r);
    const Vec3 t0 = bender::Normalized(r.start.tangent);
    const Vec3 t1 = bender::Normalized(r.end.tangent);
    EXPECT_LT(Distance(w.PointAt(0.0), r.start.position), 1e-9 * h);
    EXPECT_LT(Distance(w.PointAt(1.0), r.end.position), 1e-9 * h);
    EXPECT_LT(Distance(w.TangentAt(0.0), t0), 1e-9);
    EXPECT_LT(Distance(w.TangentAt(1.0), t1), 1e-9);

    // Both branches agree at J, and both sides within 1e-9 in s.
    const double sJ = w.JunctionParameter();
    ASSERT_GE(sJ, 0.0);
    ASSERT_LE(sJ, 1.0);
    const double L = w.Length();
    const double after = std::nextafter(sJ, 2.0);
    EXPECT_LT(Distance(w.PointAt(sJ), w.Junction()), 1e-9 * h);
    EXPECT_LT(Distance(w.PointAt(after), w.Junction()), 1e-9 * h);
    EXPECT_LT(Distance(w.TangentAt(sJ), w.JunctionTangent()), 1e-9);
    EXPECT_LT(Distance(w.TangentAt(after), w.JunctionTangent()), 1e-9);
    const double e = 1e-9;
    const double lo = std::max(0.0, sJ - e);
    const double hi = std::min(1.0, sJ + e);
    EXPECT_LT(Distance(w.PointAt(lo), w.PointAt(hi)), 2.0 * e * L * (1 + 1e-6) + 1e-12 * h);
    const double kappa = 1.0 / w.MinimumRadius();
    EXPECT_LT(Distance(w.TangentAt(lo), w.TangentAt(hi)), 2.0 * e * L * kappa * 1.01 + 1e-12);
  }
}

TEST(Biarc, TangentLengthRootAndTurningAngles)
{
  for (const auto& r : RandomValidRibbons(12, 3000))
  {
    const Biarc w = Make(r);
    const double h = bendertest::Scale(r);
    if (w.IsSemicircles())
    {
      continue;
    }
    const double a = w.TangentLength();
    ASSERT_GT(a, 0.0);
    const Vec3 t0 = w.StartTangent(), t1 = w.EndTangent();
    const Vec3 i0 = w.Start() + t0 * a;
    const Vec3 i1 = w.End() - t1 * a;
    EXPECT_NEAR(Distance(i1, i0), 2.0 * a, 1e-9 * std::max(h, a));
    EXPECT_LT(Distance(w.Junction(), (i0 + i1) * 0.5), 1e-9 * std::max(h, a));
    for (int i = 0; i < 2; ++i)
    {
      const bender::Arc& arc = w.GetArc(i);
      EXPECT_GE(arc.angle, 0.0);
      EXPECT_LE(arc.angle, Pi);
      // Chord check: |Ps - end| = 2 a cos(theta/2).
      const Vec3 end = i == 0 ? w.Junction() : w.End();
      EXPECT_NEAR(
        Distance(arc.start, end), 2.0 * a * std::cos(0.5 * arc.angle), 1e-9 * std::max(h, a));
    }
    // Turning angles: arc 1 from T0 to U, arc 2 from U to T1.
    EXPECT_NEAR(
      w.FirstArc().angle, std::acos(std::clamp(Dot(t0, w.JunctionTangent()), -1.0, 1.0)), 1e-6);
    EXPECT_NEAR(
      w.SecondArc().angle, std::acos(std::clamp(Dot(w.JunctionTangent(), t1), -1.0, 1.0)), 1e-6);
  }
}

TEST(Biarc, PointsLieOnTheirCirclesWithPerpendicularTangents)
{
  for (const auto& r : RandomValidRibbons(13, 1000))
  {
    const Biarc w = Make(r);
    const double h = bendertest::Scale(r);
    const double sJ = w.JunctionParameter();
    for (int k = 0; k <= 50; ++k)
    {
      const double s = k / 50.0;
      const int i = s <= sJ ? 0 : 1;
      const bender::Arc& arc = w.GetArc(i);
      if (arc.line)
      {
        continue;
      }
      const Vec3 x = w.PointAt(s);
      const double tol = 1e-9 * std::max(h, arc.radius);
      EXPECT_NEAR(Distance(x, arc.centre), arc.radius, tol) << "s=" << s;
      EXPECT_NEAR(Dot(w.TangentAt(s), x - arc.centre), 0.0, tol) << "s=" << s;
      // In the arc's plane.
      EXPECT_NEAR(Dot(x - arc.centre, arc.axis), 0.0, tol);
      EXPECT_NEAR(Norm(w.TangentAt(s)), 1.0, 1e-12);
    }
  }
}

TEST(Biarc, SpeedByCentralDifferencesEqualsTheLength)
{
  const auto ribbons = RandomValidRibbons(14, 60);
  int tested = 0;
  for (const auto& r : ribbons)
  {
    const Biarc w = Make(r);
    const double L = w.Length();
    if (L / w.MinimumRadius() > 1e3)
    {
      continue; // finite differences would need a finer step
    }
    ++tested;
    const double ds = 1e-6;
    double worst = 0.0;
    for (int k = 0; k < 10000; ++k)
    {
      const double s = ds + (1.0 - 2.0 * ds) * k / 9999.0;
      const double speed = Distance(w.PointAt(s + ds), w.PointAt(s - ds)) / (2.0 * ds);
      worst = std::max(worst, std::abs(speed - L) / L);
    }
    EXPECT_LT(worst, 1e-6) << "L=" << L;
  }
  EXPECT_GT(tested, 40);
}

TEST(Biarc, ReversalGivesTheSamePointSetWithReversedParameter)
{
  for (const auto& r : RandomValidRibbons(15, 1000))
  {
    const Biarc w = Make(r);
    const Biarc rev =
      Biarc::FromEnds(r.end.position, -r.end.tangent, r.start.position, -r.start.tangent);
    const double h = bendertest::Scale(r);
    EXPECT_NEAR(rev.JunctionParameter(), 1.0 - w.JunctionParameter(), 1e-9);
    EXPECT_NEAR(rev.Length(), w.Length(), 1e-9 * h);
    EXPECT_LT(Distance(rev.Junction(), w.Junction()), 1e-9 * h);
    for (int k = 0; k <= 40; ++k)
    {
      const double s = k / 40.0;
      EXPECT_LT(Distance(rev.PointAt(1.0 - s), w.PointAt(s)), 1e-9 * h) << "s=" << s;
      EXPECT_LT(Distance(rev.TangentAt(1.0 - s), -w.TangentAt(s)), 1e-9) << "s=" << s;
    }
  }
}

TEST(Biarc, StraightSegment)
{
  std::mt19937_64 rng(16);
  for (int i = 0; i < 200; ++i)
  {
    const Vec3 p0 = bendertest::RandomPoint(rng, 10);
    // Axis-aligned directions make S exactly parallel to T: both arcs are exact lines.
    // Random directions are parallel only up to rounding: then the arcs are nearly straight
    // (theta of the order of 1e-16), which the spec treats continuously.
    const bool exact = i % 2 == 0;
    Vec3 dir = bendertest::RandomUnit(rng);
    if (exact)
    {
      dir = i % 6 == 0 ? Vec3{ 1, 0, 0 } : (i % 6 == 2 ? Vec3{ 0, -1, 0 } : Vec3{ 0, 0, 1 });
    }
    const Vec3 p1 = p0 + dir * bendertest::Uniform(rng, 0.1, 20);
    const Vec3 t = exact ? dir : bender::Normalized(p1 - p0);
    const Biarc w = Biarc::FromEnds(p0, t, p1, t * 3.0);
    const double h = std::max({ 1.0, Norm(p0), Norm(p1) });
    if (exact)
    {
      EXPECT_TRUE(w.FirstArc().line);
      EXPECT_TRUE(w.SecondArc().line);
      EXPECT_TRUE(std::isinf(w.MinimumRadius()));
    }
    else
    {
      EXPECT_GT(w.MinimumRadius(), 1e6 * Distance(p0, p1));
    }
    EXPECT_NEAR(w.TangentLength(), Distance(p0, p1) / 4.0, 1e-12 * h);
    EXPECT_NEAR(w.Length(), Distance(p0, p1), 1e-12 * h);
    EXPECT_NEAR(w.JunctionParameter(), 0.5, 1e-12);
    for (int k = 0; k <= 20; ++k)
    {
      const double s = k / 20.0;
      EXPECT_LT(Distance(w.PointAt(s), p0 + (p1 - p0) * s), 1e-12 * h);
      EXPECT_LT(Distance(w.TangentAt(s), t), 1e-12);
    }
  }
}

// An arc whose end tangent equals its start tangent to the last bit (a wire along a random
// direction, the tangent repeated: its squared norm is 1 only up to rounding) turns by
// exactly 0: it must be flagged a line with its tangent and length, never a circle of
// infinite radius whose "normal" is the tangent itself.
TEST(Biarc, ArcsThatTurnByZeroAreLines)
{
  std::mt19937_64 rng(20261124);
  int zeroTurns = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const Vec3 p0 = bendertest::RandomUnit(rng) * bendertest::Uniform(rng, 0.0, 50.0);
    const Vec3 t = bendertest::RandomUnit(rng);
    const double len = bendertest::Uniform(rng, 0.1, 20.0);
    const Vec3 p1 = p0 + t * len;
    const Biarc w = Biarc::FromEnds(p0, t, p1, t);
    const double h = std::max({ 1.0, Norm(p0), Norm(p1) });
    for (int k = 0; k < 2; ++k)
    {
      const bender::Arc& arc = w.GetArc(k);
      if (arc.angle == 0.0)
      {
        ++zeroTurns;
        EXPECT_TRUE(arc.line) << "wire " << i << " arc " << k;
      }
      if (arc.line)
      {
        EXPECT_EQ(arc.angle, 0.0);
        EXPECT_TRUE(std::isinf(arc.radius));
        EXPECT_NEAR(Norm(arc.tangent), 1.0, 1e-15);
        EXPECT_NEAR(arc.length, 2.0 * w.TangentLength(), 1e-12 * h);
        EXPECT_LT(Distance(arc.PointAt(1.0), k == 0 ? w.Junction() : w.End()), 1e-12 * h);
      }
      else
      {
        // An arc: a positive turn, a finite radius and a unit normal (for a turn of the order
        // of 1e-16 its direction is rounding noise, which the points never see: spec 1.2).
        EXPECT_GT(arc.angle, 0.0);
        EXPECT_TRUE(std::isfinite(arc.radius));
        EXPECT_NEAR(Norm(arc.toCentre), 1.0, 1e-12);
        EXPECT_LT(Distance(arc.PointAt(1.0), k == 0 ? w.Junction() : w.End()), 1e-12 * h);
      }
    }
    EXPECT_NEAR(w.Length(), len, 1e-12 * h);
  }
  // The scan must reach the case it is about (about a third of random directions do).
  EXPECT_GT(zeroTurns, 0);
}

TEST(Biarc, TwoSemicircles)
{
  std::mt19937_64 rng(17);
  for (int i = 0; i < 200; ++i)
  {
    // Exact inputs: T0 = T1 = x, S = (0, y, z) exactly perpendicular, then an exact
    // permutation of the axes and a translation.
    const Vec3 p0 = bendertest::RandomPoint(rng, 10);
    const Vec3 S{ 0.0, bendertest::Uniform(rng, -5, 5), bendertest::Uniform(rng, -5, 5) };
    const Vec3 t{ bendertest::Uniform(rng, 0.5, 2), 0.0, 0.0 };
    const Vec3 p1 = p0 + S;
    const Vec3 s = p1 - p0; // the S the biarc sees
    if (Norm(s) < 0.1)
    {
      continue;
    }
    const Biarc w = Biarc::FromEnds(p0, t, p1, t);
    const double h = std::max({ 1.0, Norm(p0), Norm(p1) });
    ASSERT_TRUE(w.IsSemicircles());
    const double r = Norm(s) / 4.0;
    const Vec3 x{ 1, 0, 0 };
    EXPECT_LT(Distance(w.Junction(), (p0 + p1) * 0.5), 1e-12 * h);
    EXPECT_LT(Distance(w.JunctionTangent(), -x), 1e-15);
    for (int k = 0; k < 2; ++k)
    {
      EXPECT_NEAR(w.GetArc(k).radius, r, 1e-12 * h);
      EXPECT_NEAR(w.GetArc(k).angle, Pi, 1e-15);
    }
    EXPECT_LT(Distance(w.FirstArc().centre, p0 + s / 4.0), 1e-12 * h);
    EXPECT_LT(Distance(w.SecondArc().centre, p1 - s / 4.0), 1e-12 * h);
    EXPECT_LT(Distance(w.SecondArc().axis, -w.FirstArc().axis), 1e-12);
    EXPECT_NEAR(w.Length(), 2.0 * Pi * r, 1e-12 * h);
    EXPECT_NEAR(w.JunctionParameter(), 0.5, 1e-12);
    for (int k = 0; k <= 20; ++k)
    {
      const double u = k / 20.0;
      const bender::Arc& arc = w.GetArc(u <= 0.5 ? 0 : 1);
      EXPECT_NEAR(Distance(w.PointAt(u), arc.centre), r, 1e-9 * h);
    }
    // It is the limit of the general case along T0 = T1 with P1 slightly ahead
    // (b = 2 delta > 0, a = |S|^2 / (4 b) -> infinity).
    for (double delta : { 1e-4, 1e-6 })
    {
      const double dl = delta * Norm(s);
      const Biarc near = Biarc::FromEnds(p0, t, p1 + x * dl, t);
      EXPECT_FALSE(near.IsSemicircles());
      EXPECT_LT(Distance(near.Junction(), w.Junction()), 10 * dl + 1e-9 * h);
      EXPECT_NEAR(near.Length(), w.Length(), 10 * dl + 1e-9 * h);
      EXPECT_NEAR(near.MinimumRadius(), r, 10 * dl + 1e-9 * h);
      for (int q = 0; q <= 10; ++q)
      {
        EXPECT_LT(Distance(near.PointAt(q / 10.0), w.PointAt(q / 10.0)), 10 * dl + 1e-9 * h);
      }
    }
  }
}

TEST(Biarc, UTurnExample)
{
  const Vec3 x{ 1, 0, 0 };
  const Biarc w = Biarc::FromEnds({ 0, 0, 0 }, x, { 0, 2, 0 }, -x);
  EXPECT_NEAR(w.TangentLength(), 1.0, 1e-12);
  EXPECT_NEAR(w.FirstArc().angle, Pi / 2, 1e-12);
  EXPECT_NEAR(w.SecondArc().angle, Pi / 2, 1e-12);
  EXPECT_NEAR(w.FirstArc().radius, 1.0, 1e-12);
  EXPECT_NEAR(w.SecondArc().radius, 1.0, 1e-12);
  EXPECT_LT(Distance(w.Junction(), Vec3{ 1, 1, 0 }), 1e-12);
  EXPECT_LT(Distance(w.JunctionTangent(), Vec3{ 0, 1, 0 }), 1e-12);
  EXPECT_LT(Distance(w.FirstArc().centre, Vec3{ 0, 1, 0 }), 1e-12);
  EXPECT_LT(Distance(w.SecondArc().centre, Vec3{ 0, 1, 0 }), 1e-12);
  EXPECT_NEAR(w.Length(), Pi, 1e-12);
  EXPECT_NEAR(w.JunctionParameter(), 0.5, 1e-12);
}

TEST(Biarc, CoplanarSymmetricTangentsGiveOneCircle)
{
  std::mt19937_64 rng(18);
  for (int i = 0; i < 500; ++i)
  {
    const double alpha = bendertest::Uniform(rng, -3.0, 3.0);
    const double dist = bendertest::Uniform(rng, 0.2, 10);
    const bendertest::Rigid g = bendertest::RandomRigid(rng);
    const Vec3 p0 = g.Point({ -dist / 2, 0, 0 });
    const Vec3 p1 = g.Point({ dist / 2, 0, 0 });
    const Vec3 t0 = g.Vector({ std::cos(alpha), std::sin(alpha), 0 });
    const Vec3 t1 = g.Vector({ std::cos(alpha), -std::sin(alpha), 0 });
    const Biarc w = Biarc::FromEnds(p0, t0, p1, t1);
    const double h = std::max({ 1.0, Norm(p0), Norm(p1) });
    const double rr = w.FirstArc().radius;
    const double tol = 1e-9 * std::max(h, rr);
    EXPECT_LT(Distance(w.FirstArc().centre, w.SecondArc().centre), tol) << "alpha=" << alpha;
    EXPECT_NEAR(w.FirstArc().radius, w.SecondArc().radius, tol);
    EXPECT_LT(Distance(w.FirstArc().axis, w.SecondArc().axis), 1e-9);
    EXPECT_NEAR(w.JunctionParameter(), 0.5, 1e-9);
    EXPECT_NEAR(w.FirstArc().angle, std::abs(alpha), 1e-9);
    // J is the midpoint of the single arc: on the perpendicular bisector of P0P1.
    EXPECT_NEAR(Dot(w.Junction() - (p0 + p1) * 0.5, p1 - p0), 0.0, 1e-9 * h * h);
    // The twist's dihedral e = sang(n1, n2, U) is 0.
    EXPECT_NEAR(
      bender::SignedAngle(w.FirstArc().axis, w.SecondArc().axis, w.JunctionTangent()), 0.0, 1e-9);
  }
}

TEST(Biarc, RigidMotionAndScaleInvariance)
{
  std::mt19937_64 rng(19);
  const auto ribbons = RandomValidRibbons(20, 1000);
  for (const auto& r : ribbons)
  {
    const bendertest::Rigid g = bendertest::RandomRigid(rng);
    const bender::RibbonSpec gr = bendertest::Transformed(r, g);
    const Biarc w = Make(r);
    const Biarc gw = Make(gr);
    const double h = std::max(bendertest::Scale(r), bendertest::Scale(gr));
    EXPECT_NEAR(gw.TangentLength(), w.TangentLength(), 1e-9 * std::max(h, w.TangentLength()));
    EXPECT_NEAR(gw.JunctionParameter(), w.JunctionParameter(), 1e-9);
    EXPECT_NEAR(gw.Length(), w.Length(), 1e-9 * h);
    EXPECT_LT(Distance(gw.Junction(), g.Point(w.Junction())), 1e-9 * h);
    EXPECT_LT(Distance(gw.JunctionTangent(), g.Vector(w.JunctionTangent())), 1e-9);
    for (int i = 0; i < 2; ++i)
    {
      const bender::Arc& a = w.GetArc(i);
      const bender::Arc& ga = gw.GetArc(i);
      EXPECT_NEAR(ga.angle, a.angle, 1e-9);
      if (!a.line && a.radius < 1e6)
      {
        EXPECT_NEAR(ga.radius, a.radius, 1e-9 * std::max(h, a.radius));
        EXPECT_LT(Distance(ga.centre, g.Point(a.centre)), 1e-9 * std::max(h, a.radius));
        EXPECT_LT(Distance(ga.axis, g.Vector(a.axis)), 1e-9);
      }
    }
    for (int k = 0; k <= 10; ++k)
    {
      const double s = k / 10.0;
      EXPECT_LT(Distance(gw.PointAt(s), g.Point(w.PointAt(s))), 1e-9 * h);
    }
    // Frames move with G.
    const bender::Ribbon rib(r);
    const bender::Ribbon grib(gr);
    for (int k = 0; k <= 10; ++k)
    {
      const double s = k / 10.0;
      const bender::Frame f = rib.FrameAt(s);
      const bender::Frame gf = grib.FrameAt(s);
      EXPECT_LT(Distance(gf.origin, g.Point(f.origin)), 1e-9 * h);
      EXPECT_LT(Distance(gf.t, g.Vector(f.t)), 1e-9);
      EXPECT_LT(Distance(gf.n, g.Vector(f.n)), 1e-9);
      EXPECT_LT(Distance(gf.b, g.Vector(f.b)), 1e-9);
    }
    // Scale by lambda.
    const double lambda = bendertest::Uniform(rng, 0.01, 100);
    bender::RibbonSpec sr = r;
    sr.start.position = r.start.position * lambda;
    sr.end.position = r.end.position * lambda;
    const Biarc sw = Make(sr);
    const double sh = bendertest::Scale(sr);
    EXPECT_NEAR(sw.TangentLength(),
      lambda * w.TangentLength(),
      1e-9 * std::max(sh, lambda * w.TangentLength()));
    EXPECT_NEAR(sw.Length(), lambda * w.Length(), 1e-9 * sh);
    EXPECT_NEAR(sw.JunctionParameter(), w.JunctionParameter(), 1e-9);
    if (w.MinimumRadius() < 1e6)
    {
      EXPECT_NEAR(sw.MinimumRadius(),
        lambda * w.MinimumRadius(),
        1e-9 * std::max(sh, lambda * w.MinimumRadius()));
    }
    for (int k = 0; k <= 10; ++k)
    {
      const double s = k / 10.0;
      EXPECT_LT(Distance(sw.PointAt(s), w.PointAt(s) * lambda), 1e-9 * sh);
    }
  }
}

// --- Rejections (convention 11) --------------------------------------------------------

// Expects FromEnds to throw InvalidRibbonError (the wire as a whole: empty field) whose
// message contains `words`.
void ExpectRejected(const Vec3& p0,
  const Vec3& t0,
  const Vec3& p1,
  const Vec3& t1,
  const std::string& words)
{
  try
  {
    (void)Biarc::FromEnds(p0, t0, p1, t1);
    ADD_FAILURE() << "accepted; expected a rejection mentioning '" << words << "'";
  }
  catch (const bender::InvalidWarpError& e)
  {
    ADD_FAILURE() << "a ribbon problem reported as an InvalidWarpError: " << e.what();
  }
  catch (const bender::InvalidRibbonError& e)
  {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(e.field(), "");
    EXPECT_FALSE(e.problem().empty());
  }
}

TEST(BiarcRejection, NonFiniteInput)
{
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const Vec3 x{ 1, 0, 0 };
  ExpectRejected({ nan, 0, 0 }, x, { 1, 0, 0 }, x, "non-finite");
  ExpectRejected({ 0, 0, 0 }, x, { 1, inf, 0 }, x, "non-finite");
  ExpectRejected({ 0, 0, 0 }, { 1, nan, 0 }, { 1, 0, 0 }, x, "non-finite");
  ExpectRejected({ 0, 0, 0 }, x, { 1, 0, 0 }, { -inf, 0, 0 }, "non-finite");
}

TEST(BiarcRejection, CoincidentEnds)
{
  const Vec3 x{ 1, 0, 0 }, y{ 0, 1, 0 };
  ExpectRejected({ 1, 2, 3 }, x, { 1, 2, 3 }, y, "coincident");
  ExpectRejected({ 1, 2, 3 }, x, { 1, 2, 3 + 1e-12 }, y, "coincident");
  // Tolerance relative to h = max(1, |P0|, |P1|): 1e-9 h.
  ExpectRejected({ 1e6, 0, 0 }, x, { 1e6, 1e-4, 0 }, y, "coincident");
  EXPECT_NO_THROW((void)Biarc::FromEnds({ 0, 0, 0 }, x, { 0, 1e-6, 0 }, x));
}

TEST(BiarcRejection, Cusps)
{
  const Vec3 x{ 1, 0, 0 };
  // T0 = -T1 with S parallel to T0: J = P1 (or P0), an arc of zero length turning by pi.
  ExpectRejected({ 0, 0, 0 }, x, { 2, 0, 0 }, -x, "cusp");
  ExpectRejected({ 0, 0, 0 }, x, { -2, 0, 0 }, -x, "cusp");
  // More generally S parallel to T0 - T1 (J = P1) or to T1 - T0 (J = P0).
  const Vec3 t0 = bender::Normalized(Vec3{ 1, 1, 0 });
  const Vec3 t1 = bender::Normalized(Vec3{ -1, 1, 0 });
  ExpectRejected({ 0, 0, 0 }, t0, { 2, 0, 0 }, t1, "cusp");
  ExpectRejected({ 0, 0, 0 }, t0, { -2, 0, 0 }, t1, "cusp");
  // Random rigid copies.
  std::mt19937_64 rng(21);
  for (int i = 0; i < 50; ++i)
  {
    const bendertest::Rigid g = bendertest::RandomRigid(rng, 3.0);
    ExpectRejected(g.Point({ 0, 0, 0 }), g.Vector(x), g.Point({ 2, 0, 0 }), g.Vector(-x), "cusp");
  }
  // A near-cusp stays valid, with a tiny r_min.
  const Biarc near = Biarc::FromEnds({ 0, 0, 0 }, x, { 2, 0.01, 0 }, -x);
  EXPECT_LT(near.MinimumRadius(), 0.05);
}

TEST(BiarcRejection, NoPositiveRoot)
{
  const Vec3 x{ 1, 0, 0 };
  ExpectRejected({ 0, 0, 0 }, x, { -1, 0.3, 0 }, x, "no biarc");
  ExpectRejected({ 0, 0, 0 }, x, { -1, 0, 0 }, x, "no biarc");
  ExpectRejected({ 0, 0, 0 }, x * 2.0, { -0.5, 1, -1 }, x * 0.5, "no biarc");
}

TEST(BiarcRejection, UnstableNearParallelCase)
{
  const Vec3 x{ 1, 0, 0 }, z{ 0, 0, 1 };
  // Spec 1.3: T1 = T0 rotated by 1e-2 rad, P1 = P0 + (-1, 1, 0): L ~ 624 > 200 |S|.
  ExpectRejected({ 0, 0, 0 }, x, { -1, 1, 0 }, bender::Rotate(z, 1e-2, x), "unstable");
  ExpectRejected({ 0, 0, 0 }, x, { -1, 1, 0 }, bender::Rotate(z, -1e-2, x), "unstable");
  ExpectRejected({ 5, 5, 5 },
    x,
    { 4, 6, 5 },
    bender::Rotate(bender::Normalized(Vec3{ 1, 1, 1 }), 1e-3, x),
    "unstable");
  // Message reports the ratio.
  try
  {
    (void)Biarc::FromEnds({ 0, 0, 0 }, x, { -1, 1, 0 }, bender::Rotate(z, 1e-2, x));
  }
  catch (const bender::InvalidRibbonError& e)
  {
    EXPECT_NE(std::string(e.what()).find("times longer"), std::string::npos) << e.what();
  }
}

TEST(BiarcRejection, NearSemicirclesAndNearlyClosedCirclesAreAccepted)
{
  const Vec3 x{ 1, 0, 0 }, y{ 0, 1, 0 }, z{ 0, 0, 1 };
  for (double eps : { 1e-3, -1e-3, 1e-6, -1e-6, 1e-9, -1e-9 })
  {
    // T1 rotated about S (b = 0, a huge) and about the arcs' axis (b of either sign).
    for (const Vec3& k : { y, z })
    {
      Biarc w;
      ASSERT_NO_THROW(w = Biarc::FromEnds({ 0, 0, 0 }, x, { 0, 1, 0 }, bender::Rotate(k, eps, x)))
        << "eps=" << eps;
      // Short wires with radii of the order of |S| (the exact shape depends on the direction
      // of the perturbation: the biarc is discontinuous at the two-semicircle configuration).
      EXPECT_LT(w.Length(), 5.0);
      EXPECT_GT(w.MinimumRadius(), 0.1);
      if (std::abs(eps) >= 1e-6)
      {
        EXPECT_GT(w.TangentLength(), 50.0); // a test on a alone would reject these
      }
    }
  }
  // Along T0 = T1 with P1 slightly ahead the wire tends to the two semicircles: L ~ pi |S| / 2.
  for (double delta : { 1e-3, 1e-6, 1e-8 })
  {
    Biarc w;
    ASSERT_NO_THROW(w = Biarc::FromEnds({ 0, 0, 0 }, x, { delta, 1, 0 }, x));
    EXPECT_NEAR(w.Length(), Pi / 2, 10 * delta);
    EXPECT_GT(w.TangentLength(), 50.0);
  }
  // Nearly closed circle of radius rho with a 0.05 rad gap (paper Fig. 8): L ~ 125 |S|.
  for (double rho : { 1.0, 7.5 })
  {
    const double g = 0.05;
    const Vec3 p0{ rho * std::cos(g / 2), rho * std::sin(g / 2), 0 };
    const Vec3 t0{ -std::sin(g / 2), std::cos(g / 2), 0 };
    const Vec3 p1{ rho * std::cos(-g / 2), rho * std::sin(-g / 2), 0 };
    const Vec3 t1{ -std::sin(-g / 2), std::cos(-g / 2), 0 };
    Biarc w;
    ASSERT_NO_THROW(w = Biarc::FromEnds(p0, t0, p1, t1));
    EXPECT_NEAR(w.Length(), rho * (2 * Pi - g), 1e-9 * rho);
    EXPECT_GT(w.Length() / Distance(p0, p1), 120.0);
    EXPECT_NEAR(w.MinimumRadius(), rho, 1e-9 * rho);
    EXPECT_LT(Distance(w.FirstArc().centre, Vec3{}), 1e-9 * rho);
    EXPECT_LT(Distance(w.Junction(), Vec3{ -rho, 0, 0 }), 1e-9 * rho);
  }
}

TEST(BiarcRejection, RibbonAndWarpNameTheCulprit)
{
  bender::RibbonSpec good;
  good.start = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  good.end = { { 3, 1, 0 }, { 1, 0, 0 }, { 0, 0, 1 } };
  bender::RibbonSpec cusp = good;
  cusp.end = { { 2, 0, 0 }, { -1, 0, 0 }, { 0, 0, 1 } };
  try
  {
    bender::Ribbon r(cusp);
    ADD_FAILURE() << "cusp accepted";
  }
  catch (const bender::InvalidRibbonError& e)
  {
    EXPECT_EQ(e.field(), "");
    EXPECT_NE(std::string(e.what()).find("cusp"), std::string::npos);
  }
  bender::WarpSpec w;
  w.initial = good;
  w.final = cusp;
  w.radius = 0.5;
  try
  {
    bender::RibbonWarp warp(w);
    ADD_FAILURE() << "cusp accepted";
  }
  catch (const bender::InvalidWarpError& e)
  {
    ADD_FAILURE() << "a ribbon problem reported as an InvalidWarpError: " << e.what();
  }
  catch (const bender::InvalidRibbonError& e)
  {
    EXPECT_EQ(e.field(), "final");
    EXPECT_NE(std::string(e.what()).find("cusp"), std::string::npos);
  }
  w.initial = cusp;
  w.final = good;
  try
  {
    bender::RibbonWarp warp(w);
    ADD_FAILURE() << "cusp accepted";
  }
  catch (const bender::InvalidRibbonError& e)
  {
    EXPECT_EQ(e.field(), "initial");
  }
  // Non-finite normal: the field names the normal.
  bender::RibbonSpec bad = good;
  bad.end.normal = { std::nan(""), 0, 1 };
  w.initial = good;
  w.final = bad;
  try
  {
    bender::RibbonWarp warp(w);
    ADD_FAILURE() << "NaN normal accepted";
  }
  catch (const bender::InvalidRibbonError& e)
  {
    EXPECT_EQ(e.field(), "final.end.normal");
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos);
  }
}

} // namespace
