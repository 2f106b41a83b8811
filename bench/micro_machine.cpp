// The machine's own limits, the yardstick of every kernel (issue 31, item 1): memory bandwidth by STREAM's four
// kernels (McCalpin 1995) on arrays far larger than the caches, on one thread and on all (OpenMP), and a core's
// double-precision peak by independent fused multiply-add chains held in registers. The byte counts are STREAM's: copy
// and scale move 16 bytes an element, add and triad 24 (write-allocate traffic not counted, as STREAM does not).
//   build/bench/bench_micro_machine --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace {

constexpr std::size_t kElements = std::size_t{1} << 24;  // 128 MiB an array: far beyond any cache

struct Arrays {
  std::vector<double> a = std::vector<double>(kElements, 1.0);
  std::vector<double> b = std::vector<double>(kElements, 2.0);
  std::vector<double> c = std::vector<double>(kElements, 0.0);
};

Arrays& arrays() {
  static Arrays x;  // touched once, so the pages are mapped before any timing
  return x;
}

// kind: 0 copy c = a, 1 scale b = s c, 2 add c = a + b, 3 triad a = b + s c.
template <int kind>
void stream(benchmark::State& state) {
  Arrays& x = arrays();
  const int threads = static_cast<int>(state.range(0));
  double* a = x.a.data();
  double* b = x.b.data();
  double* c = x.c.data();
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

void peak(benchmark::State& state) {
  const long rounds = 1 << 18;
  for (auto _ : state) benchmark::DoNotOptimize(chains(rounds));
  state.counters["GFLOP/s"] = benchmark::Counter(2.0 * kChains * static_cast<double>(rounds) * 1e-9,
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

void thread_counts(benchmark::internal::Benchmark* b) {
  b->Arg(1);
  if (omp_get_max_threads() > 1) b->Arg(omp_get_max_threads());
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(stream<0>)->Name("StreamCopy")->Apply(thread_counts);
BENCHMARK(stream<1>)->Name("StreamScale")->Apply(thread_counts);
BENCHMARK(stream<2>)->Name("StreamAdd")->Apply(thread_counts);
BENCHMARK(stream<3>)->Name("StreamTriad")->Apply(thread_counts);
BENCHMARK(peak)->Name("PeakMultiplyAdd")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
