#ifndef bender_Ribbon_h
#define bender_Ribbon_h

#include "Biarc.h"
#include "Frame.h"
#include "WarpPlan.h"

namespace bender
{

/// A ribbon: the biarc wire through its two end frames plus the twist distributed linearly in
/// s along it (spec 2). Frames C_s = (P_s; T_s, N_s, B_s) are right-handed and orthonormal,
/// C_0 and C_1 are the (normalised) end frames.
class Ribbon
{
public:
  Ribbon() = default;

  /// Validates and builds. Throws InvalidRibbonError whose field() names the culprit relative
  /// to the ribbon ("start.tangent", "end.normal", ... or "" for the wire as a whole).
  explicit Ribbon(const RibbonSpec& spec);

  const Biarc& Wire() const { return this->Curve; }
  const RibbonSpec& Spec() const { return this->Input; }

  /// Unit end tangents and normals (normals made orthogonal to the tangents).
  const Vec3& StartNormal() const { return this->N0; }
  const Vec3& EndNormal() const { return this->N1; }

  /// Principal twist in (-pi, pi] (tie at pi goes to +pi), spec 2.1.
  double PrincipalTwist() const { return this->TauPrincipal; }
  /// Total twist tau = principal + 2 pi extraTurns.
  double Twist() const { return this->Tau; }

  /// The extraTurns that puts this ribbon's total twist nearest to referenceTwist: the live
  /// unwrapping of spec 2.1 (tau += 2 pi round((tau_prev - tau) / 2 pi)). An interactive
  /// session starts at grab with the initial ribbon's twist as the reference and passes the
  /// previous update's twist afterwards, so a twist past half a turn does not jump.
  /// Throws InvalidRibbonError as the constructor does.
  static int UnwrappedExtraTurns(const RibbonSpec& spec, double referenceTwist);

  /// The frame C_s at s in [0, 1] (spec 2.2).
  Frame FrameAt(double s) const;

private:
  RibbonSpec Input;
  Biarc Curve;
  Vec3 N0, N1;
  double TauPrincipal = 0.0;
  double Tau = 0.0;
};

} // namespace bender

#endif
