#ifndef bender_Screw_h
#define bender_Screw_h

#include "Frame.h"
#include "Quaternion.h"
#include "Vec3.h"

namespace bender
{

/// A unit dual quaternion real + eps dual: the rigid motion X -> R X + t with
/// real = q(R) and dual = 1/2 (0, t) real.
struct DualQuaternion
{
  Quaternion real;
  Quaternion dual{ 0, 0, 0, 0 };
};

/// Screw parameters of a rigid motion (spec 4.1): X -> A + Rot(K, beta)(X - A) + d K.
/// beta in [0, 2 pi); beta > pi only after the continuity lift. For a pure translation
/// (beta == 0) K is the translation's direction and d its length.
struct Screw
{
  Vec3 k{ 1, 0, 0 };
  double beta = 0.0;
  double d = 0.0;
  Vec3 a;               ///< a point on the axis (meaningless for a pure translation)
  bool flipped = false; ///< the lift chose the non-minimal twin (lifted w < 0)
};

/// The rigid motion carrying frame c onto frame cp, X -> O' + M' M^T (X - O), as a unit dual
/// quaternion whose rotation has the sign of q (q must be +-quat(M' M^T)).
DualQuaternion MotionBetween(const Frame& c, const Frame& cp, const Quaternion& q);

/// Screw parameters of a unit dual quaternion (the sign of its real part decides between the
/// minimal screw and its twin).
Screw ScrewOf(const DualQuaternion& m);

/// Applies the fraction f of the screw of m to p: SCREW_F(P; f) of spec 4.2, computed as the
/// dual-quaternion power m^f (spec 4.3), which is A-free and well-conditioned for every beta
/// in [0, 2 pi). f = 0 gives p, f = 1 gives m(p).
Vec3 ApplyScrewFraction(const DualQuaternion& m, const Vec3& p, double f);

/// The rigid motion of m applied to p (f = 1).
Vec3 ApplyMotion(const DualQuaternion& m, const Vec3& p);

} // namespace bender

#endif
