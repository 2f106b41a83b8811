// The two-fluid model's implicit solids continuity and packing limiter on a rank's block (ctest runs this under
// mpiexec -n 1..4) against the same on one process, bit for bit: the new solids fraction of every cell, the flux of
// every face of the block (the faces it shares with a neighbour included) and the limiter's sweeps, in 2D and 3D,
// walled and periodic, cut along y, along z and both. The block's ghosts come from fill_block_ghosts; the solves
// from StencilBicgstab. Each rank also runs the one-process reference (the grids are small).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "parallel/decomposition.hpp"
#include "tfm/packing_limiter.hpp"
#include "tfm/tvd_convection.hpp"
#include "mpi_world.hpp"

namespace fluidbed::tfm {
namespace {

// A value in [-1, 1] from a global index and a salt.
template <int Dim>
double wave(const Index<Dim>& c, int salt) {
  double phase = 0.7 * salt;
  for (int a = 0; a < Dim; ++a) phase += (0.43 + 0.19 * a) * c[a] + 0.017 * c[a] * c[a];
  return std::sin(phase);
}

template <int Dim>
struct Problem {
  FaceFields<Dim> u;
  Field<Dim> phi;
};

// Velocities of both signs on every face of the block (a periodic axis's face n equal to face 0, as the solver ties
// it), the solids fraction in [0.05, 0.6] in every cell: converging flows push cells past the bound.
template <int Dim>
Problem<Dim> problem(const Grid<Dim>& g) {
  Problem<Dim> p{FaceFields<Dim>(g.owned, kGhost), Field<Dim>(g.owned, kGhost)};
  for (int a = 0; a < Dim; ++a)
    for_each(g.owned.faces(a), [&](const Index<Dim>& f) {
      Index<Dim> k = f;
      k[a] = g.periodic[static_cast<std::size_t>(a)] ? g.wrap(a, f[a]) : f[a];
      const bool wall = !g.periodic[static_cast<std::size_t>(a)] && (f[a] == g.domain.lo[a] || f[a] == g.domain.hi[a]);
      p.u[a][f] = wall ? 0.0 : 0.3 * wave<Dim>(k, a);
    });
  for_each(g.owned, [&](const Index<Dim>& c) { p.phi[c] = 0.325 + 0.275 * wave<Dim>(c, 7); });
  return p;
}

template <int Dim>
void check(const Index<Dim>& n, const std::array<bool, Dim>& periodic, const Index<Dim>& blocks) {
  Vec<Dim> ext{};
  for (int a = 0; a < Dim; ++a) ext[a] = 0.01 * n[a];
  Grid<Dim> whole = Grid<Dim>::uniform(ext, n, kGhost);
  whole.periodic = periodic;
  Grid<Dim> part = whole;
  part.owned = block_of<Dim>(whole.domain, blocks, world().rank());
  const double dt = 0.5 * 0.01 / 0.3;
  const double bound = 0.55;
  Problem<Dim> pw = problem(whole), pp = problem(part);
  FaceFluxes<Dim> fw, fp;
  ImplicitTransportWork<Dim> ww, wp;
  const Field<Dim> nw = advance_scalar_implicit<Dim>(whole, Limiter::Superbee, pw.phi, FaceVelocity<Dim>{pw.u, periodic},
                                                     dt, 2, fw, 0, nullptr, &ww, serial_comm());
  const Field<Dim> np = advance_scalar_implicit<Dim>(part, Limiter::Superbee, pp.phi, FaceVelocity<Dim>{pp.u, periodic},
                                                     dt, 2, fp, 0, nullptr, &wp, world());
  const PackingLimitResult lw = limit_packing<Dim>(whole, pw.phi, dt, bound, fw, 1000, serial_comm());
  const PackingLimitResult lp = limit_packing<Dim>(part, pp.phi, dt, bound, fp, 1000, world());
  EXPECT_GT(lw.faces_limited, 0) << "the problem must make the limiter cut";
  EXPECT_EQ(lp.sweeps, lw.sweeps);
  const Field<Dim> cw = conservative_update(whole, pw.phi, fw, dt), cp = conservative_update(part, pp.phi, fp, dt);
  auto same = [](double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y); };
  int bad_cells = 0, bad_faces = 0;
  for_each(part.owned, [&](const Index<Dim>& c) {
    bad_cells += same(np[c], nw[c]) && same(cp[c], cw[c]) ? 0 : 1;
  });
  for (int a = 0; a < Dim; ++a)
    for_each(part.owned.faces(a), [&](const Index<Dim>& f) { bad_faces += same(fp[a][f], fw[a][f]) ? 0 : 1; });
  EXPECT_EQ(world().sum(static_cast<double>(bad_cells)), 0.0) << world().size() << " ranks: cells differ";
  EXPECT_EQ(world().sum(static_cast<double>(bad_faces)), 0.0) << world().size() << " ranks: faces differ";
}

TEST(TfmTransportRanks, Walled2dCutAlongY) { check<2>({24, 31}, {false, false}, {1, world().size()}); }
TEST(TfmTransportRanks, PeriodicX2dCutAlongY) { check<2>({20, 29}, {true, false}, {1, world().size()}); }
TEST(TfmTransportRanks, Walled3dCutAlongYAndZ) {
  const int p = world().size();
  check<3>({9, 13, 10}, {false, false, false}, {1, p, 1});
  check<3>({9, 13, 10}, {false, false, false}, {1, 1, p});
  if (p == 4) check<3>({9, 13, 10}, {false, false, false}, {1, 2, 2});
}
TEST(TfmTransportRanks, PeriodicXZ3dCutAlongY) { check<3>({8, 14, 6}, {true, false, true}, {1, world().size(), 1}); }

}  // namespace
}  // namespace fluidbed::tfm
