// The parallel layer's headers compile on their own (the MPI work fills this folder: ranks, halos, reductions,
// particle exchange).
#include "parallel/comm.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/launcher.hpp"
#include "parallel/mpi_comm.hpp"
#include "parallel/periodic_halo.hpp"
