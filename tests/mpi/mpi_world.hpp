#pragma once
// The world communicator of the MPI test program (tests/mpi: one executable run on 1 to 4 ranks).
#include "parallel/mpi_comm.hpp"

namespace fluidbed {

inline const MpiComm& world() {
  static const MpiComm comm;
  return comm;
}

}  // namespace fluidbed
