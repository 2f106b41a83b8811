#include "closures/drag.hpp"

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

double beta_gidaspow(const DragInput& in, DragSwitch mode) {
  const double eps_s = 1.0 - in.eps;
  const double slip = std::abs(in.slip);
  // Gidaspow (1994) Eq. 5.41: the Ergun branch, identical to the paper's.
  const double ergun = beta_ergun(in);
  // Gidaspow (1994) Eqs. 5.42-5.43: Wen-Yu with eps^-2.65, C_D = 24/Re (1 + 0.15 Re^0.687) below Re = 1000, 0.44
  // above; at zero slip C_D |w| -> 24 mu / (eps rho d) keeps beta finite.
  const double re = particle_reynolds(in);
  const double cd_slip = re <= 0.0      ? 24.0 * in.mu_g / (in.eps * in.rho_g * in.d_p)
                         : re < 1000.0 ? 24.0 * (1.0 + 0.15 * std::pow(re, 0.687)) / re * slip
                                       : 0.44 * slip;
  const double wen_yu = 0.75 * cd_slip * in.eps * eps_s * in.rho_g / in.d_p * std::pow(in.eps, -2.65);
  if (mode == DragSwitch::Smooth) {
    // Huilin & Gidaspow (2003), the same weight as for Eq. 13.
    const double phi = 0.5 + std::atan(262.5 * (eps_s - (1.0 - kErgunWenYuSwitch))) / std::numbers::pi;
    return phi * ergun + (1.0 - phi) * wen_yu;
  }
  return in.eps <= kErgunWenYuSwitch ? ergun : wen_yu;
}

double beta_di_felice(const DragInput& in) {
  const double re = particle_reynolds(in);
  // Di Felice (1994), Eq. 12: chi -> 3.7 as Re -> 0 (log10 Re -> -inf).
  const double chi = re > 0.0 ? 3.7 - 0.65 * std::exp(-0.5 * std::pow(1.5 - std::log10(re), 2)) : 3.7;
  // C_D |w| = (0.63 + 4.8/sqrt(Re))^2 |w| written as (0.63 sqrt(Re) + 4.8)^2 mu / (eps rho d): finite at zero slip.
  const double a = 0.63 * std::sqrt(re) + 4.8;
  // beta = K_p (1 - eps) / V_p with K_p = (pi/8) C_D rho d^2 eps^(2 - chi) |w| (Di Felice 1994, Eq. 10).
  return 0.75 * a * a * in.mu_g * (1.0 - in.eps) / (in.d_p * in.d_p) * std::pow(in.eps, 1.0 - chi);
}

double beetstra_normalised_drag(double eps, double re) {
  const double phi = 1.0 - eps;
  // Beetstra, van der Hoef & Kuipers (2007), Eq. 13: Stokes part (van der Hoef et al. 2005) plus inertial part.
  const double stokes = 10.0 * phi / (eps * eps) + eps * eps * (1.0 + 1.5 * std::sqrt(phi));
  if (re <= 0.0) return stokes;
  const double inertial = 0.413 * re / (24.0 * eps * eps) * (1.0 / eps + 3.0 * phi * eps + 8.4 * std::pow(re, -0.343)) /
                          (1.0 + std::pow(10.0, 3.0 * phi) * std::pow(re, -0.5 * (1.0 + 4.0 * phi)));
  return stokes + inertial;
}

double beta_beetstra(const DragInput& in) {
  const double d_mean = in.d_mean > 0.0 ? in.d_mean : in.d_p;
  const double y = in.d_p / d_mean;
  // Beetstra et al. (2007) polydisperse correction: F_i / F = eps y + phi y^2 for the total force; with the mean
  // pressure gradient shared by volume (V_i grad P), the drag part is F_i / F = y (docs/model.md). F and Re on d_mean.
  const double re = in.eps * in.rho_g * std::abs(in.slip) * d_mean / in.mu_g;
  return 18.0 * in.mu_g * in.eps * (1.0 - in.eps) * y * beetstra_normalised_drag(in.eps, re) / (in.d_p * in.d_p);
}

double koch_hill_normalised_force(double eps, double re) {
  const double phi = 1.0 - eps;
  // Hill, Koch & Ladd (2001) as summarised by Koch & Hill (2001): F0 matches Carman-Kozeny above phi = 0.4.
  double f0 = 10.0 * phi / (eps * eps * eps);
  if (phi < 0.4) {
    const double phi_log_phi = phi > 0.0 ? phi * std::log(phi) : 0.0;
    f0 = (1.0 + 3.0 * std::sqrt(0.5 * phi) + 135.0 / 64.0 * phi_log_phi + 16.14 * phi) /
         (1.0 + 0.681 * phi - 8.48 * phi * phi + 8.16 * phi * phi * phi);
  }
  const double f3 = 0.0673 + 0.212 * phi + 0.0232 / std::pow(eps, 5);
  return f0 + 0.5 * f3 * re;
}

double beta_koch_hill(const DragInput& in) {
  // Koch & Hill (2001): F is the total force per particle over Stokes', hence eps^2 (one eps more than Beetstra).
  return 18.0 * in.mu_g * in.eps * in.eps * (1.0 - in.eps) * koch_hill_normalised_force(in.eps, particle_reynolds(in)) /
         (in.d_p * in.d_p);
}

DragBetaFn drag_beta_function(const DragModel& model) {
  return with_drag_law(model, [](auto law) -> DragBetaFn { return &decltype(law)::beta; });
}

double drag_beta(const DragModel& model, const DragInput& in) {
  return with_drag_law(model, [&in](auto law) { return decltype(law)::beta(in); });
}

double fixed_bed_pressure_gradient(const DragModel& model, double eps, double d_p, double rho_g, double mu_g,
                                   double u_superficial) {
  const DragInput in{eps, d_p, rho_g, mu_g, u_superficial / eps};
  // Gas momentum at steady state: eps (-dP/dy) = beta w, w = U / eps.
  return drag_beta(model, in) * u_superficial / (eps * eps);
}

double minimum_fluidisation_velocity(const DragModel& model, double eps_mf, double d_p, double rho_s, double rho_g,
                                     double mu_g, double g) {
  if (!(eps_mf > 0.0 && eps_mf < 1.0 && d_p > 0.0 && rho_s > rho_g && rho_g > 0.0 && mu_g > 0.0 && g > 0.0)) {
    throw_input_error("minimum_fluidisation_velocity: need 0 < eps_mf < 1, d_p > 0, rho_s > rho_g > 0, mu_g > 0, g > 0");
  }
  const double weight = (1.0 - eps_mf) * (rho_s - rho_g) * g;
  const auto residual = [&](double u) {
    return fixed_bed_pressure_gradient(model, eps_mf, d_p, rho_g, mu_g, u) - weight;
  };
  double lo = 0.0;
  double hi = 1e-3;
  while (residual(hi) < 0.0) {
    lo = hi;
    hi *= 2.0;
  }
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
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
