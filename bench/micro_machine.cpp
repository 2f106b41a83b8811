// The machine's own limits, the yardstick of every kernel (issue 31, item 1):
// - memory bandwidth by STREAM's four kernels (McCalpin 1995) on arrays far larger than the caches, on one thread and
//   on all (OpenMP);
// - the bandwidth of each level of the cache hierarchy (L1, L2, L3, memory), one thread and all: a read-only sum, copy
//   and triad over working sets that fit the level (all arrays of the kernel together), swept many times in one
//   parallel region so that small sizes time the sweep and not the loop or the fork; compiled, as the solver is, for
//   the x86-64 baseline (16-byte SSE2), so where the core's issue of 16-byte loads binds (L1, L2) they give what the
//   solver's loops can draw from the cache, not the cache's own limit;
// - a core's double-precision peak by independent fused multiply-add chains held in registers (the widest vectors);
// - the scalar arithmetic rate the solver's own code gets: the same chains as x86-64 baseline mulsd + addsd;
// - the throughput (not the latency) of scalar square root and division, sqrtsd and divsd, and of std::pow, by
//   independent chains.
// The byte counts are STREAM's: read moves 8 bytes an element, copy and scale 16, add and triad 24 (write-allocate
// traffic not counted, as STREAM does not). Cycles are nominal ones at 2.6 GHz (the VM's usual host reports 2596 MHz;
// the clock it reports is printed in the header of the output); a boosted core does more in a nominal cycle.
//   build/bench/bench_micro_machine --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

constexpr std::size_t kElements = std::size_t{1} << 24;  // 128 MiB an array: far beyond any cache

// Elements an array at each level, so that the three arrays of triad fit together: 24 KiB in the 32 KiB L1d, 768 KiB
// in the 1 MiB L2, 12 MiB in the 32 MiB L3 (shared), and STREAM's arrays for memory. Powers of two, so that every
// thread's half is a whole number of the read kernel's 16-element blocks.
constexpr int kLevels = 4, kMemory = 3;
constexpr std::size_t kLevelElements[kLevels] = {std::size_t{1} << 10, std::size_t{1} << 15, std::size_t{1} << 19,
                                                 kElements};
constexpr const char* kLevelNames[kLevels] = {"L1", "L2", "L3", "memory"};

// The three arrays in one page-aligned block, 1 KiB apart modulo the 4 KiB page: no load follows closely a store to
// the same offset within a page (4K aliasing, which stalls the load), as happens with separately allocated vectors
// of 8 KiB (16416 bytes apart: the load of a[i + 4] would wait for the store to c[i]).
struct Arrays {
  explicit Arrays(std::size_t n) : block(3 * n + 1024, 0.0) {
    const auto p = reinterpret_cast<std::uintptr_t>(block.data());
    a = block.data() + (-p % 4096) / sizeof(double);
    b = a + n + 128;
    c = b + n + 128;
    std::fill(a, a + n, 1.0);
    std::fill(b, b + n, 2.0);
  }
  std::vector<double> block;
  double* a;
  double* b;
  double* c;
};

Arrays& arrays(int level) {
  // Allocated and touched once, so the pages are mapped before any timing.
  static Arrays x[kLevels] = {Arrays(kLevelElements[0]), Arrays(kLevelElements[1]), Arrays(kLevelElements[2]),
                              Arrays(kLevelElements[3])};
  return x[level];
}

