#ifndef bender_Biarc_h
#define bender_Biarc_h

#include "Vec3.h"

#include <limits>

namespace bender
{

/// One circular arc (or straight segment) of a biarc, spec 1.2.
/// Points are evaluated without the centre, so nearly straight arcs stay exact.
struct Arc
{
  bool line = false; ///< exactly straight (theta == 0); the centre and axis are then unused
  Vec3 start;        ///< Ps
  Vec3 tangent;      ///< Ts, unit tangent at Ps
  Vec3 toCentre;     ///< Np, unit principal normal at Ps (zero for a line)
  Vec3 axis;         ///< n = Ts x Np, unit normal of the arc's plane (zero for a line)
  Vec3 centre;       ///< O (meaningless for a line)
  double radius = std::numeric_limits<double>::infinity(); ///< r (infinite for a line)
  double angle = 0.0;                                      ///< theta in [0, pi], the turning angle
  double length = 0.0;                                     ///< L

  /// Point at the fraction u in [0, 1] of the arc's length.
  Vec3 PointAt(double u) const;
  /// Unit tangent at the fraction u.
  Vec3 TangentAt(double u) const;
  /// Rotate v by the turning of the arc up to the fraction u (identity for a line).
  Vec3 TransportAt(double u, const Vec3& v) const;
};

/// The equal-tangent-length biarc (a = b) through (P0, T0) and (P1, T1), spec 1.
/// Parameterised by global arc length s in [0, 1] (spec 1.4).
class Biarc
{
public:
  Biarc() = default;

  /// Builds the wire. Tangents need not be unit. Throws InvalidRibbonError (field empty)
  /// for non-finite input, coincident ends, a cusp, no positive root, or a wire longer than
  /// 200 |P1 - P0| (spec 1.3, convention 11).
  static Biarc FromEnds(const Vec3& p0, const Vec3& t0, const Vec3& p1, const Vec3& t1);

  Vec3 PointAt(double s) const;
  Vec3 TangentAt(double s) const;

  const Arc& FirstArc() const { return this->Arcs[0]; }
  const Arc& SecondArc() const { return this->Arcs[1]; }
  const Arc& GetArc(int i) const { return this->Arcs[i]; }

  Vec3 Start() const { return this->P0; }
  Vec3 End() const { return this->P1; }
  Vec3 StartTangent() const { return this->T0; }
  Vec3 EndTangent() const { return this->T1; }
  Vec3 Junction() const { return this->J; }
  Vec3 JunctionTangent() const { return this->U; }
  /// The tangent length a (infinite for the two-semicircle case).
  double TangentLength() const { return this->A; }
  /// s at the junction, L1 / L.
  double JunctionParameter() const { return this->SJ; }
  double Length() const { return this->Arcs[0].length + this->Arcs[1].length; }
  /// Smallest arc radius, r_min = min(r1, r2) (infinite for straight arcs), spec 3.3.
  double MinimumRadius() const;
  bool IsSemicircles() const { return this->Semicircles; }

private:
  Vec3 P0, T0, P1, T1, J, U;
  double A = 0.0;
  double SJ = 0.5;
  bool Semicircles = false;
  Arc Arcs[2];
};

} // namespace bender

#endif
