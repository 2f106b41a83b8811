// The multigrid-preconditioned CG pressure backend on 1 to 4 ranks (ctest runs this under mpiexec -n 1..4) against
// the same backend on one process, bit for bit: the answer, the iteration count and the last residual, for 2D and
// 3D problems with a fixed-pressure top, an all-Neumann (pinned) one, a periodic axis, blocks cut along every axis
// the rank count allows, coarse levels shared among the ranks, and a grid smaller than the bottom level. Each rank also solves the one-process reference itself (the problems are small).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "numerics/multigrid_cg.hpp"
#include "parallel/decomposition.hpp"
#include "mpi_world.hpp"

namespace fluidbed {
namespace {

/// A value in [e^-1.5, e^1.5] that depends only on the global index and a salt (the same on every rank).
template <int Dim>
double coefficient(const Index<Dim>& f, int salt) {
  double phase = 0.3 * salt;
  for (int a = 0; a < Dim; ++a) phase += (0.37 + 0.21 * a) * f[a] + 0.013 * f[a] * f[a];
  return std::exp(1.5 * std::sin(phase));
}

/// The problem restricted to grid's owned box: face coefficients (fixed-pressure top when `fixed_top`, the periodic
/// axis's last face tied to its first) and a right-hand side.
template <int Dim>
void fill_problem(const Grid<Dim>& grid, bool fixed_top, FaceFields<Dim>& coeff, Field<Dim>& rhs) {
  coeff = FaceFields<Dim>(grid.owned, 0, 0.0);
  for (int a = 0; a < Dim; ++a) {
    for_each(grid.owned.faces(a), [&](const Index<Dim>& f) {
      Index<Dim> g = f;
      const bool side = f[a] == grid.domain.lo[a] || f[a] == grid.domain.hi[a];
      if (grid.periodic[static_cast<std::size_t>(a)]) g[a] = grid.wrap(a, f[a]);
      double c = coefficient<Dim>(g, a);
      if (side && !grid.periodic[static_cast<std::size_t>(a)])
        c = fixed_top && a == Dim - 1 && f[a] == grid.domain.hi[a] ? 2.0 : 0.0;
      coeff[a][f] = c;
    });
  }
  rhs = Field<Dim>(grid.owned, 0);
  for_each(grid.owned, [&](const Index<Dim>& c) { rhs[c] = coefficient<Dim>(c, 7) - 1.0; });
}

template <int Dim>
std::vector<std::uint64_t> bits_on(const Grid<Dim>& domain_grid, const Field<Dim>& x) {
  // The answer on the whole domain, gathered from every rank's block (in the domain's order).
  Field<Dim> all(domain_grid.domain, 0);
  Bytes mine;
  pack(mine, x.box());
  for_each(x.box(), [&](const Index<Dim>& c) { pack(mine, x[c]); });
  for (const Bytes& from : world().allgather(mine)) {
    Unpacker in(from);
    const auto box = in.get<IndexBox<Dim>>();
    for_each(box, [&](const Index<Dim>& c) { all[c] = in.get<double>(); });
  }
  std::vector<std::uint64_t> b;
  for (double v : all.data()) b.push_back(std::bit_cast<std::uint64_t>(v));
  return b;
}

template <int Dim>
void check(const Index<Dim>& n, bool fixed_top, int periodic_axis, Index<Dim> blocks, bool line_sums = false) {
  const Comm& comm = world();
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 1.0;
  Grid<Dim> whole = Grid<Dim>::uniform(ext, n, 1);
  if (periodic_axis >= 0) whole.periodic[static_cast<std::size_t>(periodic_axis)] = true;
  // The reference: one process, the whole domain.
  FaceFields<Dim> coeff;
  Field<Dim> rhs;
  fill_problem(whole, fixed_top, coeff, rhs);
  Field<Dim> ref(whole.owned, 0);
  auto one = make_multigrid_cg_solver<Dim>(whole, serial_comm(), {.tolerance = 1e-11, .line_sums = line_sums});
  one->solve(coeff, rhs, ref, false);
  const MultigridCgStats ref_stats = multigrid_cg_stats<Dim>(*one);
  // This rank's block.
  Grid<Dim> part = whole;
  part.owned = block_of<Dim>(whole.domain, blocks, comm.rank());
  fill_problem(part, fixed_top, coeff, rhs);
  Field<Dim> x(part.owned, 0);
  auto many = make_multigrid_cg_solver<Dim>(part, comm, {.tolerance = 1e-11, .line_sums = line_sums});
  many->solve(coeff, rhs, x, false);
  const MultigridCgStats st = multigrid_cg_stats<Dim>(*many);
  EXPECT_EQ(st.iterations, ref_stats.iterations);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(st.relative_residual), std::bit_cast<std::uint64_t>(ref_stats.relative_residual));
  std::vector<std::uint64_t> want;
  for (double v : ref.data()) want.push_back(std::bit_cast<std::uint64_t>(v));
  EXPECT_EQ(bits_on(whole, x), want) << comm.size() << " ranks";
  // A second solve on the reused hierarchy, warm-started, with a changed right-hand side: still the same bits.
  for_each(part.owned, [&](const Index<Dim>& c) { rhs[c] *= 1.25; });
  Field<Dim> rhs_whole;
  FaceFields<Dim> coeff_whole;
  fill_problem(whole, fixed_top, coeff_whole, rhs_whole);
  for_each(whole.owned, [&](const Index<Dim>& c) { rhs_whole[c] *= 1.25; });
  one->solve(coeff_whole, rhs_whole, ref, true);
  many->solve(coeff, rhs, x, true);
  want.clear();
  for (double v : ref.data()) want.push_back(std::bit_cast<std::uint64_t>(v));
  EXPECT_EQ(bits_on(whole, x), want) << comm.size() << " ranks, reused hierarchy";
}

TEST(MultigridCgRanks, Fixed2dCutLikeTheSolvers) {
  check<2>({37, 53}, true, -1, block_counts<2>(world().size(), {37, 53}));
}
TEST(MultigridCgRanks, Fixed2dCutAcrossX) { check<2>({37, 53}, true, -1, {world().size(), 1}); }
TEST(MultigridCgRanks, Neumann3dPinned) {
  check<3>({13, 17, 11}, false, -1, block_counts<3>(world().size(), {13, 17, 11}));
}
TEST(MultigridCgRanks, Fixed3dAlongEveryAxis) {
  const int p = world().size();
  check<3>({19, 14, 23}, true, -1, {1, 1, p});
  check<3>({19, 14, 23}, true, -1, {p, 1, 1});
  if (p == 4) check<3>({19, 14, 23}, true, -1, {2, 2, 1});
}
// Fewer cells than the bottom level holds: still one coarse level on every rank count (a hierarchy whose depth
// followed the cut would change the preconditioner, and the bits).
TEST(MultigridCgRanks, TinyGrid) { check<2>({9, 12}, true, -1, {1, world().size()}); }
// Coarse levels shared among the ranks, some of them starting at an odd index (their first coarse cell computed by
// the rank below).
TEST(MultigridCgRanks, SharedCoarseLevels) { check<3>({24, 40, 16}, false, -1, {1, world().size(), 1}); }
TEST(MultigridCgRanks, PeriodicXCutAlongY) { check<2>({24, 41}, true, 0, {1, world().size()}); }
TEST(MultigridCgRanks, Periodic3dCutAlongZ) { check<3>({10, 12, 21}, true, 0, {1, 1, world().size()}); }
// The two-fluid model's mode: inner products as line sums along x, blocks that span x.
TEST(MultigridCgRanks, LineSumsCutAlongYAndZ) {
  const int p = world().size();
  check<2>({37, 53}, true, 0, {1, p}, true);
  check<3>({13, 24, 16}, false, -1, {1, p, 1}, true);
  check<3>({19, 14, 23}, true, 0, {1, 1, p}, true);
  if (p == 4) check<3>({19, 14, 23}, true, -1, {1, 2, 2}, true);
}

}  // namespace
}  // namespace fluidbed
