#include "RibbonWarp.h"

#include "Decay.h"
#include "GeometryErrors.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bender
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double MaxTurn = 2.0 * Pi - 20.0 * Pi / 180.0; // 340 degrees

Ribbon BuildRibbon(const RibbonSpec& spec, const std::string& which)
{
  try
  {
    return Ribbon(spec);
  }
  catch (const InvalidRibbonError& e)
  {
    throw InvalidRibbonError(e.field().empty() ? which : which + "." + e.field(), e.problem());
  }
}

// The motion X -> O' + R (X - O) with R = q: t = O' - R O, dual = 1/2 (0, t) q.
DualQuaternion MotionFrom(const Quaternion& q, const Vec3& o, const Vec3& op)
{
  const Vec3 t = op - RotateByQuaternion(q, o);
  DualQuaternion m;
  m.real = q;
  m.dual = Quaternion{ 0.0, 0.5 * t.x, 0.5 * t.y, 0.5 * t.z } * q;
  return m;
}

std::string Fixed(double v, int digits)
{
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << v;
  return os.str();
}
} // namespace

SampleGrid SampleGrid::Build(double knot1, double knot2, int samples)
{
  SampleGrid grid;
  std::vector<double> knots = { knot1, knot2 };
  std::sort(knots.begin(), knots.end());
  // A piece shorter than one spacing would cost samples of its own and gain nothing.
  const double minPiece = 1.0 / std::max(samples, 2);
  std::vector<double> kept = { 0.0 };
  for (double k : knots)
  {
    if (k - kept.back() >= minPiece && 1.0 - k >= minPiece)
    {
      kept.push_back(k);
    }
  }
  kept.push_back(1.0);
  int offset = 0;
  for (std::size_t k = 0; k + 1 < kept.size(); ++k)
  {
    Piece p;
    p.start = kept[k];
    p.end = kept[k + 1];
    const double length = p.end - p.start;
    const int n = std::max(2, static_cast<int>(std::ceil(length * (samples - 1))) + 1);
    p.scale = (n - 1) / length;
    p.offset = offset;
    p.last = offset + n - 1;
    for (int j = 0; j < n; ++j)
    {
      grid.s.push_back(j + 1 == n ? p.end : p.start + j / p.scale);
    }
    offset += n;
    grid.pieces.push_back(p);
  }
  return grid;
}

const SampleGrid::Piece& SampleGrid::PieceOf(double s) const
{
  std::size_t k = 0;
  while (k + 1 < this->pieces.size() && s >= this->pieces[k].end)
  {
    ++k;
  }
  return this->pieces[k];
}

int SampleGrid::Nearest(double s) const
{
  s = std::clamp(s, 0.0, 1.0);
  const Piece& p = this->PieceOf(s);
  const int j = p.offset + static_cast<int>(std::lround((s - p.start) * p.scale));
  return std::clamp(j, p.offset, p.last);
}

RibbonWarp::RibbonWarp(const WarpSpec& spec, const WarpOptions& options)
  : Input(spec)
  , Opts(options)
{
  if (!std::isfinite(spec.radius) || !(spec.radius > 0.0))
  {
    throw InvalidWarpError("radius", "must be a finite number > 0");
  }
  if (spec.decay.shape == DecayShape::Plateau &&
    !(spec.decay.plateau >= 0.0 && spec.decay.plateau <= 0.95))
  {
    throw InvalidWarpError("decay.plateau", "must be in [0, 0.95]");
  }
  this->InitialRibbon = BuildRibbon(spec.initial, "initial");
  this->FinalRibbon = BuildRibbon(spec.final, "final");
  this->InitialPath = FramePath(this->InitialRibbon);
  this->FinalPath = FramePath(this->FinalRibbon);

  const double twistChange = this->FinalRibbon.Twist() - this->InitialRibbon.Twist();
  if (std::abs(twistChange) > MaxTurn)
  {
    throw InvalidWarpError("final",
      "the ribbon twists by " + Fixed(twistChange * 180.0 / Pi, 0) +
        " degrees relative to where it was grabbed (more than 340); release and grab again to "
        "go further");
  }

  int samples = std::max(1024, options.signTableSamples);
  while (true)
  {
    if (this->TryBuildSignTable(samples))
    {
      break;
    }
    if (samples >= (1 << 20))
    {
      throw InvalidWarpError(
        "", "the ribbon's frames rotate too fast along the wire to follow the screws");
    }
    samples *= 2;
  }

  // The 340 degree rule on the lifted rotation (spec 4.4).
  const int n = static_cast<int>(this->Lifted.size());
  for (int j = 0; j < n; ++j)
  {
    const Quaternion& q = this->Lifted[j];
    const double beta = 2.0 * std::atan2(Norm(q.Vector()), q.w);
    if (beta > MaxTurn)
    {
      const double s = this->Samples.s[j];
      throw InvalidWarpError("",
        "the ribbon turns more than 340 degrees relative to where it was grabbed (at s = " +
          Fixed(s, 2) + "); release and grab again to go further");
    }
  }
}

