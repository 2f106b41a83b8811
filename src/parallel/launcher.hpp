#pragma once
// How many processes an MPI launcher started and which one this is, read from the environment the launcher sets
// (Open MPI's mpirun, an MPICH/Hydra PMI launcher, Slurm's srun) without initialising MPI: a run can refuse a
// launch it cannot use before any process writes anything.
#include <algorithm>
#include <cstdlib>

namespace fluidbed {

struct LaunchedAs {
  int size = 1;  ///< processes of the launch; 1 without a launcher
  int rank = 0;  ///< this process among them
};

inline LaunchedAs launched_as() {
  const char* pairs[][2] = {{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"},
                            {"PMI_SIZE", "PMI_RANK"},
                            {"SLURM_STEP_NUM_TASKS", "SLURM_PROCID"}};
  for (const auto& p : pairs) {
    const char* size = std::getenv(p[0]);
    if (size == nullptr || *size == '\0') continue;
    const char* rank = std::getenv(p[1]);
    LaunchedAs l;
    l.size = std::max(1, std::atoi(size));
    l.rank = rank ? std::atoi(rank) : 0;
    return l;
  }
  return {};
}

}  // namespace fluidbed
