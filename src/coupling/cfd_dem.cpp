#include "coupling/cfd_dem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include <fmt/format.h>

#include "coupling/voidage.hpp"
#include "core/error.hpp"
#include "closures/drag.hpp"
#include "parallel/exact_sum.hpp"

namespace fluidbed {

template <int Dim>
CfdDemSimulation<Dim>::CfdDemSimulation(DemSolver<Dim> dem, std::optional<GasSolver<Dim>> gas, CouplingConfig coupling)
    : dem_(std::move(dem)), gas_(std::move(gas)), coupling_(coupling) {
  depth_ = coupling_.depth > 0.0 ? coupling_.depth : largest_diameter();
  dem_.couple_to_fluid(gas_.has_value());  // without gas nothing writes the fluid arrays: the update skips them
  if (gas_) {
    const IndexBox<Dim>& box = gas_->grid().owned;
    for (Field<Dim>* f : {&eps_, &eps_gas_old_, &eps_gas_, &beta_}) *f = Field<Dim>(box, 0);
    for (int a = 0; a < Dim; ++a) {
      us_[a] = Field<Dim>(box, 0);
      us_gas_[a] = Field<Dim>(box, 0);
      ug_[a] = Field<Dim>(box, 0);
    }
  }
}

template <int Dim>
void CfdDemSimulation<Dim>::clip_voidage() {
  const std::vector<double>& e = eps_.data();
  std::vector<double>& out = eps_gas_.data();
  for (std::size_t c = 0; c < e.size(); ++c) out[c] = std::clamp(e[c], coupling_.eps_min, 1.0);
}

template <int Dim>
std::span<const std::uint32_t> CfdDemSimulation<Dim>::id_order() {
  return dem_.canonical_order();
}

template <int Dim>
void CfdDemSimulation<Dim>::share_owned_cells(std::span<Field<Dim>* const> fields) const {
  const BlockLayout<Dim>* layout = dem_.layout();
  if (layout == nullptr) return;
  const Comm& comm = dem_.comm();
  Bytes mine;
  for (int b = 0; b < layout->blocks(); ++b) {
    if (layout->owner(b) != comm.rank()) continue;
    for_each(layout->cells_of(b), [&](const Index<Dim>& c) {
      for (Field<Dim>* f : fields) pack(mine, (*f)[c]);
    });
  }
  const std::vector<Bytes> all = comm.allgather(mine);
  std::vector<Unpacker> from;
  for (const Bytes& b : all) from.emplace_back(b);
  for (int b = 0; b < layout->blocks(); ++b) {
    Unpacker& u = from[static_cast<std::size_t>(layout->owner(b))];
    for_each(layout->cells_of(b), [&](const Index<Dim>& c) {
      for (Field<Dim>* f : fields) (*f)[c] = u.get<double>();
    });
  }
}

template <int Dim>
void CfdDemSimulation<Dim>::deposit() {
  const Grid<Dim>& g = gas_->grid();
  // One set of kernel weights per gas step serves the deposition here and the interpolation to the particles in
  // update_particle_forces (the particles do not move in between).
  particle_cell_weights(dem_.particles(), g, eps_, coupling_.voidage, weights_);
  // Voidage, mean solids velocity and the interphase coefficient as the gas sees it in one pass: the particles'
  // drag coefficients K_p = V_p beta / (1 - eps) summed with the deposition kernel per unit cell volume (Eq. 12's
  // beta) and the K-weighted mean particle velocity, so that the gas receives what the particles feel (Newton's
  // third law). On several ranks each computes the cells of its blocks (its particles and the ghosts reach them
  // all) and shares them.
  deposition_.deposit(dem_.particles(), weights_, g, depth_, DepositedFields<Dim>{&eps_, &us_, &beta_, &us_gas_},
                      id_order());
  if (dem_.distributed()) {
    std::vector<Field<Dim>*> f{&eps_, &beta_};
    for (int a = 0; a < Dim; ++a) {
      f.push_back(&us_[static_cast<std::size_t>(a)]);
      f.push_back(&us_gas_[static_cast<std::size_t>(a)]);
    }
    share_owned_cells(f);
  }
  refuse_negative_voidage();
  clip_voidage();
}

// A cell holding more particle volume than it has is not a dense bed but a wrong volume basis (a 2D slab thinner
// than its spheres, a cell smaller than a particle); clipping it to eps_min would hide a drag several times the
// bed's weight, so the run stops and says where.
template <int Dim>
void CfdDemSimulation<Dim>::refuse_negative_voidage() const {
  const std::vector<double>& e = eps_.data();
  const auto low = std::min_element(e.begin(), e.end());
  if (low == e.end() || *low >= 0.0) return;
  const auto bad = std::count_if(e.begin(), e.end(), [](double v) { return v < 0.0; });
  std::string basis = Dim == 2 ? fmt::format("the 2D slab of coupling.depth = {} m", depth_) : std::string("the cell volume");
  throw_simulation_error(fmt::format(
      "at t = {} s the voidage is {:.4g} (below zero) in {} of {} gas cells: the particles there hold more volume "
      "than {} gives them; the slab must be at least as deep as the largest particle ({} m) and a cell wider than "
      "a particle", time(), *low, bad, e.size(), basis, largest_diameter()));
}

template <int Dim>
double CfdDemSimulation<Dim>::largest_diameter() const {
  // Over every rank (collective): the slab depth must not depend on the split.
  const ParticleStore<Dim>& p = dem_.particles();
  double r = 0.0;
  for (std::size_t i = 0; i < dem_.owned(); ++i) r = std::max(r, p.radius[i]);
  return 2.0 * dem_.comm().max(r);
}

template <int Dim>
void CfdDemSimulation<Dim>::update_particle_forces() {
  const Grid<Dim>& g = gas_->grid();
  const GasConfig& gc = gas_->config();
  ParticleStore<Dim>& p = dem_.particles();
  const auto n = static_cast<std::ptrdiff_t>(p.size());
  const bool pressure_force = coupling_.pressure_gradient_force;
  if (weights_.size() != p.size()) particle_cell_weights(p, g, eps_, coupling_.voidage, weights_);
  // Gas velocity and pressure gradient at cell centres once per gas step, then one weighted sum per particle with
  // the deposition's own weights (the weights fold at walls: the boundary cell's value holds up to the wall).
  gas_->cell_velocity(ug_);
  if (pressure_force) gas_->cell_pressure_gradient(grad_p_);
  // The paper's counting deposits into one cell; the gas fields are still read multilinearly.
  const bool counting = coupling_.voidage == VoidageMethod::Centre;
  if (counting) particle_cell_weights(p, g, eps_, VoidageMethod::Bilinear, interp_weights_);
  const std::vector<CellWeights<Dim>>& iw = counting ? interp_weights_ : weights_;
  // Beetstra et al.'s polydisperse correction needs the Sauter mean diameter sum d^3 / sum d^2 around each
  // particle: both sums deposited with the particles' own kernel weights (per cell in ascending particle id, as the
  // deposition) and gathered back with the same weights.
  Field<Dim> sum_d3, sum_d2;
  if (coupling_.drag_law == DragLaw::Beetstra) {
    sum_d3 = Field<Dim>(g.owned, 0);
    sum_d2 = Field<Dim>(g.owned, 0);
    CellEntries e;
    e.build(weights_, id_order(), sum_d3.data().size());
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t cc = 0; cc < static_cast<std::ptrdiff_t>(e.cells()); ++cc) {
      const auto c = static_cast<std::size_t>(cc);
      double s3 = 0.0, s2 = 0.0;
      for (std::size_t q = e.begin(c); q < e.end(c); ++q) {
        const double d = 2.0 * p.radius[e.slot(q)];
        s3 += e.weight(q) * d * d * d;
        s2 += e.weight(q) * d * d;
      }
      sum_d3.data()[c] = s3;
      sum_d2.data()[c] = s2;
    }
    Field<Dim>* f[2] = {&sum_d3, &sum_d2};
    share_owned_cells(f);
  }
  // The drag law is chosen here, once; the particle loop is compiled per law.
  with_drag_law(DragModel{coupling_.drag_law, coupling_.drag_switch}, [&](auto law) {
    using Law = decltype(law);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const CellWeights<Dim>& cw = weights_[i];
      const CellWeights<Dim>& cwi = iw[i];
      const double eps = std::min(gather(eps_gas_, cw), 1.0 - 1e-9);
      Vec<Dim> ug{};
      for (int a = 0; a < Dim; ++a) ug[a] = gather(ug_[static_cast<std::size_t>(a)], cwi);
      const double r = p.radius[i];
      const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
      const double slip = norm(ug - p.vel(i));
      DragInput in{eps, 2.0 * r, gc.rho_g, gc.mu_g, slip};
      if constexpr (std::is_same_v<Law, BeetstraLaw>) in.d_mean = gather(sum_d3, cw) / gather(sum_d2, cw);
      const double beta = Law::beta(in);
      // Eq. 12's beta is per unit mixture volume; one particle's share is V_p / (1 - eps).
      p.drag_k[i] = vp * beta / (1.0 - eps);
      for (int a = 0; a < Dim; ++a) p.gas_velocity(a)[i] = ug[a];
      if (pressure_force) {
        for (int a = 0; a < Dim; ++a) p.force_ext(a)[i] = -vp * gather(grad_p_[static_cast<std::size_t>(a)], cwi);
      } else {
        for (int a = 0; a < Dim; ++a) p.force_ext(a)[i] = 0.0;
      }
    }
  });
}

