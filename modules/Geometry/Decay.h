#ifndef bender_Decay_h
#define bender_Decay_h

#include "WarpPlan.h"

namespace bender
{

/// The decay F(x) of spec 5 at x = D / R >= 0, clamped to [0, 1]; F(x) = 0 for x >= 1.
/// bell: (1 - x^2)^3.  plateau p: 1 for x <= p, then G((x - p)/(1 - p)) with
/// G(u) = (1 - u)^3 (1 + 3u + 6u^2), C2 everywhere.
double EvaluateDecay(const DecaySpec& decay, double x);

} // namespace bender

#endif
