#pragma once
// The two-fluid model behind the run driver.
#include <memory>

#include "config/case_config.hpp"
#include "models/model_run.hpp"
#include "parallel/comm.hpp"

namespace fluidbed {

/// The model on the ranks of `comm` (which must outlive it): each holds a block of the grid (docs/parallel.md).
std::unique_ptr<ModelRun> make_tfm_model(const CaseConfig& config, const Comm& comm = serial_comm());

}  // namespace fluidbed
