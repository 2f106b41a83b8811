// [tfm]: the two-fluid model's section into CaseConfig::tfm (tfm::TfmConfig, tfm/tfm_config.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "config/case_check.hpp"
#include "config/case_sections.hpp"
#include "core/error.hpp"

namespace fluidbed {

namespace case_sections {

void read_tfm(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  tfm::TfmConfig& t = c.tfm;
  t.domain = c.domain;
  if (std::abs(c.grid.dx - c.grid.dy) > 1e-12 * c.grid.dx) {
    r.fail("grid.cell_height", "the two-fluid model needs square cells (cell_height = cell_width)");
  }
  if (c.domain.dimension == 3 && std::abs(c.grid.dx - c.grid.dz) > 1e-12 * c.grid.dx) {
    r.fail("grid.cell_depth", "the two-fluid model needs cubic cells in 3D (cell_depth = cell_width)");
  }
  t.cell_size = c.grid.dx;
  t.rho_g = c.gas.rho_g;
  t.mu_g = c.gas.mu_g;
  t.boundary = c.gas.boundary;
  t.drag_law = c.coupling.drag_law;
  t.pressure_solver = c.gas.pressure_solver;
  t.drag_switch = c.coupling.drag_switch;
  t.d_p = r.number("tfm.particle_diameter", 0.004, "m", "particle diameter d_p", R::positive());
  t.rho_s = r.number("tfm.particle_density", 2700.0, "kg/m^3", "particle density rho_s", R::positive());
  check_particle_plausible(r, "tfm.particle_diameter", t.d_p, "tfm.particle_density", t.rho_s, c.domain, c.grid);
  if (!(t.rho_s > t.rho_g)) {
    r.fail("tfm.particle_density", fmt::format("solids of {} kg/m^3 are not heavier than the gas ({} kg/m^3): they "
                                               "do not form a bed", t.rho_s, t.rho_g));
  }
  if (c.gas.viscous != ViscousStress::Off) {
    r.fail("gas.viscous_stress", "the two-fluid model's gas has no viscous stress (Eq. 12 of the paper); only \"off\"");
  }
  t.e = r.number("tfm.restitution", 0.9, "", "restitution e of the kinetic theory (Eqs. 23-25)", R::Range{0.0, 1.0, true, false});
  t.phi_deg = r.number("tfm.friction_angle", 40.0, "deg", "angle of internal friction phi (Eq. 21)", R::Range{0.0, 90.0, true, true});
  t.eps_initial = r.number("tfm.eps_initial", 0.431, "", "voidage of the initial bed (Table 1)", R::Range{0.0, 1.0, true, true});
  t.packed_height = r.number("tfm.packed_height", 0.54, "m", "height of the initial bed", R::positive());
  if (t.packed_height > c.domain.height) r.fail("tfm.packed_height", "the bed is taller than the domain");
  t.eps_star = r.number("tfm.eps_star", 0.43, "", "compaction voidage eps* (Eq. 20)", R::Range{0.0, 1.0, true, true});
  const std::string rh = r.string("tfm.rheology", "kinetic_theory", "solids rheology: kinetic theory with the "
                                  "frictional regime (Eqs. 21-26), constant viscosity, inviscid, or the Bingham "
                                  "plastic of the paper's closing remarks (the last three with Eq. 20)",
                                  {"kinetic_theory", "constant_viscosity", "inviscid", "bingham"});
  t.rheology = rh == "inviscid"             ? tfm::SolidsRheology::Inviscid
               : rh == "constant_viscosity" ? tfm::SolidsRheology::ConstantViscosity
               : rh == "bingham"            ? tfm::SolidsRheology::Bingham
                                            : tfm::SolidsRheology::KineticTheory;
  if (t.rheology == tfm::SolidsRheology::KineticTheory && t.e >= 1.0) {
    r.fail("tfm.restitution", "e = 1 has no granular temperature in the kinetic theory: its algebraic balance of "
                              "shear production against collisional dissipation (~ 1 - e^2, Eqs. 25-26) has no "
                              "finite solution for elastic particles; use e < 1 (the paper: 0.9)");
  }
  if (t.rheology == tfm::SolidsRheology::KineticTheory && t.e > 0.95) {
    c.notes.push_back(fmt::format("tfm.restitution = {:g} is nearly elastic: the collisional dissipation (~ 1 - e^2) is "
                                  "small and the granular temperature may run away (the paper's case runs at 0.97 "
                                  "and stops at 0.12 s at 0.99); the run stops with a diagnosis if it does", t.e));
  }
  t.mu_s_constant = r.number("tfm.solids_viscosity", 0.5, "Pa s", "solids viscosity of the constant-viscosity rheology, "
                             "the plastic viscosity of the Bingham one (the paper gives no value)", R::positive());
  const std::string yield = r.string("tfm.yield", "given", "Bingham rheology: the yield stress as given "
                                     "(tfm.yield_stress) or Mohr-Coulomb's P_s sin(phi) from the Eq. 20 solids "
                                     "pressure", {"given", "mohr_coulomb"});
  t.yield = yield == "mohr_coulomb" ? tfm::YieldStress::MohrCoulomb : tfm::YieldStress::Given;
  t.yield_stress = r.number("tfm.yield_stress", 10.0, "Pa", "Bingham rheology: the yield stress in the bed "
                            "(tfm.yield = \"given\"; the paper gives no value)", R::non_negative());
  t.yield_regularisation = r.number("tfm.yield_regularisation", 100.0, "s", "Bingham rheology: Papanastasiou's m "
                                    "(mu = mu_p + tau_y (1 - exp(-m shear rate)) / shear rate)", R::positive());
  if (t.rheology != tfm::SolidsRheology::Bingham) {
    for (const char* key : {"tfm.yield", "tfm.yield_stress", "tfm.yield_regularisation"}) {
      if (r.has(key)) r.fail(key, "belongs to tfm.rheology = \"bingham\"");
    }
  }
  const std::string fm = r.string("tfm.frictional_model", "schaeffer",
                                  "kinetic theory's dense-bed closure: the paper's Schaeffer regime alone at or below "
                                  "eps* (Eqs. 21-22), or the Johnson-Jackson frictional pressure added to the kinetic "
                                  "theory with Schaeffer's viscosity or Srivastava-Sundaresan's (docs/model-tfm.md)",
                                  {"schaeffer", "johnson_jackson", "srivastava_sundaresan"});
  t.frictional = fm == "johnson_jackson"         ? tfm::FrictionalModel::JohnsonJackson
                 : fm == "srivastava_sundaresan" ? tfm::FrictionalModel::SrivastavaSundaresan
                                                 : tfm::FrictionalModel::Schaeffer;
  t.friction.eps_s_min = r.number("tfm.frictional_onset", 0.5, "", "solids fraction above which the Johnson-Jackson "
                                  "frictional pressure acts", R::Range{0.0, 1.0, false, false});
  t.friction.eps_s_max = r.number("tfm.frictional_packing_limit", 0.63, "", "solids fraction at which the "
                                  "Johnson-Jackson frictional pressure diverges", R::Range{0.0, 1.0, false, false});
  const bool jj = t.rheology == tfm::SolidsRheology::KineticTheory && t.frictional != tfm::FrictionalModel::Schaeffer;
  for (const char* key : {"tfm.frictional_onset", "tfm.frictional_packing_limit"}) {
    if (r.has(key) && !jj)
      r.fail(key, "belongs to tfm.frictional_model = \"johnson_jackson\" or \"srivastava_sundaresan\"");
  }
  if (r.has("tfm.frictional_model") && t.rheology != tfm::SolidsRheology::KineticTheory) {
    r.fail("tfm.frictional_model", "belongs to tfm.rheology = \"kinetic_theory\"");
  }
  t.mu_s_max = r.number("tfm.max_solids_viscosity", 100.0, "Pa s", "cap on the frictional viscosity", R::positive());
  t.modulus.a = r.number("tfm.modulus_a", 1.0, "Pa", "A of G = A exp(B (eps* - eps)) (Eq. 20)", R::positive());
  t.modulus.b = r.number("tfm.modulus_b", 600.0, "", "B of G = A exp(B (eps* - eps)) (Eq. 20)", R::positive());
  const std::string lim = r.string("tfm.limiter", "superbee", "flux limiter of the convection (the paper: superbee)",
                                   {"superbee", "van_leer", "minmod", "upwind"});
  t.limiter = lim == "upwind" ? tfm::Limiter::Upwind
              : lim == "minmod" ? tfm::Limiter::Minmod : lim == "van_leer" ? tfm::Limiter::VanLeer : tfm::Limiter::Superbee;
  t.cfl = r.number("tfm.cfl", 0.5, "", "Courant number of the adaptive time step", R::Range{0.0, 1.0, true, false});
  t.dt_max = r.number("tfm.dt_max", 1e-3, "s", "largest time step", R::positive());
  t.dt_min = r.number("tfm.dt_min", 1e-8, "s", "the run fails below this time step", R::positive());
  t.max_compaction = r.number("tfm.max_compaction", tfm::default_max_compaction(t.rheology), "",
                              "compaction below eps* that the packing limiter allows, eps >= eps* - max_compaction "
                              "exactly (default 0.015 with kinetic_theory, 0.03 with the Eq. 20 rheologies)",
                              R::Range{0.0, t.eps_star, false, true});
  t.solids_no_slip_walls = r.boolean("tfm.solids_no_slip_walls", false, "solids stick to the side walls");
  const std::size_t dim = static_cast<std::size_t>(c.domain.dimension);
  const std::vector<double> slide = r.numbers("tfm.sliding_wall_velocity", std::vector<double>(dim, 0.0), "m/s",
                                              "velocity of the side wall at the high end of z (3D) or x (2D), "
                                              "tangential to it: the solids stick to it and are sheared (a shear "
                                              "cell, plane Couette flow); needs tfm.solids_no_slip_walls", dim);
  for (std::size_t a = 0; a < dim; ++a) t.sliding_wall[a] = slide[a];
  t.eps_noise = r.number("tfm.eps_noise", 0.0, "", "amplitude of the seeded (case.seed) initial voidage noise of the "
                         "bed: eps + a (2u - 1), kept in [eps*, 1]", R::Range{0.0, 0.5, false, true});
  t.seed = c.seed;
  try {
    tfm::validate(t);
  } catch (const Error& e) {
    throw_input_error(fmt::format("{}: [tfm]: {}", r.file_name(), e.what()));
  }
}

}  // namespace case_sections
}  // namespace fluidbed
