#pragma once
// Gas-particle drag laws: the paper's Eqs. 13-14 (Gera et al. 1998), Gidaspow (1994), Di Felice (1994),
// Beetstra, van der Hoef & Kuipers (2007) and Koch & Hill (2001), with packed-bed relations used to check them.
// Shared by the CFD-DEM coupling and the two-fluid model; every function is pure. Every law returns beta, the
// interphase momentum coefficient per unit mixture volume [kg/m^3/s], with the pressure gradient shared by
// volume fraction (Gidaspow's "model A"): the gas exerts beta (u_g - u_s) per unit volume besides -eps_s grad P,
// one particle of volume V_p feels V_p beta / (1 - eps) (u_g - v) besides -V_p grad P.

#include <utility>

namespace fluidbed {

/// Local state for an interphase momentum coefficient. SI units.
struct DragInput {
  double eps = 1.0;     ///< gas volume fraction (voidage), 0 < eps <= 1
  double d_p = 0.004;   ///< particle diameter [m]
  double rho_g = 1.205; ///< gas density [kg/m^3]
  double mu_g = 1.8e-5; ///< gas dynamic viscosity [Pa s]
  double slip = 0.0;    ///< |u_s - u_g|, magnitude of the interstitial slip velocity [m/s]
  /// Sauter mean diameter sum(d^3)/sum(d^2) of the particles around [m], for the polydisperse correction of
  /// Beetstra et al.; <= 0 means d_p (monodisperse). The other laws ignore it.
  double d_mean = 0.0;
};

/// Drag law chosen by name in the case file (`coupling.drag_law`).
enum class DragLaw {
  ErgunWenYu,  ///< the paper's Eqs. 13-14 (Wen-Yu exponent -2.7, C_D = 0.43 above Re = 1000); default
  Gidaspow,    ///< Gidaspow (1994): Ergun / Wen-Yu with eps^-2.65 and C_D = 0.44 above Re = 1000
  DiFelice,    ///< Di Felice (1994): Dallavalle C_D times eps^(-chi(Re))
  Beetstra,    ///< Beetstra, van der Hoef & Kuipers (2007), lattice-Boltzmann fit, polydisperse correction
  KochHill,    ///< Koch & Hill (2001), lattice-Boltzmann fit (Hill, Koch & Ladd 2001)
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

/// Gidaspow (1994), "Multiphase Flow and Fluidization", Eqs. 5.41-5.43 (Ergun below eps = 0.8, Wen-Yu with
/// eps^-2.65 and C_D = 0.44 for Re >= 1000 above), joined by `mode` (MFIX's GIDASPOW_BLEND is Smooth).
double beta_gidaspow(const DragInput& in, DragSwitch mode = DragSwitch::Smooth);

/// Di Felice (1994), Int. J. Multiphase Flow 20:153: one particle's drag (1/2) C_D rho_g (pi d^2/4) eps^2 |w| w
/// eps^-chi, C_D = (0.63 + 4.8 / sqrt(Re))^2 (Dallavalle), chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2),
/// Re = eps rho_g |w| d / mu_g with w the interstitial slip.
double beta_di_felice(const DragInput& in);

/// Normalised drag F = F_d / (3 pi mu_g d eps |w|) of Beetstra, van der Hoef & Kuipers (2007), AIChE J.
/// 53:489, Eq. 13, for solids fraction phi = 1 - eps and Re = eps rho_g |w| d / mu_g.
double beetstra_normalised_drag(double eps, double re);

/// Beetstra et al. (2007): beta = 18 mu_g eps (1 - eps) y F(eps, <Re>) / d_p^2 with y = d_p / d_mean and <Re>
/// built on d_mean; y = 1 gives the monodisperse law.
double beta_beetstra(const DragInput& in);

/// Normalised total force F = F_t / (3 pi mu_g d eps |w|) of Koch & Hill (2001), Annu. Rev. Fluid Mech. 33:619
/// (fit of Hill, Koch & Ladd 2001, J. Fluid Mech. 448:243): F0(phi) + F3(phi) Re / 2, Re = eps rho_g |w| d / mu_g.
double koch_hill_normalised_force(double eps, double re);

/// Koch & Hill (2001): beta = 18 mu_g eps^2 (1 - eps) F / d_p^2.
double beta_koch_hill(const DragInput& in);

/// A law with its Ergun/Wen-Yu join, as configured.
struct DragModel {
  DragLaw law = DragLaw::ErgunWenYu;
  DragSwitch blend = DragSwitch::Sharp;  ///< used by ErgunWenYu and Gidaspow only
};

/// Each law as a type, so that a particle or cell loop is compiled once per law and the choice is made once,
/// outside it (with_drag_law).
struct ErgunWenYuSharpLaw {
  static double beta(const DragInput& in) { return beta_ergun_wen_yu(in, DragSwitch::Sharp); }
};
struct ErgunWenYuSmoothLaw {
  static double beta(const DragInput& in) { return beta_ergun_wen_yu(in, DragSwitch::Smooth); }
};
struct GidaspowSharpLaw {
  static double beta(const DragInput& in) { return beta_gidaspow(in, DragSwitch::Sharp); }
};
struct GidaspowSmoothLaw {
  static double beta(const DragInput& in) { return beta_gidaspow(in, DragSwitch::Smooth); }
};
struct DiFeliceLaw {
  static double beta(const DragInput& in) { return beta_di_felice(in); }
};
struct BeetstraLaw {
  static double beta(const DragInput& in) { return beta_beetstra(in); }
};
struct KochHillLaw {
  static double beta(const DragInput& in) { return beta_koch_hill(in); }
};

/// Calls f(Law{}) with the law type of `model`: the one run-time switch, taken before a loop.
template <class F>
decltype(auto) with_drag_law(const DragModel& model, F&& f) {
  const bool smooth = model.blend == DragSwitch::Smooth;
  switch (model.law) {
    case DragLaw::Gidaspow:
      if (smooth) return std::forward<F>(f)(GidaspowSmoothLaw{});
      return std::forward<F>(f)(GidaspowSharpLaw{});
    case DragLaw::DiFelice: return std::forward<F>(f)(DiFeliceLaw{});
    case DragLaw::Beetstra: return std::forward<F>(f)(BeetstraLaw{});
    case DragLaw::KochHill: return std::forward<F>(f)(KochHillLaw{});
    case DragLaw::ErgunWenYu: break;
  }
  if (smooth) return std::forward<F>(f)(ErgunWenYuSmoothLaw{});
  return std::forward<F>(f)(ErgunWenYuSharpLaw{});
}

/// A law's beta as a plain function, chosen once (for loops that are not hot enough to template).
using DragBetaFn = double (*)(const DragInput&);
DragBetaFn drag_beta_function(const DragModel& model);

/// beta of a law chosen at run time (for code outside the hot loops, and tests).
double drag_beta(const DragModel& model, const DragInput& in);

/// Frictional pressure gradient -dP/dy [Pa/m] of a fixed bed at superficial velocity U > 0 that `model` implies:
/// the interstitial slip is U / eps and the particles carry the whole gradient, so -dP/dy = beta U / eps^2.
double fixed_bed_pressure_gradient(const DragModel& model, double eps, double d_p, double rho_g, double mu_g,
                                   double u_superficial);

/// Minimum fluidisation velocity [m/s] that `model` implies: the U at which fixed_bed_pressure_gradient equals
/// the buoyant bed weight (1 - eps_mf)(rho_s - rho_g) g (bisection; the gradient grows with U for every law).
double minimum_fluidisation_velocity(const DragModel& model, double eps_mf, double d_p, double rho_s, double rho_g,
                                     double mu_g, double g = 9.81);

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
