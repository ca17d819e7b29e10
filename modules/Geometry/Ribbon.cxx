#include "Ribbon.h"

#include "GeometryErrors.h"

#include <cmath>

namespace bender
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

void CheckEnd(const RibbonEnd& e, const std::string& name)
{
  if (!IsFinite(e.position))
  {
    throw InvalidRibbonError(name + ".position", "non-finite coordinate");
  }
  if (!IsFinite(e.tangent))
  {
    throw InvalidRibbonError(name + ".tangent", "non-finite coordinate");
  }
  if (!IsFinite(e.normal))
  {
    throw InvalidRibbonError(name + ".normal", "non-finite coordinate");
  }
  const double tn = Norm(e.tangent);
  if (!(tn > 0.0) || !std::isfinite(tn))
  {
    throw InvalidRibbonError(name + ".tangent", "zero vector");
  }
  const double nn = Norm(e.normal);
  if (!std::isfinite(nn) || !(Norm(Cross(e.normal, e.tangent / tn)) > 1e-9 * nn))
  {
    throw InvalidRibbonError(name + ".normal", "zero or parallel to the tangent");
  }
}

Vec3 OrthoNormal(const Vec3& n, const Vec3& t)
{
  return Normalized(n - t * Dot(n, t));
}
} // namespace

Ribbon::Ribbon(const RibbonSpec& spec)
  : Input(spec)
{
  CheckEnd(spec.start, "start");
  CheckEnd(spec.end, "end");
  this->Curve =
    Biarc::FromEnds(spec.start.position, spec.start.tangent, spec.end.position, spec.end.tangent);
  this->N0 = OrthoNormal(spec.start.normal, this->Curve.StartTangent());
  this->N1 = OrthoNormal(spec.end.normal, this->Curve.EndTangent());

  // tau = sang(N0*, N1, T1) with N0* the rotation-minimising transport of N0 to P1.
  const Vec3 n0Star =
    this->Curve.SecondArc().TransportAt(1.0, this->Curve.FirstArc().TransportAt(1.0, this->N0));
  double tau = SignedAngle(n0Star, this->N1, this->Curve.EndTangent());
  if (std::abs(tau) > Pi - 1e-9)
  {
    tau = Pi;
  }
  this->TauPrincipal = tau;
  this->Tau = tau + 2.0 * Pi * spec.extraTurns;
}

int Ribbon::UnwrappedExtraTurns(const RibbonSpec& spec, double referenceTwist)
{
  RibbonSpec principal = spec;
  principal.extraTurns = 0;
  const double tau = Ribbon(principal).PrincipalTwist();
  return static_cast<int>(std::lround((referenceTwist - tau) / (2.0 * Pi)));
}

Frame Ribbon::FrameAt(double s) const
{
  const Biarc& w = this->Curve;
  const double sJ = w.JunctionParameter();
  Frame f;
  if (s <= sJ)
  {
    const double u = sJ > 0.0 ? s / sJ : 0.0;
    const Arc& arc = w.FirstArc();
    f.origin = arc.PointAt(u);
    f.t = arc.TangentAt(u);
    f.n = arc.TransportAt(u, Rotate(w.StartTangent(), s * this->Tau, this->N0));
  }
  else
  {
    const double u = (s - sJ) / (1.0 - sJ);
    const Arc& arc = w.SecondArc();
    f.origin = arc.PointAt(u);
    f.t = arc.TangentAt(u);
    // Rotate C1 by -(1 - s) tau about T1, then backwards about arc 2's axis by the angle
    // still to go to P1.
    const Vec3 twisted = Rotate(w.EndTangent(), -(1.0 - s) * this->Tau, this->N1);
    f.n = arc.line ? twisted : Rotate(arc.axis, -arc.angle * (1.0 - u), twisted);
  }
  f.b = Cross(f.t, f.n);
  return f;
}

} // namespace bender
