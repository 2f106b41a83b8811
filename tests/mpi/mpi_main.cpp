// main() of the MPI tests: MPI around GoogleTest, one report (rank 0's), and a failure on any rank fails the run.
#include <gtest/gtest.h>

#include "mpi_world.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const fluidbed::Comm& c = fluidbed::world();
  if (c.rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int failed = RUN_ALL_TESTS();
  // Every rank's verdict: a failure on any rank fails the run.
  failed = c.max(failed) > 0 ? 1 : 0;
  return failed;
}
