#pragma once
// Solids-phase stress closures of the two-fluid model (paper Eqs. 20-26), as small pure functions.
// Voidage eps is the gas volume fraction; eps_s = 1 - eps.
#include "core/sym_tensor.hpp"

namespace fluidbed::tfm {

/// Particle properties the kinetic theory needs.
struct GranularMaterial {
  double d_p = 0.004;       ///< particle diameter [m]
  double rho_s = 2700.0;    ///< particle density [kg/m^3]
  double e = 0.9;           ///< coefficient of restitution [-]
};

/// Strain-rate tensor D = (grad v + grad v^T) / 2 [1/s]; in 2D the out-of-plane components are zero.
template <int Dim>
using StrainRate = SymTensor<Dim>;
using fluidbed::double_dot;
using fluidbed::trace;

/// Second invariant used by Schaeffer's frictional viscosity (Eq. 21):
/// I_2D = [(Dxx - Dyy)^2 + (Dyy - Dzz)^2 + (Dzz - Dxx)^2] / 6 + Dxy^2 + Dxz^2 + Dyz^2; in 2D Dzz = Dxz = Dyz = 0
/// (plane strain), which is the paper's [(Dxx - Dyy)^2 + Dyy^2 + Dxx^2] / 6 + Dxy^2 to the last bit.
template <int Dim>
double second_invariant(const StrainRate<Dim>& d);

/// Eq. 26 exactly as printed: g0 = (1/eps) (1 + 1.5 eps_s / eps), eps the voidage.
double radial_distribution(double eps);

/// Eq. 25, K1: bulk-viscosity coefficient [kg/m^2].
double kt_k1(const GranularMaterial& m, double eps_s, double g0);
/// Eq. 25, K2: shear-viscosity coefficient [kg/m^2].
double kt_k2(const GranularMaterial& m, double eps_s, double g0);
/// Collisional dissipation coefficient K4 of the algebraic energy balance: gamma = K4 eps_s^2 Theta^1.5
/// (Syamlal, Rogers & O'Brien 1993, MFIX Theory Guide, DOE/METC-94/1004) [kg/m^4].
double kt_k4(const GranularMaterial& m, double g0);

/// Eq. 23: kinetic/collisional solids pressure P_s^c = 2 (1 + e) rho_s g0 eps_s^2 Theta [Pa].
double kt_pressure(const GranularMaterial& m, double eps, double theta);
/// Eq. 24: mu_s^c = K2 eps_s sqrt(Theta) [Pa s].
double kt_shear_viscosity(const GranularMaterial& m, double eps, double theta);
/// Eq. 24: lambda_s^c = K1 eps_s sqrt(Theta) [Pa s].
double kt_bulk_viscosity(const GranularMaterial& m, double eps, double theta);

/// Granular temperature [m^2/s^2] from the algebraic granular energy balance (production by the
/// kinetic-theory stresses of Eqs. 23-25 equals collisional dissipation; convection and conduction dropped),
/// the form of Syamlal, Rogers & O'Brien (1993, MFIX Theory Guide). Zero for eps_s <= 0.
template <int Dim>
double algebraic_granular_temperature(const GranularMaterial& m, double eps, const StrainRate<Dim>& d);

/// Eq. 22: P* = 1e24 (eps* - eps)^10 Pa for eps < eps*, else 0.
double frictional_p_star(double eps, double eps_star);
/// Eq. 21: P_s^f = (1 - eps) P*.
double frictional_pressure(double eps, double eps_star);
/// Eq. 21: mu_s^f = P* sin(phi) / (2 sqrt(I_2D)), capped at mu_max because sqrt(I_2D) -> 0 in a bed at rest
/// (frictional_viscosity_on with P* and no regularisation).
template <int Dim>
double frictional_viscosity(double eps, double eps_star, double phi_rad, const StrainRate<Dim>& d, double mu_max);

/// The frictional normal stress of Johnson & Jackson (J. Fluid Mech. 176 (1987) 67, with the constants of Johnson,
/// Jackson & Pfeffer, J. Fluid Mech. 210 (1990) 501), the dense-bed closure that MFIX, OpenFOAM and Fluent add to
/// the kinetic theory: P_f = Fr (eps_s - eps_s,min)^n / (eps_s,max - eps_s)^p for eps_s > eps_s,min.
struct FrictionalParams {
  double fr = 0.05;          ///< Fr [Pa]
  double n = 2.0;            ///< exponent of the excess over the onset
  double p = 5.0;            ///< exponent of the distance to the packing limit
  double eps_s_min = 0.5;    ///< solids fraction at which friction sets in
  double eps_s_max = 0.63;   ///< random close packing, where P_f diverges
};
/// P_f [Pa] at solids fraction eps_s (0 at or below the onset); eps_s must stay below eps_s_max.
double jj_frictional_pressure(const FrictionalParams& f, double eps_s);
/// Frictional viscosity on a frictional pressure p_f [Pa]: sqrt(2) p_f sin(phi) / (2 sqrt(S:S + theta_d2)), S the
/// deviatoric strain rate (S:S = 2 I_2D), capped at mu_max. theta_d2 = Theta / d_p^2 [1/s^2] is the
/// regularisation of Srivastava & Sundaresan (Powder Technol. 129 (2003) 72, their critical-state pressure, the
/// dilatancy factor left out); theta_d2 = 0 is Schaeffer's form, p_f sin(phi) / (2 sqrt(I_2D)), as in Eq. 21.
template <int Dim>
double frictional_viscosity_on(double p_f, double phi_rad, const StrainRate<Dim>& d, double theta_d2, double mu_max);

/// Papanastasiou's regularised Bingham viscosity (J. Rheol. 31 (1987) 385): mu = mu_p + tau_y (1 - exp(-m g)) / g
/// [Pa s], g the shear rate [1/s] (2 sqrt(I_2D): the simple shear's du/dy), m [s] the regularisation; the stress
/// mu g is tau_y + mu_p g up to tau_y exp(-m g), and at g = 0 the viscosity is its limit mu_p + tau_y m.
double bingham_viscosity(double mu_p, double tau_y, double m, double g);

/// Parameters of the solids-pressure modulus of Eq. 20 in the exponential form the paper cites,
/// G = A exp(B (eps* - eps)).
struct ModulusParams {
  double a = 1.0;     ///< normalising factor A [Pa]
  double b = 600.0;   ///< compaction modulus B [-]
};
/// Eq. 20: G(eps) = A exp(B (eps* - eps)) [Pa], so that grad P_s = -G grad eps = G grad eps_s.
double modulus_g(const ModulusParams& p, double eps, double eps_star);
/// Solids pressure whose gradient is Eq. 20: P_s = (A / B) exp(B (eps* - eps)) [Pa].
double modulus_pressure(const ModulusParams& p, double eps, double eps_star);
/// Voidage at which modulus_pressure equals p_s: the compaction this model needs to carry a load p_s.
double modulus_voidage_for_pressure(const ModulusParams& p, double p_s, double eps_star);

}  // namespace fluidbed::tfm
