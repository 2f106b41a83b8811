#pragma once

#include <exception>
#include <omp.h>

#include "core/index_box.hpp"
#include "numerics/stencil_matrix.hpp"

namespace fluidbed {

/// The number of lines along axis 0 of box b (the product of its other extents).
template <int Dim>
int line_count(const IndexBox<Dim>& b) {
  int n = 1;
  for (int a = 1; a < Dim; ++a) n *= b.extent(a);
  return b.empty() ? 0 : n;
}

/// The first index (at b.lo[0]) of line l of box b, lines numbered axis 1 fastest, as for_each visits them.
template <int Dim>
Index<Dim> line_start(const IndexBox<Dim>& b, int l) {
  Index<Dim> c = b.lo;
  c[1] += l % b.extent(1);
  if constexpr (Dim == 3) c[2] += l / b.extent(1);
  return c;
}

/// Calls f(line start) for every line along axis 0 of box b, the lines split into contiguous static blocks over
/// the OpenMP threads. Only for loops in which each index writes its own outputs and reads nothing another writes:
/// every output is then the same bits at any thread count. Call it outside any parallel region. Boxes under
/// kParallelCells run serially, as in the gas solver: on the paper's 30 x 50 grid two threads lost to one
/// (docs/performance.md section 17, threads).
template <int Dim, class F>
void for_each_line_parallel(const IndexBox<Dim>& b, F&& f) {
  const int n = line_count(b);
  if (static_cast<int>(b.count()) < kParallelCells) {  // no OpenMP region at all: the serial code as it was
    for (int l = 0; l < n; ++l) f(line_start(b, l));
    return;
  }
#pragma omp parallel for schedule(static)
  for (int l = 0; l < n; ++l) f(line_start(b, l));
}

/// As for_each_line_parallel, for loops that keep per-thread state across the lines of a block (a carried flux):
/// make() builds one state per thread, f(state, line start) runs the lines of the thread's block in order.
template <int Dim, class Make, class F>
void for_each_line_parallel_with(const IndexBox<Dim>& b, Make&& make, F&& f) {
  const int n = line_count(b);
  if (static_cast<int>(b.count()) < kParallelCells) {
    auto state = make();
    for (int l = 0; l < n; ++l) f(state, line_start(b, l));
    return;
  }
#pragma omp parallel
  {
    auto state = make();
#pragma omp for schedule(static)
    for (int l = 0; l < n; ++l) f(state, line_start(b, l));
  }
}

/// Whether side_by_side runs its two tasks on two threads for a grid of `cells` cells: only below kParallelCells,
/// where the per-line loops above are serial, so that one fork per pair of tasks replaces none (the barriers of
/// per-loop threads lost on the paper's grid), and only outside any parallel region.
inline bool two_tasks(long cells) {
  return cells < kParallelCells && omp_get_max_threads() > 1 && !omp_in_parallel();
}

/// Runs f0() and f1(), on two threads when `parallel`, else one after the other. Only for tasks that write
/// disjoint outputs and read nothing the other writes: the same bits either way. An exception of either task is
/// rethrown after both have finished (f0's first).
template <class F0, class F1>
void side_by_side(bool parallel, F0&& f0, F1&& f1) {
  if (!parallel) {
    f0();
    f1();
    return;
  }
  std::exception_ptr e0, e1;
#pragma omp parallel sections num_threads(2)
  {
#pragma omp section
    {
      try {
        f0();
      } catch (...) {
        e0 = std::current_exception();
      }
    }
#pragma omp section
    {
      try {
        f1();
      } catch (...) {
        e1 = std::current_exception();
      }
    }
  }
  if (e0) std::rethrow_exception(e0);
  if (e1) std::rethrow_exception(e1);
}

}  // namespace fluidbed
