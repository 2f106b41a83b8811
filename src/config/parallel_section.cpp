// [parallel]: how a run over several MPI ranks deals its work, into CaseConfig::parallel (ParallelConfig,
// config/case_config.hpp). None of it changes a result: a case gives the same bits on any number of ranks.
#include "config/case_sections.hpp"

namespace fluidbed {

namespace case_sections {

void read_parallel(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  c.parallel.rebalance_threshold = r.number(
      "parallel.rebalance_threshold", 1.2, "",
      "on several ranks: deal the blocks of the domain again (along the Hilbert curve, by particles and contacts) "
      "when the busiest rank's cost exceeds this many times the mean; checked at each neighbour-list rebuild",
      R::between(1.0, 1e9));
}

}  // namespace case_sections
}  // namespace fluidbed