template <int Dim>
void CfdDemSimulation<Dim>::initialize() {
  if (!gas_) return;
  dem_.prepare();  // on several ranks: the ghosts, which the deposition needs
  deposit();
  eps_gas_old_ = eps_gas_;
  // One quasi-steady gas solve for the bed at rest (particles have no drag coefficient yet: do it twice, the
  // second time with the drag of the first).
  for (int pass = 0; pass < 2; ++pass) {
    report_ = gas_->advance(time(), macro_dt(), eps_gas_old_, eps_gas_, beta_, us_gas_);
    update_particle_forces();
    deposit();
  }
  eps_gas_old_ = eps_gas_;
}

template <int Dim>
void CfdDemSimulation<Dim>::advance(double h) {
  const bool full = h == macro_dt();
  if (!gas_) {
    if (full) {
      dem_.step();
    } else {
      dem_.step(h);
    }
    return;
  }
  for (int k = 0; k < coupling_.dem_substeps; ++k) {
    if (full) {
      dem_.step();
    } else {
      dem_.step(h / coupling_.dem_substeps);
    }
  }
  eps_gas_old_ = eps_gas_;
  deposit();
  report_ = gas_->advance(time(), h, eps_gas_old_, eps_gas_, beta_, us_gas_);
  ++gas_steps_;
  update_particle_forces();
}

