#include "Biarc.h"

#include "GeometryErrors.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bender
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

// sin(x)/x, accurate near 0.
double Sinc(double x)
{
  if (std::abs(x) < 1e-4)
  {
    const double x2 = x * x;
    return 1.0 - x2 / 6.0 + x2 * x2 / 120.0;
  }
  return std::sin(x) / x;
}

// theta / tan(theta/2), with the series near 0 (spec 1.2).
double ThetaOverTanHalf(double theta)
{
  if (theta < 1e-4)
  {
    const double t2 = theta * theta;
    return 2.0 - t2 / 6.0 - t2 * t2 / 360.0;
  }
  return theta / std::tan(0.5 * theta);
}

// ARC(Ps, Ts, Te, a) of spec 1.2.
Arc MakeArc(const Vec3& ps, const Vec3& ts, const Vec3& te, double a)
{
  Arc arc;
  arc.start = ps;
  arc.tangent = ts;
  const double cosT = Dot(ts, te);
  const double sinT = Norm(Cross(ts, te));
  arc.angle = std::atan2(sinT, cosT);
  const Vec3 w = te - ts * cosT;
  const double wn = Norm(w);
  const double radius = arc.angle > 0.0 ? a / std::tan(0.5 * arc.angle) : 0.0;
  if (cosT > 0.0 && (wn == 0.0 || arc.angle == 0.0 || !std::isfinite(radius)))
  {
    // Exactly straight: decided on exact zero, never on a threshold. Te may equal Ts to the
    // last bit while w is not zero (|Ts|^2 is 1 only to rounding, so w is a multiple of Ts):
    // the turn is then exactly 0 and the radius infinite, a line all the same.
    arc.line = true;
    arc.angle = 0.0;
    arc.length = 2.0 * a;
    return arc;
  }
  arc.toCentre = wn > 0.0 ? w / wn : Vec3{};
  arc.axis = Cross(ts, arc.toCentre);
  arc.radius = radius;
  arc.centre = ps + arc.toCentre * arc.radius;
  arc.length = a * ThetaOverTanHalf(arc.angle);
  return arc;
}

std::string Num(double v)
{
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}
} // namespace

Vec3 Arc::PointAt(double u) const
{
  const double l = this->length * u;
  if (this->line)
  {
    return this->start + this->tangent * l;
  }
  const double x = this->angle * u;
  return this->start + this->tangent * (l * Sinc(x)) +
    this->toCentre * (l * std::sin(0.5 * x) * Sinc(0.5 * x));
}

Vec3 Arc::TangentAt(double u) const
{
  if (this->line)
  {
    return this->tangent;
  }
  const double x = this->angle * u;
  return this->tangent * std::cos(x) + this->toCentre * std::sin(x);
}

Vec3 Arc::TransportAt(double u, const Vec3& v) const
{
  if (this->line)
  {
    return v;
  }
  return Rotate(this->axis, this->angle * u, v);
}

