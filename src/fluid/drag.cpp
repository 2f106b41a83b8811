#include "fluid/drag.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"

namespace fluidbed {

double drag_coefficient(double re) {
  if (re <= 0.0) return std::numeric_limits<double>::infinity();
  // Eq. 14
  if (re < 1000.0) return 24.0 * (1.0 + 0.15 * std::pow(re, 0.687)) / re;
  return 0.43;
}

double particle_reynolds(const DragInput& in) { return in.eps * in.rho_g * std::abs(in.slip) * in.d_p / in.mu_g; }

double beta_ergun(const DragInput& in) {
  const double eps_s = 1.0 - in.eps;
  // Eq. 13, first branch (Ergun 1952 written per unit volume of mixture, Gidaspow 1994)
  return 150.0 * eps_s * eps_s * in.mu_g / (in.eps * in.d_p * in.d_p) + 1.75 * eps_s * in.rho_g * std::abs(in.slip) / in.d_p;
}

double beta_wen_yu(const DragInput& in) {
  const double slip = std::abs(in.slip);
  if (slip == 0.0) {
    // C_D |slip| -> 24 mu / (eps rho d) as slip -> 0: the Stokes limit keeps beta finite and continuous.
    return 18.0 * in.mu_g * (1.0 - in.eps) / (in.d_p * in.d_p) * std::pow(in.eps, -2.7);
  }
  // Eq. 13, second branch (Wen & Yu 1966)
  return 0.75 * drag_coefficient(particle_reynolds(in)) * in.eps * (1.0 - in.eps) / in.d_p * in.rho_g * slip *
         std::pow(in.eps, -2.7);
}

double beta_ergun_wen_yu(const DragInput& in, DragSwitch mode) {
  if (mode == DragSwitch::Smooth) {
    // Huilin & Gidaspow (2003): weight phi -> 1 (Ergun) in dense regions, -> 0 (Wen-Yu) in dilute ones.
    const double phi = 0.5 + std::atan(262.5 * ((1.0 - in.eps) - (1.0 - kErgunWenYuSwitch))) / std::numbers::pi;
    return phi * beta_ergun(in) + (1.0 - phi) * beta_wen_yu(in);
  }
  return in.eps <= kErgunWenYuSwitch ? beta_ergun(in) : beta_wen_yu(in);
}

double terminal_velocity(double d_p, double rho_p, double rho_g, double mu_g, double g) {
  if (!(d_p > 0.0 && rho_p > rho_g && rho_g > 0.0 && mu_g > 0.0 && g > 0.0)) {
    throw_input_error("terminal_velocity: need d_p > 0, rho_p > rho_g > 0, mu_g > 0, g > 0");
  }
  const double weight = d_p * (rho_p - rho_g) * g;
  // Force balance per projected area: (3/4) C_D(Re) rho_g u^2 = d_p (rho_p - rho_g) g. C_D u^2 grows with u
  // on each branch of Eq. 14, so bisection on the residual finds the root.
  const auto residual = [&](double u) {
    return 0.75 * drag_coefficient(rho_g * u * d_p / mu_g) * rho_g * u * u - weight;
  };
  double lo = 0.0;
  double hi = std::sqrt(weight / (0.75 * 0.43 * rho_g)) * 4.0 + 1.0;
  while (residual(hi) < 0.0) hi *= 2.0;
  for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double ergun_pressure_gradient(double eps, double d_p, double rho_g, double mu_g, double u_superficial) {
  const double eps_s = 1.0 - eps;
  const double eps3 = eps * eps * eps;
  // Ergun (1952)
  return 150.0 * eps_s * eps_s * mu_g * u_superficial / (eps3 * d_p * d_p) +
         1.75 * eps_s * rho_g * u_superficial * std::abs(u_superficial) / (eps3 * d_p);
}

double ergun_minimum_fluidisation_velocity(double eps_mf, double d_p, double rho_s, double rho_g, double mu_g,
                                           double g) {
  if (!(eps_mf > 0.0 && eps_mf < 1.0 && d_p > 0.0 && rho_s > rho_g && mu_g > 0.0 && g > 0.0)) {
    throw_input_error("ergun_minimum_fluidisation_velocity: need 0 < eps_mf < 1, d_p > 0, rho_s > rho_g, mu_g > 0");
  }
  const double eps_s = 1.0 - eps_mf;
  const double eps3 = eps_mf * eps_mf * eps_mf;
  const double a = 1.75 * eps_s * rho_g / (eps3 * d_p);
  const double b = 150.0 * eps_s * eps_s * mu_g / (eps3 * d_p * d_p);
  const double c = eps_s * (rho_s - rho_g) * g;
  // a U^2 + b U = c; the rationalised root avoids cancellation when b^2 >> a c.
  return 2.0 * c / (b + std::sqrt(b * b + 4.0 * a * c));
}

}  // namespace fluidbed
