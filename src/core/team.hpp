#pragma once
// The calling thread's place in its OpenMP team, for loops that share fixed blocks among the threads: a block's
// result does not depend on which thread runs it, so the outputs are the same for any thread count.
// OpenMP is a required dependency (CMakeLists.txt), so there is no serial fallback to keep in step.
#include <cstddef>
#include <omp.h>

namespace fluidbed {

struct TeamSlot {
  std::size_t index;  ///< this thread's number in the team, 0 .. size - 1
  std::size_t size;   ///< threads in the team
};

inline TeamSlot team_slot() {
  return {static_cast<std::size_t>(omp_get_thread_num()), static_cast<std::size_t>(omp_get_num_threads())};
}

}  // namespace fluidbed
