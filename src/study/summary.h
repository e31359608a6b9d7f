// The table a study prints when it ends: per scene and sampler, the
// convergence slope, the MSE ratio to independent sampling at 1, 8 and 64 spp
// and the time to reach the target error.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "study/results_store.h"

namespace pathlab {

std::string summaryTable(const nlohmann::ordered_json& analysis,
                         const std::vector<ReferenceRow>& references);

}  // namespace pathlab
