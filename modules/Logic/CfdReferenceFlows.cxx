#include "CfdReferenceFlows.h"

#include <cmath>

namespace bender
{

double ShahApparentFrictionRe(double xPlus)
{
  const double root = 3.44 / std::sqrt(xPlus);
  return root + (1.25 / (4.0 * xPlus) + 16.0 - root) / (1.0 + 0.00021 / (xPlus * xPlus));
}

double ShahPressureDrop(double length, double diameter, double meanVelocity, double nu, double rho)
{
  const double reynolds = meanVelocity * diameter / nu;
  const double fanning = ShahApparentFrictionRe(length / (diameter * reynolds)) / reynolds;
  return 4.0 * fanning * (length / diameter) * 0.5 * rho * meanVelocity * meanVelocity;
}

double PoiseuilleWallShearStress(double diameter, double meanVelocity, double nu, double rho)
{
  return 8.0 * rho * nu * meanVelocity / diameter;
}

double PoiseuillePressureGradient(double diameter, double meanVelocity, double nu, double rho)
{
  return 32.0 * rho * nu * meanVelocity / (diameter * diameter);
}

double DeanNumber(double reynolds, double tubeRadius, double bendRadius)
{
  return reynolds * std::sqrt(tubeRadius / bendRadius);
}

double WhiteFrictionRatio(double dean)
{
  if (dean <= 11.6)
  {
    return 1.0;
  }
  return 1.0 / (1.0 - std::pow(1.0 - std::pow(11.6 / dean, 0.45), 1.0 / 0.45));
}

} // namespace bender