RibbonWarp::FramePath::FramePath(const Ribbon& ribbon)
{
  const Biarc& w = ribbon.Wire();
  this->sJ = w.JunctionParameter();
  this->tau = ribbon.Twist();
  // Arc 1: N = Rot(n1, theta1 u) Rot(T0, tau s) N0, T = Rot(n1, theta1 u) T0.
  Piece& p1 = this->pieces[0];
  p1.arc = w.FirstArc();
  p1.base = QuaternionOfFrame(FrameOfTangentNormal(w.StartTangent(), ribbon.StartNormal()));
  p1.twistOffset = 0.0;
  // Arc 2: N = Rot(n2, -theta2 (1 - u)) Rot(T1, -(1 - s) tau) N1
  //          = Rot(n2, theta2 u) Rot(Tj, tau s - tau) Rot(n2, -theta2) N1,
  // since Rot(n2, -theta2) carries T1 to the arc's start tangent Tj.
  Piece& p2 = this->pieces[1];
  p2.arc = w.SecondArc();
  const double h2 = -0.5 * p2.arc.angle;
  const Vec3 n2 = p2.arc.line ? Vec3{ 0.0, 0.0, 0.0 } : p2.arc.axis;
  const Quaternion back{
    std::cos(h2), std::sin(h2) * n2.x, std::sin(h2) * n2.y, std::sin(h2) * n2.z
  };
  p2.base = back * QuaternionOfFrame(FrameOfTangentNormal(w.EndTangent(), ribbon.EndNormal()));
  p2.twistOffset = -this->tau;
}

void RibbonWarp::FramePath::At(double s, Quaternion& q, Vec3& origin) const
{
  const bool first = s <= this->sJ;
  const Piece& p = this->pieces[first ? 0 : 1];
  const double u =
    first ? (this->sJ > 0.0 ? s / this->sJ : 0.0) : (s - this->sJ) / (1.0 - this->sJ);
  const Arc& arc = p.arc;
  // Twist about the arc's start tangent by half of tau s + c.
  const double halfTwist = 0.5 * (this->tau * s + p.twistOffset);
  const double ct = std::cos(halfTwist);
  const double st = std::sin(halfTwist);
  const Quaternion twist{ ct, st * arc.tangent.x, st * arc.tangent.y, st * arc.tangent.z };
  const double l = arc.length * u;
  if (arc.line)
  {
    q = twist * p.base;
    origin = arc.start + arc.tangent * l;
    return;
  }
  // Turning by x = theta u about the arc's axis; the origin from the same half angle:
  // P = Ps + Ts l sin(x) / x + Np l sin(x / 2)^2 / (x / 2) (the centre is never formed).
  const double half = 0.5 * arc.angle * u;
  const double c2 = std::cos(half);
  const double s2 = std::sin(half);
  const Quaternion turn{ c2, s2 * arc.axis.x, s2 * arc.axis.y, s2 * arc.axis.z };
  q = turn * (twist * p.base);
  const double sinc = half > 0.0 ? s2 / half : 1.0;
  origin = arc.start + arc.tangent * (l * sinc * c2) + arc.toCentre * (l * sinc * s2);
}

DualQuaternion RibbonWarp::LiftedMotion(double s, const Quaternion& near) const
{
  Quaternion qi, qf;
  Vec3 oi, of;
  this->InitialPath.At(s, qi, oi);
  this->FinalPath.At(s, qf, of);
  Quaternion q = qf * Conjugate(qi);
  if (Dot4(near, q) < 0.0)
  {
    q = -q;
  }
  return MotionFrom(q, oi, of);
}

void RibbonWarp::Validate(const WarpSpec& spec)
{
  RibbonWarp warp(spec);
  (void)warp;
}

