#include "tfm/solids_stress.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed::tfm {

namespace {
constexpr double sqrt_pi = 1.7724538509055160273;
}

template <int Dim>
double second_invariant(const StrainRate<Dim>& d) {
  const double xx = d.diag[0], yy = d.diag[1], zz = Dim == 3 ? d.diag[Dim - 1] : 0.0;
  double shear = d.off[0] * d.off[0];
  for (int k = 1; k < static_cast<int>(d.off.size()); ++k) shear += d.off[k] * d.off[k];
  return ((xx - yy) * (xx - yy) + (yy - zz) * (yy - zz) + (zz - xx) * (zz - xx)) / 6.0 + shear;
}

double radial_distribution(double eps) { return (1.0 / eps) * (1.0 + 1.5 * (1.0 - eps) / eps); }

double kt_k2(const GranularMaterial& m, double eps_s, double g0) {
  const double e = m.e;
  return 0.5 * m.d_p * m.rho_s *
         (sqrt_pi / (3.0 * (3.0 - e)) * (1.0 + 0.4 * (1.0 + e) * (3.0 * e - 1.0) * eps_s * g0) +
          8.0 * eps_s * g0 * (1.0 + e) / (5.0 * sqrt_pi));
}

double kt_k1(const GranularMaterial& m, double eps_s, double g0) {
  return 4.0 * m.d_p * m.rho_s * (1.0 + m.e) * eps_s * g0 / (3.0 * sqrt_pi) - 2.0 / 3.0 * kt_k2(m, eps_s, g0);
}

double kt_k4(const GranularMaterial& m, double g0) {
  return 12.0 * (1.0 - m.e * m.e) * m.rho_s * g0 / (m.d_p * sqrt_pi);
}

double kt_pressure(const GranularMaterial& m, double eps, double theta) {
  const double eps_s = 1.0 - eps;
  return 2.0 * (1.0 + m.e) * m.rho_s * radial_distribution(eps) * eps_s * eps_s * theta;
}

double kt_shear_viscosity(const GranularMaterial& m, double eps, double theta) {
  const double eps_s = 1.0 - eps;
  return kt_k2(m, eps_s, radial_distribution(eps)) * eps_s * std::sqrt(theta);
}

double kt_bulk_viscosity(const GranularMaterial& m, double eps, double theta) {
  const double eps_s = 1.0 - eps;
  return kt_k1(m, eps_s, radial_distribution(eps)) * eps_s * std::sqrt(theta);
}

template <int Dim>
double algebraic_granular_temperature(const GranularMaterial& m, double eps, const StrainRate<Dim>& d) {
  const double eps_s = 1.0 - eps;
  if (eps_s <= 0.0) return 0.0;
  const double g0 = radial_distribution(eps);
  // Balance for x = sqrt(Theta), after dividing by eps_s x:
  // K4 eps_s x^2 + c_p eps_s tr(D) x - [K1 tr(D)^2 + 2 K2 D:D] = 0, with c_p = 2 (1 + e) rho_s g0 (Eq. 23).
  const double c_p = 2.0 * (1.0 + m.e) * m.rho_s * g0;
  const double k4 = kt_k4(m, g0);
  const double tr = trace(d);
  const double source = kt_k1(m, eps_s, g0) * tr * tr + 2.0 * kt_k2(m, eps_s, g0) * double_dot(d);
  const double b = c_p * eps_s * tr;
  const double disc = b * b + 4.0 * k4 * eps_s * std::max(source, 0.0);
  const double x = (-b + std::sqrt(disc)) / (2.0 * k4 * eps_s);
  return x > 0.0 ? x * x : 0.0;
}

double frictional_p_star(double eps, double eps_star) {
  if (eps >= eps_star) return 0.0;
  // (eps* - eps)^10 by squaring: four products, within two ulp of pow and a tenth of its cost.
  const double x = eps_star - eps, x2 = x * x, x4 = x2 * x2;
  return 1e24 * ((x4 * x4) * x2);
}

double frictional_pressure(double eps, double eps_star) { return (1.0 - eps) * frictional_p_star(eps, eps_star); }

template <int Dim>
double frictional_viscosity_on(double p_f, double phi_rad, const StrainRate<Dim>& d, double theta_d2, double mu_max) {
  if (p_f <= 0.0) return 0.0;
  // sqrt(2) p_f sin(phi) / (2 sqrt(2 I_2D + theta_d2)), written so that theta_d2 = 0 is Eq. 21's expression bit for
  // bit (I_2D + 0 is I_2D).
  const double root = std::sqrt(second_invariant(d) + 0.5 * theta_d2);
  const double numerator = 0.5 * p_f * std::sin(phi_rad);
  // Written as a comparison so that a strain rate of exactly zero gives the cap, not a division by zero.
  if (numerator >= mu_max * root) return mu_max;
  return numerator / root;
}

template <int Dim>
double frictional_viscosity(double eps, double eps_star, double phi_rad, const StrainRate<Dim>& d, double mu_max) {
  return frictional_viscosity_on(frictional_p_star(eps, eps_star), phi_rad, d, 0.0, mu_max);
}

double jj_frictional_pressure(const FrictionalParams& f, double eps_s) {
  if (eps_s <= f.eps_s_min) return 0.0;
  return f.fr * std::pow(eps_s - f.eps_s_min, f.n) / std::pow(f.eps_s_max - eps_s, f.p);
}


double bingham_viscosity(double mu_p, double tau_y, double m, double g) {
  const double x = m * g;
  // Below 1e-8 the series 1 - x / 2 is exact to rounding, and expm1(-x) / g would lose its digits.
  if (x < 1e-8) return mu_p + tau_y * m * (1.0 - 0.5 * x);
  return mu_p + tau_y * -std::expm1(-x) / g;
}

double modulus_g(const ModulusParams& p, double eps, double eps_star) { return p.a * std::exp(p.b * (eps_star - eps)); }

double modulus_pressure(const ModulusParams& p, double eps, double eps_star) {
  return p.a / p.b * std::exp(p.b * (eps_star - eps));
}

double modulus_voidage_for_pressure(const ModulusParams& p, double p_s, double eps_star) {
  return eps_star - std::log(p_s * p.b / p.a) / p.b;
}

template double second_invariant<2>(const StrainRate<2>&);
template double second_invariant<3>(const StrainRate<3>&);
template double algebraic_granular_temperature<2>(const GranularMaterial&, double, const StrainRate<2>&);
template double algebraic_granular_temperature<3>(const GranularMaterial&, double, const StrainRate<3>&);
template double frictional_viscosity_on<2>(double, double, const StrainRate<2>&, double, double);
template double frictional_viscosity_on<3>(double, double, const StrainRate<3>&, double, double);
template double frictional_viscosity<2>(double, double, double, const StrainRate<2>&, double);
template double frictional_viscosity<3>(double, double, double, const StrainRate<3>&, double);

}  // namespace fluidbed::tfm