// kind: 0 copy c = a, 1 scale b = s c, 2 add c = a + b, 3 triad a = b + s c.
template <int kind>
void stream(benchmark::State& state) {
  Arrays& x = arrays(kMemory);
  const int threads = static_cast<int>(state.range(0));
  double* a = x.a;
  double* b = x.b;
  double* c = x.c;
  const double s = 3.0;
  const auto n = static_cast<std::ptrdiff_t>(kElements);
  for (auto _ : state) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      if constexpr (kind == 0) c[i] = a[i];
      if constexpr (kind == 1) b[i] = s * c[i];
      if constexpr (kind == 2) c[i] = a[i] + b[i];
      if constexpr (kind == 3) a[i] = b[i] + s * c[i];
    }
    benchmark::ClobberMemory();
  }
  const double bytes = (kind < 2 ? 16.0 : 24.0) * static_cast<double>(kElements);
  state.counters["GB/s"] = benchmark::Counter(bytes * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

// A sum of a[lo, hi) for measurement only: 16 partial sums (eight SSE2 registers) so that the adds' latency does not
// bound the loads, and added up as a tree so that the short sweeps of L1 do not wait on a chain of 16 adds; it is not
// the ordered sum any kernel of the solver may rely on.
double read_sum(const double* a, std::ptrdiff_t lo, std::ptrdiff_t hi) {
  double s[16] = {};
  for (std::ptrdiff_t i = lo; i < hi; i += 16)
    for (int j = 0; j < 16; ++j) s[j] += a[i + j];
  for (int w = 8; w > 0; w /= 2)
    for (int j = 0; j < w; ++j) s[j] += s[j + w];
  return s[0];
}

// One sweep of [lo, hi). kind: 0 read s += a, 1 copy c = a, 2 triad a = b + s c.
template <int kind>
void sweep(Arrays& x, std::ptrdiff_t lo, std::ptrdiff_t hi) {
  double* a = x.a;
  const double* b = x.b;
  double* c = x.c;
  const double s = 3.0;
  if constexpr (kind == 0) benchmark::DoNotOptimize(read_sum(a, lo, hi));
  if constexpr (kind == 1)
    for (std::ptrdiff_t i = lo; i < hi; ++i) c[i] = a[i];
  if constexpr (kind == 2)
    for (std::ptrdiff_t i = lo; i < hi; ++i) a[i] = b[i] + s * c[i];
  benchmark::ClobberMemory();  // every sweep is done: none is merged with the next or dropped
}

// Every iteration sweeps the level's arrays kElements / n times (2^24 elements in all, milliseconds at every level),
// in one parallel region, so the fork is paid once an iteration, not once a sweep; each thread sweeps its own half,
// with no barrier between sweeps: on this VM a barrier costs 1.5-6 us (and milliseconds when the other core is busy),
// against about 0.1 us for a thread's half of the L1 arrays, so a barrier a sweep would time the barrier.
template <int kind>
void level(benchmark::State& state) {
  const int lv = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  Arrays& x = arrays(lv);
  const auto n = static_cast<std::ptrdiff_t>(kLevelElements[lv]);
  const std::ptrdiff_t sweeps = static_cast<std::ptrdiff_t>(kElements) / n;
  for (auto _ : state) {
#pragma omp parallel num_threads(threads)
    {
      const std::ptrdiff_t t = omp_get_thread_num(), nt = omp_get_num_threads();
      const std::ptrdiff_t lo = n * t / nt, hi = n * (t + 1) / nt;
      for (std::ptrdiff_t r = 0; r < sweeps; ++r) sweep<kind>(x, lo, hi);
    }
  }
  const double bytes = (kind == 0 ? 8.0 : kind == 1 ? 16.0 : 24.0) * static_cast<double>(kElements);
  state.counters["GB/s"] = benchmark::Counter(bytes * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(kLevelNames[lv]);
}

// 64 independent chains x = fma(x, m, k): enough vector registers' worth to cover the multiply-add latency on two
// pipes; the clones let the compiler use the machine's widest vectors with FMA. 2 flops an update.
constexpr int kChains = 64;

[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]] double chains(long rounds) {
  double x[kChains];
  for (int j = 0; j < kChains; ++j) x[j] = 1.0 + 1e-3 * j;
  const double m = 0.999999, k = 1e-6;
  for (long r = 0; r < rounds; ++r)
    for (int j = 0; j < kChains; ++j) x[j] = std::fma(x[j], m, k);
  double s = 0.0;
  for (double v : x) s += v;
  return s;
}

// The same chains as the solver's scalar loops run them: the build targets the x86-64 baseline (no FMA) with
// -ffp-contract=off, so x m + k is a mulsd and an addsd, and with the vectoriser off here it stays scalar (no packed
// mulpd / addpd): the most a scalar loop of the solver can do. 2 flops an update. 12 chains, not 64: they and m, k fit
// the 16 SSE registers and cover the multiply-add latency on two pipes, where 64 would live on the stack and time its
// loads and stores (a fifth slower). noipa: a pure function of a constant, it would otherwise run once.
constexpr int kScalarChains = 12;

[[gnu::noipa, gnu::optimize("no-tree-vectorize")]] double scalar_chains(long rounds) {
  double x[kScalarChains];  // none starts at 1, the fixed point of x m + k, which the compiler would see and drop
  for (int j = 0; j < kScalarChains; ++j) x[j] = 1.0 + 1e-3 * (j + 1);
  const double m = 0.999999, k = 1e-6;
  for (long r = 0; r < rounds; ++r)
    for (int j = 0; j < kScalarChains; ++j) x[j] = x[j] * m + k;
  double s = 0.0;
  for (double v : x) s += v;
  return s;
}

// 16 independent chains of square roots or divisions: more in flight than either unit's latency over its issue
// interval, so the time an operation is the throughput. Scalar (sqrtsd, divsd) as in the solver; std::sqrt keeps its
// errno check (a compare and a branch never taken), as the solver's does; noipa as above.
constexpr int kSlowChains = 16;

// The chains x_j = step(x_j) from x_j = start + 1e-3 j, summed at the end so that none is dropped.
template <class Step>
[[gnu::always_inline]] inline double slow_chains(long rounds, double start, Step step) {
  double x[kSlowChains];
  for (int j = 0; j < kSlowChains; ++j) x[j] = start + 1e-3 * j;
  for (long r = 0; r < rounds; ++r)
    for (int j = 0; j < kSlowChains; ++j) x[j] = step(x[j]);
  double s = 0.0;
  for (double v : x) s += v;
  return s;
}

[[gnu::noipa, gnu::optimize("no-tree-vectorize")]] double sqrt_chains(long rounds) {
  return slow_chains(rounds, 2.0, [](double x) { return std::sqrt(x) + 1.0; });  // towards 2.618..., never 1 or 0
}

[[gnu::noipa, gnu::optimize("no-tree-vectorize")]] double divide_chains(long rounds) {
  // Not a power of two: no multiply by the reciprocal; x grows by under 2% in 2^14 rounds.
  return slow_chains(rounds, 1.0, [](double x) { return x / 0.999999; });
}

// std::pow with a non-integer exponent, the drag laws' transcendental (Eqs. 13-14: eps^-2.65, Re^0.687): a libm
// call an operation.
[[gnu::noipa, gnu::optimize("no-tree-vectorize")]] double pow_chains(long rounds) {
  return slow_chains(rounds, 0.4, [](double x) { return 0.5 * std::pow(x, -2.65) + 0.3; });  // stays in [0.3, 4]
}

constexpr double kNominalHz = 2.6e9;  // the VM's nominal clock (2596 MHz on its usual host), not the boosted one

// Times the benchmark loop, for counters an operation or a cycle (the library's own are rates and their inverses,
// printed with a "/s" or "s" suffix).
template <class Body>
double loop_seconds(benchmark::State& state, Body body) {
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) body();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void peak(benchmark::State& state) {
  const long rounds = 1 << 18;
  for (auto _ : state) benchmark::DoNotOptimize(chains(rounds));
  state.counters["GFLOP/s"] = benchmark::Counter(2.0 * kChains * static_cast<double>(rounds) * 1e-9,
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

void scalar_peak(benchmark::State& state) {
  const long rounds = 1 << 18;
  const double seconds = loop_seconds(state, [&] { benchmark::DoNotOptimize(scalar_chains(rounds)); });
  const double flops = 2.0 * kScalarChains * static_cast<double>(rounds) * static_cast<double>(state.iterations());
  state.counters["GFLOP/s"] = flops * 1e-9 / seconds;
  state.counters["flops/cycle"] = flops / (seconds * kNominalHz);
}

// kind: 0 sqrtsd, 1 divsd, 2 std::pow.
template <int kind>
void slow_op(benchmark::State& state) {
  const long rounds = 1 << 14;
  const double seconds = loop_seconds(state, [&] {
    benchmark::DoNotOptimize(kind == 0 ? sqrt_chains(rounds) : kind == 1 ? divide_chains(rounds) : pow_chains(rounds));
  });
  const double ops = kSlowChains * static_cast<double>(rounds) * static_cast<double>(state.iterations());
  state.counters["ns/op"] = seconds * 1e9 / ops;
  state.counters["cycles/op"] = seconds * kNominalHz / ops;
}

void thread_counts(benchmark::internal::Benchmark* b) {
  b->Arg(1);
  if (omp_get_max_threads() > 1) b->Arg(omp_get_max_threads());
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

void levels_and_threads(benchmark::internal::Benchmark* b) {
  for (int lv = 0; lv < kLevels; ++lv) {
    b->Args({lv, 1});
    if (omp_get_max_threads() > 1) b->Args({lv, omp_get_max_threads()});
  }
  b->ArgNames({"level", "threads"})->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(stream<0>)->Name("StreamCopy")->Apply(thread_counts);
BENCHMARK(stream<1>)->Name("StreamScale")->Apply(thread_counts);
BENCHMARK(stream<2>)->Name("StreamAdd")->Apply(thread_counts);
BENCHMARK(stream<3>)->Name("StreamTriad")->Apply(thread_counts);
BENCHMARK(level<0>)->Name("LevelRead")->Apply(levels_and_threads);
BENCHMARK(level<1>)->Name("LevelCopy")->Apply(levels_and_threads);
BENCHMARK(level<2>)->Name("LevelTriad")->Apply(levels_and_threads);
BENCHMARK(peak)->Name("PeakMultiplyAdd")->Unit(benchmark::kMillisecond);
BENCHMARK(scalar_peak)->Name("ScalarMultiplyAdd")->Unit(benchmark::kMillisecond);
BENCHMARK(slow_op<0>)->Name("ScalarSqrt")->Unit(benchmark::kMillisecond);
BENCHMARK(slow_op<1>)->Name("ScalarDivide")->Unit(benchmark::kMillisecond);
BENCHMARK(slow_op<2>)->Name("ScalarPow")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
