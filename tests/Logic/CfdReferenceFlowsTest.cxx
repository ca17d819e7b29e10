// The published laminar results of the CFD verification cases (CfdReferenceFlows.h), checked
// against their own limits and an independent correlation rather than against copied numbers.

#include "CfdReferenceFlows.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
constexpr double Nu = 3.5e-6, Rho = 1060.0;

TEST(CfdReferenceFlows, ShahTendsToPoiseuillePlusTheEntranceExcess)
{
  // Far downstream: f_app Re = 16 + K / (4 x+) with Hagenbach's K(inf) = 1.25.
  for (const double x : { 10.0, 100.0, 1000.0 })
  {
    EXPECT_NEAR(bender::ShahApparentFrictionRe(x), 16.0 + 1.25 / (4.0 * x), 2e-3 * 16.0);
  }
  // Near the inlet: the boundary-layer term 3.44 / sqrt(x+) dominates.
  for (const double x : { 1e-5, 1e-4 })
  {
    EXPECT_NEAR(bender::ShahApparentFrictionRe(x) / (3.44 / std::sqrt(x)), 1.0, 1e-3);
  }
  // The apparent friction falls monotonically along the tube.
  double previous = INFINITY;
  for (double x = 1e-5; x < 10.0; x *= 1.5)
  {
    const double f = bender::ShahApparentFrictionRe(x);
    EXPECT_LT(f, previous) << "x+ " << x;
    previous = f;
  }
}

TEST(CfdReferenceFlows, ShahsPressureDropIsPoiseuillesPlusTheInletLoss)
{
  const double d = 4e-3, u = 0.0875; // Re 100
  const double length = 2.0;         // x+ = 5: developed over nearly all of it
  const double poiseuille = bender::PoiseuillePressureGradient(d, u, Nu, Rho) * length;
  const double excess = bender::ShahPressureDrop(length, d, u, Nu, Rho) - poiseuille;
  EXPECT_NEAR(excess / (0.5 * Rho * u * u), 1.25, 0.02);
}

TEST(CfdReferenceFlows, PoiseuillesShearBalancesItsPressureGradient)
{
  // tau pi D L = G L pi D^2 / 4 for developed flow.
  for (const double d : { 2e-3, 4e-3, 2e-2 })
  {
    const double u = 0.1;
    EXPECT_NEAR(bender::PoiseuilleWallShearStress(d, u, Nu, Rho),
      bender::PoiseuillePressureGradient(d, u, Nu, Rho) * d / 4.0,
      1e-12);
  }
}

TEST(CfdReferenceFlows, WhitesRatioAgreesWithMishraAndGupta)
{
  EXPECT_DOUBLE_EQ(bender::WhiteFrictionRatio(5.0), 1.0);
  EXPECT_NEAR(bender::WhiteFrictionRatio(11.6), 1.0, 1e-12);
  EXPECT_NEAR(bender::DeanNumber(100.0, 1.0, 4.0), 50.0, 1e-12);
  double previous = 1.0;
  for (double dean = 12.0; dean < 2000.0; dean *= 1.2)
  {
    const double white = bender::WhiteFrictionRatio(dean);
    EXPECT_GT(white, previous) << "Dean " << dean;
    previous = white;
    // Mishra and Gupta (1979), an independent fit of the same experiments over the range the
    // verification uses.
    if (dean >= 50.0 && dean <= 300.0)
    {
      const double mishra = 1.0 + 0.033 * std::pow(std::log10(dean), 4.0);
      EXPECT_NEAR(white / mishra, 1.0, 0.05) << "Dean " << dean;
    }
  }
}

} // namespace
