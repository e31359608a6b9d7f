// The numbers that answer "which sampler gives the best image for the least
// time": convergence slopes, ratios to independent sampling, equal-time error
// and time to a target error, per scene and sampler (analysis.json, whose
// layout docs/study-output.md fixes).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "study/results_store.h"

namespace pathlab {

// The sampler whose final error is every sampler's target.
inline constexpr const char* kTargetSampler = "standard";

// Reference noise biases every MSE up by the reference's noise floor; slopes
// and ratios use mse − floor (clamped at 0), the raw means are kept as well.
nlohmann::ordered_json analyzeStudy(const std::vector<CellRow>& cells,
                                    const std::vector<ReferenceRow>& references,
                                    std::optional<double> timeBudgetSeconds);

// Least-squares slope of y against x; nullopt for fewer than two distinct x.
std::optional<double> leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y);

// A sampler's error curve along its spp list: mean seconds and MSE per spp.
struct ErrorPoint {
    double seconds = 0, mse = 0;
};

// The first time the curve reaches `target`, interpolated linearly in
// (log seconds, log mse); nullopt when it never does.
std::optional<double> timeToReach(const std::vector<ErrorPoint>& curve, double target);

// The MSE at `seconds`, interpolated the same way between the two measured
// points around it; nullopt when the budget lies outside the measured times.
std::optional<double> errorAtTime(const std::vector<ErrorPoint>& curve, double seconds);

}  // namespace pathlab
