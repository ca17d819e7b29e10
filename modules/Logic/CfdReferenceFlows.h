#ifndef bender_CfdReferenceFlows_h
#define bender_CfdReferenceFlows_h

// Published laminar pipe-flow results the CFD verification cases are measured against
// (issue 23, bender-cli cfd-verify). SI units; D the tube's diameter, U the mean velocity,
// Re = U D / nu, mu = rho nu.

namespace bender
{

/// Shah's apparent Fanning friction factor times Re for developing laminar flow in a circular
/// duct from a uniform inlet velocity (R. K. Shah, "A correlation for laminar hydrodynamic entry
/// length solutions for circular and noncircular ducts", J. Fluids Eng. 100, 177-179, 1978),
/// within 2 % of the numerical solutions it fits:
///
///   f_app Re = 3.44 / sqrt(x+) + (1.25 / (4 x+) + 16 - 3.44 / sqrt(x+)) / (1 + 0.00021 x+^-2)
///
/// with x+ = x / (D Re) > 0. Tends to 16 (Poiseuille) plus the entrance excess 1.25 / (4 x+).
double ShahApparentFrictionRe(double xPlus);

/// The pressure drop (Pa) from a uniform inlet over a length L of a circular duct, by Shah's
/// correlation: dp = 4 f_app (L / D) rho U^2 / 2.
double ShahPressureDrop(double length, double diameter, double meanVelocity, double nu, double rho);

/// Poiseuille's wall shear stress of developed laminar flow, 8 mu U / D (Pa).
double PoiseuilleWallShearStress(double diameter, double meanVelocity, double nu, double rho);

/// Poiseuille's pressure gradient of developed laminar flow, 32 mu U / D^2 (Pa/m).
double PoiseuillePressureGradient(double diameter, double meanVelocity, double nu, double rho);

/// The Dean number Re sqrt(a / Rc), a the tube's radius, Rc the bend's centreline radius.
double DeanNumber(double reynolds, double tubeRadius, double bendRadius);

/// White's friction ratio of developed laminar flow in a curved pipe to the straight pipe's at
/// the same Re (C. M. White, "Streamline flow through curved pipes", Proc. R. Soc. Lond. A 123,
/// 645-663, 1929):
///
///   f_c / f_s = 1 / (1 - (1 - (11.6 / De)^0.45)^(1 / 0.45)),   11.6 < De < 2000;
///
/// 1 for De <= 11.6 (Dean's regime, where curvature barely changes the friction).
double WhiteFrictionRatio(double dean);

} // namespace bender

#endif
