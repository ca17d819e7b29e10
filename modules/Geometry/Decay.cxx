#include "Decay.h"

#include <algorithm>

namespace bender
{

double EvaluateDecay(const DecaySpec& decay, double x)
{
  if (!(x < 1.0))
  {
    return 0.0;
  }
  x = std::max(0.0, x);
  double f = 0.0;
  if (decay.shape == DecayShape::Bell)
  {
    const double v = 1.0 - x * x;
    f = v * v * v;
  }
  else
  {
    const double p = decay.plateau;
    if (x <= p)
    {
      return 1.0;
    }
    const double u = (x - p) / (1.0 - p);
    const double v = 1.0 - u;
    // Factored form: the expanded polynomial goes slightly negative near u = 1.
    f = v * v * v * (1.0 + 3.0 * u + 6.0 * u * u);
  }
  return std::clamp(f, 0.0, 1.0);
}

} // namespace bender
