#pragma once
// The two-fluid model behind the run driver.
#include <memory>

#include "config/case_config.hpp"
#include "models/model_run.hpp"

namespace fluidbed {

std::unique_ptr<ModelRun> make_tfm_model(const CaseConfig& config);

}  // namespace fluidbed
