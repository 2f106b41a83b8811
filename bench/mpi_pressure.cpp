// The cg-multigrid pressure backend over ranks (docs/parallel.md, "The pressure solve over ranks"): one gas step's
// solves as the SIMPLE loop makes them (a fresh solve, then 8 with the coefficients moved by 1e-3 and a warm start,
// as bench/micro_pressure.cpp), on a 3D grid cut into blocks by block_counts. Prints the median wall time of 5 such
// steps (the slowest rank's), the iterations, the time inside communication and the answer's checksum (the same
// bits on every rank count: compare the lines of two runs).
// Run: mpirun -n P build/bench/bench_mpi_pressure [NX NY NZ]   (default 60 60 60: 216,000 cells)
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "numerics/multigrid_cg.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/mpi_comm.hpp"

int main(int argc, char** argv) {
  using namespace fluidbed;
  const MpiComm comm;
  Index<3> n{60, 60, 60};
  for (int a = 0; a < 3 && a + 1 < argc; ++a) n[a] = std::atoi(argv[a + 1]);
  Grid<3> grid = Grid<3>::uniform({1.0, 1.0, 1.0}, n, 1);
  grid.owned = block_of<3>(grid.domain, block_counts<3>(comm.size(), n), comm.rank());
  // Coefficients varying by +-30%, fixed pressure on the top, as bench/micro_pressure.cpp.
  FaceFields<3> coeff(grid.owned, 0, 0.0);
  for (int a = 0; a < 3; ++a) {
    for_each(grid.owned.faces(a), [&](const Index<3>& f) {
      const bool side = f[a] == grid.domain.lo[a] || f[a] == grid.domain.hi[a];
      coeff[a][f] = side ? (a == 1 && f[a] == grid.domain.hi[a] ? 2.0 : 0.0) : 1.0 + 0.3 * std::sin(0.7 * f[0] + 0.3 * a);
    });
  }
  Field<3> rhs(grid.owned, 0);
  for_each(grid.owned, [&](const Index<3>& c) { rhs[c] = std::sin(0.37 * c[0] + 0.11 * c[1] + 0.05 * c[2]); });
  auto solver = make_multigrid_cg_solver<3>(grid, comm, {.tolerance = 1e-12});
  std::vector<double> wall;
  int iterations = 0;
  double inside = 0.0, checksum = 0.0;
  for (int rep = 0; rep < 5; ++rep) {
    Field<3> x(grid.owned, 0);
    FaceFields<3> c = coeff;
    comm.barrier();
    const double comm0 = comm.seconds_communicating();
    const auto t0 = std::chrono::steady_clock::now();
    iterations = 0;
    for (int it = 0; it < 9; ++it) {
      for (int a = 0; a < 3; ++a)
        for (double& v : c[a].data()) v *= 1.0 + 1e-3 * ((it + a) % 3 - 1);
      solver->solve(c, rhs, x, it > 0);
      iterations += multigrid_cg_stats<3>(*solver).iterations;
    }
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    inside = comm.max(comm.seconds_communicating() - comm0);
    wall.push_back(comm.max(t));
    ExactSum s;
    for_each(grid.owned, [&](const Index<3>& q) { s.add(x[q]); });
    checksum = comm.sum(s);
  }
  std::sort(wall.begin(), wall.end());
  if (comm.rank() == 0)
    std::printf("ranks %d, %d x %d x %d cells, %d levels: one step (9 solves, %d iterations) median %.1f ms, "
                "communication (last step, slowest rank) %.1f ms, sum of the answer %.17g (bits %016llx)\n",
                comm.size(), n[0], n[1], n[2], multigrid_cg_stats<3>(*solver).levels, iterations, 1e3 * wall[2],
                1e3 * inside, checksum, static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(checksum)));
  return 0;
}
