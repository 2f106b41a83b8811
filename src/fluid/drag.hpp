#pragma once
// Gas-particle drag laws of Gera et al. (1998), Eqs. 13-14, and packed-bed relations used to check them.
// Shared by the CFD-DEM coupling and the two-fluid model; every function is pure.

namespace fluidbed {

/// Local state for an interphase momentum coefficient. SI units.
struct DragInput {
  double eps = 1.0;     ///< gas volume fraction (voidage), 0 < eps <= 1
  double d_p = 0.004;   ///< particle diameter [m]
  double rho_g = 1.205; ///< gas density [kg/m^3]
  double mu_g = 1.8e-5; ///< gas dynamic viscosity [Pa s]
  double slip = 0.0;    ///< |u_s - u_g|, magnitude of the interstitial slip velocity [m/s]
};

/// How the Ergun and Wen-Yu branches of Eq. 13 are joined.
enum class DragSwitch {
  Sharp,   ///< the paper's step at eps = 0.8 (default)
  Smooth,  ///< arctan blend of Huilin & Gidaspow (2003) centred at eps = 0.8
};

/// Voidage at which Eq. 13 changes from Ergun to Wen-Yu.
inline constexpr double kErgunWenYuSwitch = 0.8;

/// Eq. 14: drag coefficient of an isolated sphere (Schiller-Naumann below Re = 1000, Newton regime above).
/// Re <= 0 returns +infinity (the Stokes limit 24/Re).
double drag_coefficient(double re);

/// Particle Reynolds number Re = eps rho_g |slip| d_p / mu_g (Gidaspow 1994, "Multiphase Flow and Fluidization", Ch. 5).
double particle_reynolds(const DragInput& in);

/// Ergun branch of Eq. 13 [kg/m^3/s].
double beta_ergun(const DragInput& in);

/// Wen-Yu branch of Eq. 13 (exponent -2.7 as in the paper) [kg/m^3/s].
double beta_wen_yu(const DragInput& in);

/// Eq. 13: interphase momentum coefficient beta [kg/m^3/s], Ergun for eps <= 0.8 and Wen-Yu above.
double beta_ergun_wen_yu(const DragInput& in, DragSwitch mode = DragSwitch::Sharp);

/// Terminal settling velocity [m/s] of an isolated sphere with C_D from Eq. 14
/// (solves (3/4) C_D(Re) rho_g u^2 = d_p (rho_p - rho_g) g by bisection). g is the magnitude of gravity.
double terminal_velocity(double d_p, double rho_p, double rho_g, double mu_g, double g = 9.81);

/// Ergun (1952) frictional pressure gradient -dP/dy [Pa/m] of a packed bed at superficial velocity U (sign follows U).
double ergun_pressure_gradient(double eps, double d_p, double rho_g, double mu_g, double u_superficial);

/// Ergun minimum fluidisation velocity [m/s]: the U at which ergun_pressure_gradient equals the buoyant bed weight
/// (1 - eps_mf)(rho_s - rho_g) g; positive root of the quadratic. g is the magnitude of gravity.
double ergun_minimum_fluidisation_velocity(double eps_mf, double d_p, double rho_s, double rho_g, double mu_g,
                                           double g = 9.81);

}  // namespace fluidbed
