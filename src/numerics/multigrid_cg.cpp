#include "numerics/multigrid_cg.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "numerics/stencil_matrix.hpp"
#include "numerics/line_sum.hpp"
#include "parallel/periodic_halo.hpp"

namespace fluidbed {
namespace {

/// Calls f(c) for every cell of b, the planes of the last axis shared among threads (each cell's work is its own,
/// so the split does not change a bit).
template <int Dim, class F>
void for_cells(const IndexBox<Dim>& b, F&& f) {
  const int lo = b.lo[Dim - 1], hi = b.hi[Dim - 1];
#pragma omp parallel for schedule(static) if (b.count() >= static_cast<std::size_t>(kParallelCells))
  for (int k = lo; k < hi; ++k) {
    IndexBox<Dim> plane = b;
    plane.lo[Dim - 1] = k;
    plane.hi[Dim - 1] = k + 1;
    for_each(plane, f);
  }
}

/// Calls f(k, n, first) for every line of b along axis 0: k the offset of its first cell `first` in a field laid out
/// as `layout`, n its length (every field of a level shares one layout, so k + i addresses the line in all of them).
template <int Dim, class F>
void for_lines(const IndexBox<Dim>& b, const Field<Dim>& layout, F&& f) {
  IndexBox<Dim> starts = b;
  starts.hi[0] = starts.lo[0] + 1;
  const int n = b.extent(0);
  for_cells(starts, [&](const Index<Dim>& c) { f(layout.index(c), n, c); });
}

/// One level of the hierarchy: every field on the same owned box with one ghost layer, so one offset addresses a
/// cell in all of them.
template <int Dim>
struct Level {
  Grid<Dim> grid;                 ///< owned = domain on the redundant levels
  bool shared = false;            ///< the owned box is a part of the domain: ghosts come from other ranks
  std::vector<IndexBox<Dim>> boxes;  ///< when shared: every rank's owned box (its halos need no collective)
  std::array<int, Dim> ratio{};   ///< cells per coarse cell along each axis, towards the next level (1 or 2)
  Field<Dim> diag;                ///< a_PP
  std::array<Field<Dim>, Dim> w;  ///< w[a] at c: the coupling of c with its high neighbour along a (wrapped)
  Field<Dim> x, b, r, t;          ///< iterate, right-hand side, residual, a colour's new values
  /// A periodic axis of odd length: there a cell can have a neighbour of its own colour, so a colour's new values
  /// are computed apart and written after its sweep (elsewhere in place, which computes the same values).
  bool odd_periodic = false;

  explicit Level(const Grid<Dim>& g, bool is_shared) : grid(g), shared(is_shared) {
    diag = x = b = r = t = Field<Dim>(g.owned, 1);
    for (int a = 0; a < Dim; ++a) {
      w[a] = Field<Dim>(g.owned, 1);
      odd_periodic = odd_periodic || (g.periodic[static_cast<std::size_t>(a)] && g.domain.extent(a) % 2 == 1);
    }
  }
  /// Offset of cell c in every field, and the offset of a step along each axis.
  std::size_t at(const Index<Dim>& c) const { return x.index(c); }
  std::size_t step(int a) const { return x.stride(a); }
  /// Along axis a, the coarse cell holding cell i of this level.
  int parent(int a, int i) const { return (i - grid.domain.lo[a]) / ratio[a]; }
  /// The cells of this level aggregated into coarse cell cc (fewer at the domain's high side when its extent is odd).
  IndexBox<Dim> children(const Index<Dim>& cc) const {
    IndexBox<Dim> kids;
    for (int a = 0; a < Dim; ++a) {
      kids.lo[a] = grid.domain.lo[a] + ratio[a] * cc[a];
      kids.hi[a] = std::min(kids.lo[a] + ratio[a], grid.domain.hi[a]);
    }
    return kids;
  }
  /// Red (0) or black (1): the parity of the cell's global index, the same whoever owns it.
  int colour(const Index<Dim>& c) const {
    int s = 0;
    for (int a = 0; a < Dim; ++a) s += c[a] - grid.domain.lo[a];
    return s & 1;
  }
};

/// The coarse cells whose first child lies in `owned`, a box of the fine level: the ones its rank computes (and
/// owns, where the coarse level is shared among the ranks too).
template <int Dim>
IndexBox<Dim> first_children_box(const Level<Dim>& fine, const IndexBox<Dim>& owned) {
  IndexBox<Dim> b;
  for (int a = 0; a < Dim; ++a) {
    const int r = fine.ratio[a], lo = owned.lo[a] - fine.grid.domain.lo[a];
    const int hi = owned.hi[a] - fine.grid.domain.lo[a];
    b.lo[a] = (lo + r - 1) / r;
    b.hi[a] = (hi + r - 1) / r;
  }
  return b;
}
template <int Dim>
IndexBox<Dim> first_children_box(const Level<Dim>& fine) {
  return first_children_box(fine, fine.grid.owned);
}

template <int Dim>
class MultigridCg final : public StructuredSolver<Dim> {
 public:
  MultigridCg(const Grid<Dim>& grid, const Comm& comm, MultigridCgOptions options);
  const char* name() const override { return "cg-multigrid"; }
  void set_tolerance(double relative) override { options_.tolerance = relative; }
  void solve(const FaceFields<Dim>& coeff, const Field<Dim>& rhs, Field<Dim>& x, bool reuse_factorisation) override;
  MultigridCgStats stats;