bool RibbonWarp::TryBuildSignTable(int samples)
{
  const double cos45 = std::sqrt(0.5);
  this->Samples = SampleGrid::Build(this->InitialRibbon.Wire().JunctionParameter(),
    this->FinalRibbon.Wire().JunctionParameter(),
    samples);
  const int count = static_cast<int>(this->Samples.s.size());
  this->Lifted.assign(count, Quaternion{});
  this->Table.assign(count, DualQuaternion{});
  this->AnyFlip = false;
  for (int j = 0; j < count; ++j)
  {
    const double s = this->Samples.s[j];
    // quat(M' M^T) = q' conj(q), normalised to the minimal rotation (w >= 0).
    Quaternion qi, qf;
    Vec3 oi, of;
    this->InitialPath.At(s, qi, oi);
    this->FinalPath.At(s, qf, of);
    Quaternion q = qf * Conjugate(qi);
    if (q.w < 0.0)
    {
      q = -q;
    }
    if (j == 0)
    {
      if (std::abs(q.w) <= 1e-12)
      {
        // Half a turn at s = 0: w >= 0 does not decide; the axis in C_0's own coordinates does.
        const Frame c = this->InitialRibbon.FrameAt(s);
        const Vec3 v = q.Vector();
        const double comps[3] = { Dot(v, c.t), Dot(v, c.n), Dot(v, c.b) };
        for (double comp : comps)
        {
          if (std::abs(comp) > 1e-9)
          {
            if (comp < 0.0)
            {
              q = -q;
            }
            break;
          }
        }
      }
      if (this->Input.reverseScrews)
      {
        q = -q;
      }
    }
    else
    {
      const Quaternion& prev = this->Lifted[j - 1];
      const double dot = Dot4(q, prev);
      if (dot < 0.0)
      {
        q = -q;
      }
      if (std::abs(dot) <= cos45)
      {
        return false;
      }
    }
    this->Lifted[j] = q;
    this->Table[j] = MotionFrom(q, oi, of);
    if (q.w < 0.0)
    {
      this->AnyFlip = true;
    }
  }
  return true;
}

bool RibbonWarp::SpaceInversionRisk() const
{
  const double r = this->Input.radius;
  return r >= this->InitialMinimumRadius() || r >= this->FinalMinimumRadius();
}

std::string RibbonWarp::SpaceInversionWarning() const
{
  if (!this->SpaceInversionRisk())
  {
    return {};
  }
  const double ri = this->InitialMinimumRadius();
  const double rf = this->FinalMinimumRadius();
  const bool initial = this->Input.radius >= ri;
  std::ostringstream os;
  os.precision(4);
  os << "space inversion possible: R = " << this->Input.radius << " is not smaller than the "
     << (initial ? "initial" : "final")
     << " wire's smallest arc radius r_min = " << (initial ? ri : rf)
     << "; reduce R or straighten the ribbon";
  return os.str();
}

DualQuaternion RibbonWarp::MotionAt(double s) const
{
  s = std::clamp(s, 0.0, 1.0);
  return this->LiftedMotion(s, this->Lifted[this->Samples.Nearest(s)]);
}

Screw RibbonWarp::ScrewAt(double s) const
{
  return ScrewOf(this->MotionAt(s));
}

double RibbonWarp::Weight(double distance) const
{
  return EvaluateDecay(this->Input.decay, distance / this->Input.radius);
}

Vec3 RibbonWarp::Apply(const Vec3& p) const
{
  return this->Apply(p, ProjectOntoWire(this->InitialRibbon.Wire(), p, this->Input.radius));
}

Vec3 RibbonWarp::Apply(const Vec3& p, const WireProjections& pr) const
{
  if (pr.count == 0)
  {
    return p;
  }
  const double f0 = this->Weight(pr.items[0].distance);
  if (pr.count == 1 || this->Opts.blend == BlendMode::SingleProjection)
  {
    return ApplyScrewFraction(this->MotionAt(pr.items[0].s), p, f0);
  }
  const double f1 = this->Weight(pr.items[1].distance);
  if (!(f0 + f1 > 0.0))
  {
    return p;
  }
  const double f = 1.0 - (1.0 - f0) * (1.0 - f1);
  const double l0 = f0 / (f0 + f1);
  const double l1 = f1 / (f0 + f1);
  return ApplyScrewFraction(this->MotionAt(pr.items[0].s), p, f) * l0 +
    ApplyScrewFraction(this->MotionAt(pr.items[1].s), p, f) * l1;
}

} // namespace bender