template <int Dim>
double CfdDemSimulation<Dim>::min_voidage() const {
  const std::vector<double>& e = eps_.data();
  return e.empty() ? 1.0 : *std::min_element(e.begin(), e.end());
}

template <int Dim>
Vec<Dim> CfdDemSimulation<Dim>::total_fluid_force() const {
  // Summed exactly over the owned particles: the same bits for any order and split of the particles.
  const ParticleStore<Dim>& p = dem_.particles();
  std::array<ExactSum, Dim> s;
  for (std::size_t i = 0; i < dem_.owned(); ++i) {
    for (int a = 0; a < Dim; ++a) {
      s[static_cast<std::size_t>(a)].add(p.force_ext(a)[i] + p.drag_k[i] * (p.gas_velocity(a)[i] - p.velocity(a)[i]));
    }
  }
  Vec<Dim> f{};
  for (int a = 0; a < Dim; ++a) f[a] = dem_.comm().sum(s[static_cast<std::size_t>(a)]);
  return f;
}

template <int Dim>
Vec<Dim> CfdDemSimulation<Dim>::total_gas_reaction() const {
  if (!gas_) return {};
  const double vcell = deposition_volume(gas_->grid(), depth_);
  Vec<Dim> f{};
  const std::size_t n = beta_.data().size();
  for (std::size_t c = 0; c < n; ++c) {
    for (int a = 0; a < Dim; ++a) f[a] += beta_.data()[c] * (ug_[a].data()[c] - us_gas_[a].data()[c]) * vcell;
  }
  return f;
}

template <int Dim>
void CfdDemSimulation<Dim>::restore(Field<Dim> eps, std::uint64_t gas_steps) {
  gas_steps_ = gas_steps;
  if (!gas_) return;
  eps_ = std::move(eps);
  const Grid<Dim>& g = gas_->grid();
  clip_voidage();
  dem_.prepare();  // on several ranks: the ghosts, which the deposition needs
  particle_cell_weights(dem_.particles(), g, eps_, coupling_.voidage, weights_);  // of the restored particles
  // The solids velocity as deposit() computes it (the voidage stays the restored one; the rest is recomputed
  // before the next gas step).
  Field<Dim> eps_now, beta_now;
  std::array<Field<Dim>, Dim> us_gas_now;
  deposition_.deposit(dem_.particles(), weights_, g, depth_, DepositedFields<Dim>{&eps_now, &us_, &beta_now, &us_gas_now},
                      id_order());
  if (dem_.distributed()) {
    std::vector<Field<Dim>*> f;
    for (Field<Dim>& u : us_) f.push_back(&u);
    share_owned_cells(f);
  }
  gas_->cell_velocity(ug_);
}

template class CfdDemSimulation<2>;
template class CfdDemSimulation<3>;

}  // namespace fluidbed