 private:
  /// The smoother and the products read the face ghosts only; the transfers read a block's children or parents
  /// across its edges and corners too (HaloCells::All).
  void halo(const Level<Dim>& l, Field<Dim>& f, HaloCells cells = HaloCells::All) const {
    if (l.shared) comm_.exchange_halo_among(f, l.boxes, cells);
    fill_periodic_ghosts(l.grid, f);
  }
  void assemble_fine(const FaceFields<Dim>& coeff, const Field<Dim>& rhs);
  void check_finite(const FaceFields<Dim>& coeff, const Field<Dim>& rhs) const;
  void coarsen(const Level<Dim>& fine, Level<Dim>& coarse) const;
  void factorise_coarsest();
  void gather_redundant(const Level<Dim>& fine, const Level<Dim>& coarse, std::span<Field<Dim>* const> fields) const;
  void apply(Level<Dim>& l, Field<Dim>& in, Field<Dim>& out) const;
  void smooth(Level<Dim>& l, int colour, bool ghosts_current = false) const;
  void vcycle(std::size_t level);
  double dot(const Field<Dim>& u, const Field<Dim>& v) const;

  const Comm& comm_;
  MultigridCgOptions options_;
  std::vector<Level<Dim>> levels_;
  Eigen::LDLT<Eigen::MatrixXd> coarsest_;
  bool hierarchy_built_ = false;
  bool pinned_ = false;  ///< the last problem had no fixed-pressure face: the domain's first cell is held at zero
  Field<Dim> p_, q_, res_, sol_;
  std::vector<std::size_t> fine_lines_;  ///< offsets of the first level's lines along axis 0 (the inner products')
};

template <int Dim>
MultigridCg<Dim>::MultigridCg(const Grid<Dim>& grid, const Comm& comm, MultigridCgOptions options)
    : comm_(comm), options_(options) {
  if (options.line_sums && grid.owned.extent(0) != grid.domain.extent(0)) {
    throw_input_error("pressure solver \"cg-multigrid\" with line sums: axis 0 (x) is cut across ranks; its inner "
                      "products sum whole lines along x in one order, so cut the other axes");
  }
  for (int a = 0; a < Dim; ++a) {
    if (grid.periodic[static_cast<std::size_t>(a)] && grid.owned.extent(a) != grid.domain.extent(a))
      throw_input_error("pressure solver \"cg-multigrid\": periodic axis " + std::to_string(a) +
                        " is cut across ranks (its ghosts would need the opposite rank); cut the other axes");
  }
  // The levels' shapes depend on the domain only: every level's extents by one rule, at least one coarse level,
  // down to at most 128 cells (a chain that depended on the cut would change the preconditioner, and the bits).
  std::vector<Index<Dim>> extents(1);
  for (int a = 0; a < Dim; ++a) extents[0][a] = grid.domain.extent(a);
  auto cells = [](const Index<Dim>& n) {
    std::size_t c = 1;
    for (int a = 0; a < Dim; ++a) c *= static_cast<std::size_t>(n[a]);
    return c;
  };
  auto coarsenable = [](const Index<Dim>& n) {
    bool any = false;
    for (int a = 0; a < Dim; ++a) any = any || n[a] > 1;
    return any;
  };
  while ((cells(extents.back()) > 128 || extents.size() == 1) && coarsenable(extents.back())) {
    Index<Dim> c{};
    for (int a = 0; a < Dim; ++a) c[a] = (extents.back()[a] + 1) / 2;
    extents.push_back(c);
  }
  // The first level is the rank's block; a coarse level above the bottom stays shared among the ranks while every
  // rank's part of it keeps 2 cells per axis (where the domain has them); the first level below that and all below
  // it are the whole coarse domain on every rank.
  levels_.emplace_back(grid, comm.size() > 1);
  if (comm.size() > 1) levels_[0].boxes = all_boxes<Dim>(comm, grid.owned);
  for (std::size_t l = 1; l < extents.size(); ++l) {
    Level<Dim>& fine = levels_.back();
    Grid<Dim> g;
    for (int a = 0; a < Dim; ++a) {
      fine.ratio[a] = extents[l - 1][a] > 1 ? 2 : 1;
      g.domain.hi[a] = extents[l][a];
    }
    g.owned = g.domain;
    g.periodic = grid.periodic;
    std::vector<IndexBox<Dim>> parts;
    bool share = fine.shared && l + 1 < extents.size();
    if (share) {
      for (const IndexBox<Dim>& b : fine.boxes) {
        parts.push_back(first_children_box(fine, b));
        for (int a = 0; a < Dim; ++a) share = share && parts.back().extent(a) >= std::min(2, extents[l][a]);
      }
    }
    if (share) g.owned = parts[static_cast<std::size_t>(comm.rank())];
    levels_.emplace_back(g, share);
    if (share) levels_.back().boxes = std::move(parts);
  }
  stats.levels = static_cast<int>(levels_.size());
  p_ = q_ = res_ = sol_ = Field<Dim>(grid.owned, 1);
  IndexBox<Dim> starts = grid.owned;
  starts.hi[0] = starts.lo[0] + 1;
  for_each(starts, [&](const Index<Dim>& c) { fine_lines_.push_back(p_.index(c)); });
}

template <int Dim>
void MultigridCg<Dim>::check_finite(const FaceFields<Dim>& coeff, const Field<Dim>& rhs) const {
  // Collective: the rank with the first bad cell (global index order) names it, every rank throws the same.
  const Grid<Dim>& g = levels_[0].grid;
  std::optional<std::string> bad;
  double key = 0.0;
  for_each(g.owned, [&](const Index<Dim>& c) {
    if (bad) return;
    bool finite = std::isfinite(rhs[c]);
    for (int a = 0; a < Dim; ++a)
      finite = finite && std::isfinite(coeff[a][c]) && std::isfinite(coeff[a][shifted<Dim>(c, a, 1)]);
    if (finite) return;
    std::string name = "(";
    for (int a = 0; a < Dim; ++a) name += (a > 0 ? ", " : "") + std::to_string(c[a]);
    bad = "gas pressure correction: the mass imbalance or a face coefficient of cell " + name +
          ") is not finite (imbalance " + std::to_string(rhs[c]) + ")";
    double k = 0.0, stride = 1.0;
    for (int a = 0; a < Dim; ++a) {
      k += (c[a] - g.domain.lo[a]) * stride;
      stride *= g.domain.extent(a);
    }
    key = k;
  });
  if (auto failure = comm_.first_failure(bad, key)) throw_simulation_error(*failure);
}

template <int Dim>
void MultigridCg<Dim>::assemble_fine(const FaceFields<Dim>& coeff, const Field<Dim>& rhs) {
  Level<Dim>& l = levels_[0];
  const Grid<Dim>& g = l.grid;
  // Singular without a fixed-pressure face anywhere: then the domain's first cell is pinned to zero, its couplings
  // dropped from its neighbours' rows (which keep the face in their diagonal), as the other backends do.
  double open = 0.0;
  for (int a = 0; a < Dim; ++a)
    for (bool high : {false, true}) {
      if (!g.at_domain_side(a, high)) continue;
      IndexBox<Dim> side = g.owned.inside(a, high);
      if (high) side = IndexBox<Dim>{shifted<Dim>(side.lo, a, 1), shifted<Dim>(side.hi, a, 1)};
      for_each(side, [&](const Index<Dim>& f) { open = coeff[a][f] > 0.0 ? 1.0 : open; });
    }
  const bool pin = comm_.max(open) == 0.0;
  pinned_ = pin;
  const Index<Dim> pinned = g.domain.lo;
  for_cells(g.owned, [&](const Index<Dim>& c) {
    double diag = 0.0;
    for (int a = 0; a < Dim; ++a) {
      // The high face of the last cell of a periodic axis is the domain's first face (the same plane).
      const bool wraps = c[a] == g.domain.hi[a] - 1;
      const Index<Dim> hi_face = wraps && g.periodic[static_cast<std::size_t>(a)]
                                     ? shifted<Dim>(c, a, 1 - g.domain.extent(a))
                                     : shifted<Dim>(c, a, 1);
      const double lo = coeff[a][c], hi = coeff[a][hi_face];
      diag = a == 0 ? lo + hi : diag + lo + hi;
      Index<Dim> up = c;
      up[a] = g.wrap(a, c[a] + 1);
      const bool couples = !wraps || g.periodic[static_cast<std::size_t>(a)];
      l.w[a][c] = couples && !(pin && (c == pinned || up == pinned)) ? hi : 0.0;
    }
    l.diag[c] = diag > 0.0 ? diag : 1.0;  // a cell with no open face: keep it at zero
    l.b[c] = rhs[c];
    if (pin && c == pinned) {
      l.diag[c] = 1.0;
      l.b[c] = 0.0;
    }
  });
  halo(l, l.diag);
  for (int a = 0; a < Dim; ++a) halo(l, l.w[a]);
}

template <int Dim>
void MultigridCg<Dim>::coarsen(const Level<Dim>& fine, Level<Dim>& coarse) const {
  // 0.5 P^T A P: the coarse diagonal sums the children's minus twice their couplings inside the aggregate, a coarse
  // coupling sums the fine couplings across the aggregate's high face.
  const IndexBox<Dim> mine = first_children_box(fine);
  for_cells(mine, [&](const Index<Dim>& cc) {
    double d = 0.0;
    std::array<double, Dim> wc{};
    for_each(fine.children(cc), [&](const Index<Dim>& c) {
      const std::size_t k = fine.at(c);
      d += fine.diag.data()[k];
      for (int a = 0; a < Dim; ++a) {
        const double wf = fine.w[a].data()[k];
        if (fine.parent(a, fine.grid.wrap(a, c[a] + 1)) == cc[a]) {  // a coupling inside the aggregate
          d -= 2.0 * wf;
        } else {
          wc[static_cast<std::size_t>(a)] += wf;
        }
      }
    });
    coarse.diag[cc] = 0.5 * d;
    for (int a = 0; a < Dim; ++a) coarse.w[a][cc] = 0.5 * wc[static_cast<std::size_t>(a)];
  });
  std::array<Field<Dim>*, Dim + 1> op{&coarse.diag};
  for (int a = 0; a < Dim; ++a) op[static_cast<std::size_t>(a + 1)] = &coarse.w[a];
  gather_redundant(fine, coarse, op);
  halo(coarse, coarse.diag);
  for (int a = 0; a < Dim; ++a) halo(coarse, coarse.w[a]);
}

template <int Dim>
void MultigridCg<Dim>::gather_redundant(const Level<Dim>& fine, const Level<Dim>& coarse,
                                        std::span<Field<Dim>* const> fields) const {
  // Each rank computed the coarse cells of its first children; where the coarse level is not shared every rank
  // receives them all, so it and the levels below are the same on every rank.
  if (!fine.shared || coarse.shared) return;
  const std::vector<const Field<Dim>*> mine(fields.begin(), fields.end());
  gather_parts<Dim>(comm_, first_children_box(fine), mine, fields);
}

template <int Dim>
void MultigridCg<Dim>::factorise_coarsest() {
  const Level<Dim>& l = levels_.back();
  const IndexBox<Dim>& box = l.grid.owned;
  const auto m = static_cast<Eigen::Index>(box.count());
  auto row = [&](const Index<Dim>& c) { return static_cast<Eigen::Index>(cell_row(box, c)); };
  Eigen::MatrixXd a_mat = Eigen::MatrixXd::Zero(m, m);
  for_each(box, [&](const Index<Dim>& c) {
    const Eigen::Index i = row(c);
    a_mat(i, i) += l.diag[c];
    for (int a = 0; a < Dim; ++a) {
      if (l.w[a][c] == 0.0) continue;
      Index<Dim> up = c;
      up[a] = l.grid.wrap(a, c[a] + 1);
      const Eigen::Index j = row(up);
      a_mat(i, j) -= l.w[a][c];
      a_mat(j, i) -= l.w[a][c];
    }
  });
  coarsest_.compute(a_mat);
}

template <int Dim>
void MultigridCg<Dim>::apply(Level<Dim>& l, Field<Dim>& in, Field<Dim>& out) const {
  halo(l, in, HaloCells::Faces);
  const double* u = in.data().data();
  const double* d = l.diag.data().data();
  double* y = out.data().data();
  std::array<const double*, Dim> w;
  std::array<std::size_t, Dim> s;
  for (int a = 0; a < Dim; ++a) {
    w[a] = l.w[a].data().data();
    s[a] = l.step(a);
  }
  for_lines(l.grid.owned, l.x, [&](std::size_t k0, int n, const Index<Dim>&) {
    for (std::size_t k = k0; k < k0 + static_cast<std::size_t>(n); ++k) {
      double v = d[k] * u[k];
      for (int a = 0; a < Dim; ++a) v -= w[a][k] * u[k + s[a]] + w[a][k - s[a]] * u[k - s[a]];
      y[k] = v;
    }
  });
}

template <int Dim>
void MultigridCg<Dim>::smooth(Level<Dim>& l, int colour, bool ghosts_current) const {
  // One colour's cells, each from its neighbours of the other colour (Level::odd_periodic: see there).
  if (!ghosts_current) halo(l, l.x, HaloCells::Faces);
  double* u = l.x.data().data();
  double* dst = l.odd_periodic ? l.t.data().data() : u;
  const double* d = l.diag.data().data();
  const double* rhs = l.b.data().data();
  std::array<const double*, Dim> w;
  std::array<std::size_t, Dim> s;
  for (int a = 0; a < Dim; ++a) {
    w[a] = l.w[a].data().data();
    s[a] = l.step(a);
  }
  auto lines = [&](auto&& body) {
    for_lines(l.grid.owned, l.x, [&](std::size_t k0, int n, const Index<Dim>& first) {
      for (auto i = static_cast<std::size_t>(l.colour(first) != colour); i < static_cast<std::size_t>(n); i += 2)
        body(k0 + i);
    });
  };
  lines([&](std::size_t k) {
    double v = rhs[k];
    for (int a = 0; a < Dim; ++a) v += w[a][k] * u[k + s[a]] + w[a][k - s[a]] * u[k - s[a]];
    dst[k] = v / d[k];
  });
  if (l.odd_periodic) lines([&](std::size_t k) { u[k] = dst[k]; });
}

template <int Dim>
void MultigridCg<Dim>::vcycle(std::size_t level) {
  Level<Dim>& l = levels_[level];
  if (level + 1 == levels_.size()) {
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(l.grid.owned.count()));
    Eigen::Index i = 0;
    for_each(l.grid.owned, [&](const Index<Dim>& c) { rhs[i++] = l.b[c]; });
    const Eigen::VectorXd sol = coarsest_.solve(rhs);
    i = 0;
    for_each(l.grid.owned, [&](const Index<Dim>& c) { l.x[c] = sol[i++]; });
    return;
  }
  l.x.fill(0.0);  // the ghosts too: the first sweep needs no halo
  for (int s = 0; s < options_.smoothing_sweeps; ++s) {
    smooth(l, 0, s == 0);
    smooth(l, 1);
  }
  apply(l, l.x, l.r);
  for_cells(l.grid.owned, [&](const Index<Dim>& c) { l.r[c] = l.b[c] - l.r[c]; });
  halo(l, l.r);  // the children of this rank's coarse cells beyond its block
  Level<Dim>& coarse = levels_[level + 1];
  for_cells(first_children_box(l), [&](const Index<Dim>& cc) {
    double s = 0.0;
    for_each(l.children(cc), [&](const Index<Dim>& c) { s += l.r[c]; });
    coarse.b[cc] = s;
  });
  Field<Dim>* const rhs = &coarse.b;
  gather_redundant(l, coarse, std::span(&rhs, 1));
  vcycle(level + 1);
  halo(coarse, coarse.x);  // a parent below this rank's first child lies in the coarse level's ghosts
  for_cells(l.grid.owned, [&](const Index<Dim>& c) {
    Index<Dim> parent;
    for (int a = 0; a < Dim; ++a) parent[a] = l.parent(a, c[a]);
    l.x[c] += coarse.x[parent];
  });
  for (int s = 0; s < options_.smoothing_sweeps; ++s) {
    smooth(l, 1);
    smooth(l, 0);
  }
}

template <int Dim>
double MultigridCg<Dim>::dot(const Field<Dim>& u, const Field<Dim>& v) const {
  const IndexBox<Dim>& box = levels_[0].grid.owned;
  const std::vector<std::size_t>& first = fine_lines_;
  const double* pu = u.data().data();
  const double* pv = v.data().data();
  const auto n = static_cast<std::size_t>(box.extent(0));
  ExactSum total;
#pragma omp parallel if (box.count() >= static_cast<std::size_t>(kParallelCells))
  {
    ExactSum part;  // exact: how the lines are shared among threads does not matter
#pragma omp for schedule(static) nowait
    for (std::size_t line = 0; line < first.size(); ++line) {
      const std::size_t k0 = first[line];
      if (options_.line_sums) {
        part.add(line_dot(pu + k0, pv + k0, static_cast<int>(n)));
      } else {
        for (std::size_t k = k0; k < k0 + n; ++k) part.add(pu[k] * pv[k]);
      }
    }
#pragma omp critical
    total.merge(part);
  }
  return comm_.sum(total);
}

template <int Dim>
void MultigridCg<Dim>::solve(const FaceFields<Dim>& coeff, const Field<Dim>& rhs, Field<Dim>& x,
                             bool reuse_factorisation) {
  check_finite(coeff, rhs);
  assemble_fine(coeff, rhs);
  if (!reuse_factorisation || !hierarchy_built_) {
    for (std::size_t l = 0; l + 1 < levels_.size(); ++l) coarsen(levels_[l], levels_[l + 1]);
    factorise_coarsest();
    hierarchy_built_ = true;
  }
  Level<Dim>& fine = levels_[0];
  const IndexBox<Dim>& box = fine.grid.owned;
  // The right-hand side is kept in res_ (the V-cycle uses the level's own b); the pinned cell's zero included.
  for_each(box, [&](const Index<Dim>& c) {
    sol_[c] = pinned_ && c == fine.grid.domain.lo ? 0.0 : x[c];
    res_[c] = fine.b[c];
  });
  const double bnorm = std::sqrt(dot(res_, res_));
  stats.iterations = 0;
  stats.relative_residual = 0.0;
  if (bnorm == 0.0) {
    for_each(box, [&](const Index<Dim>& c) { x[c] = 0.0; });
    return;
  }
  apply(fine, sol_, q_);
  for_cells(box, [&](const Index<Dim>& c) { res_[c] -= q_[c]; });
  auto precondition = [&] {  // fine.x = M r
    for_cells(box, [&](const Index<Dim>& c) { fine.b[c] = res_[c]; });
    vcycle(0);
  };
  double rnorm = std::sqrt(dot(res_, res_));
  precondition();
  for_cells(box, [&](const Index<Dim>& c) { p_[c] = fine.x[c]; });
  double rz = dot(res_, fine.x);
  int it = 0;
  while (rnorm > options_.tolerance * bnorm) {
    if (it == options_.max_iterations || !std::isfinite(rnorm))
      throw_simulation_error("gas pressure correction (cg-multigrid): relative residual " +
                             std::to_string(rnorm / bnorm) + " after " + std::to_string(it) +
                             " iterations, above the tolerance " + std::to_string(options_.tolerance));
    apply(fine, p_, q_);
    const double alpha = rz / dot(p_, q_);
    for_cells(box, [&](const Index<Dim>& c) {
      sol_[c] += alpha * p_[c];
      res_[c] -= alpha * q_[c];
    });
    ++it;
    rnorm = std::sqrt(dot(res_, res_));
    if (rnorm <= options_.tolerance * bnorm) break;
    precondition();
    const double rz_new = dot(res_, fine.x);
    const double beta = rz_new / rz;
    rz = rz_new;
    for_cells(box, [&](const Index<Dim>& c) { p_[c] = fine.x[c] + beta * p_[c]; });
  }
  stats.iterations = it;
  stats.relative_residual = rnorm / bnorm;
  for_each(box, [&](const Index<Dim>& c) { x[c] = sol_[c]; });
}

}  // namespace

template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_multigrid_cg_solver(const Grid<Dim>& grid, const Comm& comm,
                                                                MultigridCgOptions options) {
  return std::make_unique<MultigridCg<Dim>>(grid, comm, options);
}

template <int Dim>
MultigridCgStats multigrid_cg_stats(const StructuredSolver<Dim>& solver) {
  return dynamic_cast<const MultigridCg<Dim>&>(solver).stats;
}

template std::unique_ptr<StructuredSolver<2>> make_multigrid_cg_solver(const Grid<2>&, const Comm&, MultigridCgOptions);
template std::unique_ptr<StructuredSolver<3>> make_multigrid_cg_solver(const Grid<3>&, const Comm&, MultigridCgOptions);
template MultigridCgStats multigrid_cg_stats(const StructuredSolver<2>&);
template MultigridCgStats multigrid_cg_stats(const StructuredSolver<3>&);

}  // namespace fluidbed