Biarc Biarc::FromEnds(const Vec3& p0, const Vec3& t0In, const Vec3& p1, const Vec3& t1In)
{
  if (!IsFinite(p0) || !IsFinite(p1) || !IsFinite(t0In) || !IsFinite(t1In))
  {
    throw InvalidRibbonError("", "non-finite position or tangent");
  }
  const double n0 = Norm(t0In);
  const double n1 = Norm(t1In);
  if (!(n0 > 0.0) || !(n1 > 0.0) || !std::isfinite(n0) || !std::isfinite(n1))
  {
    throw InvalidRibbonError("", "zero tangent");
  }
  Biarc b;
  b.P0 = p0;
  b.P1 = p1;
  b.T0 = t0In / n0;
  b.T1 = t1In / n1;
  const Vec3 S = p1 - p0;
  const Vec3 T = b.T0 + b.T1;
  const double h = std::max({ 1.0, Norm(p0), Norm(p1) });
  const double epsLen = 1e-9 * h;
  const double epsC = 1e-12;
  const double epsB = 1e-9;
  const double sLen = Norm(S);
  if (sLen < epsLen)
  {
    throw InvalidRibbonError(
      "", "coincident ends (the two ends of the wire are at the same point)");
  }
  const double q = Dot(S, S);
  const double bb = Dot(S, T);
  const double c = 2.0 * (1.0 - Dot(b.T0, b.T1));
  const double disc = std::max(0.0, bb * bb + c * q);

  if (c <= epsC && std::abs(bb) <= epsB * sLen)
  {
    // Two semicircles (spec 1.3): the limit of the general case from both sides.
    b.Semicircles = true;
    b.A = std::numeric_limits<double>::infinity();
    const Vec3 sDir = S / sLen;
    b.J = (p0 + p1) * 0.5;
    b.U = -b.T0;
    const double r = sLen / 4.0;
    for (int i = 0; i < 2; ++i)
    {
      Arc& arc = b.Arcs[i];
      arc.start = i == 0 ? p0 : b.J;
      arc.tangent = i == 0 ? b.T0 : b.U;
      arc.toCentre = sDir;
      arc.axis = Cross(arc.tangent, sDir);
      arc.radius = r;
      arc.centre = arc.start + sDir * r;
      arc.angle = Pi;
      arc.length = Pi * r;
    }
  }
  else
  {
    double a = 0.0;
    if (bb > 0.0)
    {
      a = q / (bb + std::sqrt(disc));
    }
    else if (c > 0.0)
    {
      a = (std::sqrt(disc) - bb) / c;
    }
    else
    {
      throw InvalidRibbonError(
        "", "no biarc: the end tangents are parallel and the end lies behind the start");
    }
    if (!(a > 0.0) || !std::isfinite(a))
    {
      throw InvalidRibbonError("", "no biarc: no positive tangent length");
    }
    b.A = a;
    const Vec3 i0 = p0 + b.T0 * a;
    const Vec3 i1 = p1 - b.T1 * a;
    b.J = (i0 + i1) * 0.5;
    const Vec3 d = i1 - i0;
    const double dn = Norm(d);
    // |I1 - I0| = 2a > 0 for a valid root; guard the division all the same.
    b.U = dn > 0.0 ? d / dn : b.T0;
    b.Arcs[0] = MakeArc(p0, b.T0, b.U, a);
    b.Arcs[1] = MakeArc(b.J, b.U, b.T1, a);
  }

  const double total = b.Arcs[0].length + b.Arcs[1].length;
  for (int i = 0; i < 2; ++i)
  {
    if (b.Arcs[i].length < 1e-9 * sLen && b.Arcs[i].angle > 0.5 * Pi)
    {
      throw InvalidRibbonError("",
        std::string("cusp: the wire reverses on itself at its ") + (i == 0 ? "start" : "end") +
          " (an end tangent points back along the wire)");
    }
  }
  if (!(total <= 200.0 * sLen))
  {
    throw InvalidRibbonError("",
      "unstable wire: the biarc would be " + Num(total / sLen) +
        " times longer than the distance between its ends (end tangents nearly parallel with "
        "the end behind the start)");
  }
  b.SJ = total > 0.0 ? b.Arcs[0].length / total : 0.5;
  return b;
}

Vec3 Biarc::PointAt(double s) const
{
  if (s <= this->SJ)
  {
    return this->Arcs[0].PointAt(this->SJ > 0.0 ? s / this->SJ : 0.0);
  }
  return this->Arcs[1].PointAt((s - this->SJ) / (1.0 - this->SJ));
}

Vec3 Biarc::TangentAt(double s) const
{
  if (s <= this->SJ)
  {
    return this->Arcs[0].TangentAt(this->SJ > 0.0 ? s / this->SJ : 0.0);
  }
  return this->Arcs[1].TangentAt((s - this->SJ) / (1.0 - this->SJ));
}

double Biarc::MinimumRadius() const
{
  return std::min(this->Arcs[0].radius, this->Arcs[1].radius);
}

} // namespace bender
