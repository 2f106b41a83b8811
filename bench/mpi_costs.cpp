// The costs of the parallel layer's primitives on the machine it runs on, for the performance model of
// docs/parallel.md: the neighbour exchange the ghosts take every step (latency and bandwidth from a ring of ranks,
// messages of 8 B to 4 MB), the step's reduction (a maximum of 5 doubles), and the exact sum (ExactSum: the
// local accumulation per term and the reduction of the accumulators over ranks).
// Run: mpirun -n 2 build/bench/bench_mpi_costs   (medians of 7 timings of REPS repetitions each)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "parallel/exact_sum.hpp"
#include "parallel/mpi_comm.hpp"

namespace {

using Clock = std::chrono::steady_clock;

template <class F>
double median_seconds_per_rep(const fluidbed::Comm& c, int reps, F&& f) {
  std::vector<double> t;
  for (int k = 0; k < 7; ++k) {
    c.barrier();
    const auto t0 = Clock::now();
    for (int r = 0; r < reps; ++r) f();
    // The slowest rank's time: a collective costs what its last rank waits.
    t.push_back(c.max(std::chrono::duration<double>(Clock::now() - t0).count()) / reps);
  }
  std::sort(t.begin(), t.end());
  return t[3];
}

}  // namespace

int main() {
  const fluidbed::MpiComm comm;
  const int p = comm.size(), me = comm.rank();
  if (me == 0) std::printf("ranks %d\n", p);
  // Ring exchange: each rank sends n doubles to the next and the previous rank, as the ghosts of a slab split do.
  std::vector<int> ranks;
  if (p > 1) {
    ranks.push_back((me + 1) % p);
    if (p > 2) ranks.push_back((me + p - 1) % p);
  }
  if (me == 0) std::printf("%12s %14s %14s\n", "bytes/msg", "us/exchange", "MB/s per rank");
  for (std::size_t n : {1ul, 16ul, 256ul, 4096ul, 32768ul, 131072ul, 524288ul}) {
    std::vector<std::vector<double>> send(ranks.size(), std::vector<double>(n, 1.0)), recv(ranks.size(), std::vector<double>(n));
    const int reps = n > 100000 ? 20 : 200;
    const double s = median_seconds_per_rep(comm, reps, [&] { comm.exchange_with(ranks, send, recv); });
    const double bytes = static_cast<double>(n * sizeof(double) * ranks.size());
    if (me == 0) std::printf("%12zu %14.2f %14.1f\n", n * sizeof(double), 1e6 * s, bytes / s / 1e6);
  }
  // The step's reduction: a maximum of five doubles.
  double v[5] = {1, 2, 3, 4, 5};
  const double red = median_seconds_per_rep(comm, 2000, [&] { comm.max(std::span<double>(v)); });
  // The exact sum: adding terms to an accumulator, and reducing accumulators over the ranks.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> terms(100000);
  for (double& x : terms) x = u(rng);
  double sink = 0.0;
  const double add = median_seconds_per_rep(comm, 20, [&] {
    fluidbed::ExactSum e;
    for (double x : terms) e.add(x);
    sink += e.value();
  }) / static_cast<double>(terms.size());
  const double plain = median_seconds_per_rep(comm, 20, [&] {
    double s = 0.0;
    for (double x : terms) s += x;
    sink += s;
  }) / static_cast<double>(terms.size());
  fluidbed::ExactSum acc(0.5);
  const double exact_red = median_seconds_per_rep(comm, 2000, [&] { sink += comm.sum(acc); });
  if (me == 0) {
    std::printf("step reduction (max of 5 doubles): %.2f us\n", 1e6 * red);
    std::printf("exact sum: %.2f ns per term (plain sum %.2f ns), reduction of the accumulators %.2f us\n", 1e9 * add,
                1e9 * plain, 1e6 * exact_red);
    std::printf("(checksum %g)\n", sink);
  }
  return 0;
}
