#pragma once
// `fluidbed check`: derived quantities of a case, so a user sees what the numbers imply before running; the
// loader takes its derived defaults (DEM time step, U_mf) and its plausibility rules from here too.
#include <optional>
#include <string>
#include <vector>

#include "config/case_config.hpp"
#include "config/case_reader.hpp"

namespace fluidbed {

std::string describe_case(const CaseConfig& c);

/// Normal-mode contact duration t_c of the stiffest contact of the case (the shortest over species pairs and
/// particle-wall contacts), Eq. 8 damping from the contact's restitution on its reduced mass.
struct StiffestContact {
  double t_c = 0.0;  ///< s
  int a = 0;         ///< species
  int b = -1;        ///< partner species, or -1 for a wall
};
StiffestContact stiffest_contact(const DemConfig& dem);

/// A contact of species a with species b (b < 0: a wall) seen as a linear spring-dashpot, for the time-step rules:
/// the linear law's own k_n, k_t and Eq. 8 dashpot; for Hertz (Hertz 1882) the tangent stiffness 2 E* a_max at
/// the largest overlap of an impact at contact.impact_speed, Mindlin's 8 G* a_max (or k_n times the ratio), the
/// Tsuji dashpot there, and the Hertz contact duration (Johnson 1985), which shrinks as v^(-1/5).
struct EquivalentContact {
  double m_eff;  ///< kg
  double k_n;    ///< N/m
  double k_t;    ///< N/m
  double eta_n;  ///< kg/s
  double t_c;    ///< s
};
EquivalentContact equivalent_contact(const DemConfig& dem, int a, int b);

/// Time steps per contact of the default DEM time step: dt = t_c / 20 (at most, see default_dem_time_step).
inline constexpr double kStepsPerContact = 20.0;
/// The DEM time step used when dem.time_step is not given: t_c / kStepsPerContact of the stiffest contact (and
/// never above the stability limit), rounded down to 1, 1.25, 2, 2.5, 4, 5 or 8 x 10^n so that decimal output
/// intervals are whole numbers of steps.
double default_dem_time_step(const DemConfig& dem);

/// Mixture means of a bed of species with number fractions `fraction`: the Sauter diameter d32 = sum f d^3 /
/// sum f d^2 (the diameter with the mixture's volume-to-surface ratio, which sets its Ergun pressure drop) and
/// the volume-weighted density.
struct BedMixture {
  double d32 = 0.0;  ///< m
  double rho = 0.0;  ///< kg/m^3
};
BedMixture bed_mixture(const DemConfig& dem, const std::vector<double>& fraction);

/// The particle sizes of each species as `check` reports them: for a random placement the count it places and the
/// requested distribution (mean, Sauter d32 = <d^3>/<d^2>, cut-offs); for a particle file its rows' sizes.
struct SpeciesSizes {
  std::string what;        ///< "fixed", "<law> (requested)", "sizes of the file" or "one size"
  std::size_t count = 0;
  double mean = 0.0, d32 = 0.0, d_min = 0.0, d_max = 0.0;  ///< m
  bool from_file = false;
};
std::vector<SpeciesSizes> species_sizes(const CaseConfig& c);

/// Voidage at minimum fluidisation of the discrete model's bed (the paper's eps_mf, about 0.43).
inline constexpr double kDemEpsMf = 0.43;
/// Ergun U_mf of the case's bed (DEM: the mixture at kDemEpsMf; TFM: the solids at tfm.eps_initial), the default of
/// bubble.u_mf; empty where the bed has none (no downward gravity, solids not heavier than the gas).
std::optional<double> bed_minimum_fluidisation_velocity(const CaseConfig& c);
/// What bed_minimum_fluidisation_velocity is, in words ("Ergun U_mf" for the paper's law).
std::string bed_minimum_fluidisation_label(const CaseConfig& c);

/// Plausibility of the domain (width, height, and depth in 3D): larger than any bed is an error naming the likely
/// unit slip.
void check_domain_plausible(const CaseReader& r, const DomainConfig& domain);
/// Plausibility of a particle diameter and density (either model): a value that cannot describe a bed particle
/// is a bad-input error saying what looks wrong and the likely unit slip. `cell` is the gas cell when particles
/// are averaged over cells (CFD-DEM, TFM), else empty.
void check_particle_plausible(const CaseReader& r, const std::string& diameter_key, double d,
                              const std::string& density_key, double rho, const DomainConfig& domain,
                              const std::optional<CaseGrid>& cell);
/// Plausibility of the gas: no fluid at all is an error; a liquid's value is a note.
void check_gas_plausible(const CaseReader& r, const GasConfig& g, std::vector<std::string>& notes);

}  // namespace fluidbed
