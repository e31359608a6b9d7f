// Is a sampler biased? Per scene, sampler and spp, the mean of the cells'
// relative bias over the seeds with its Student-t 95% confidence half-width,
// and a verdict (bias.csv, docs/study-output.md). MSE cannot tell a biased
// sampler from a noisy one; the sign of the error averaged over seeds can.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "study/results_store.h"

namespace pathlab {

// The relative bias no verdict calls biased: 0.5% of the reference's mean.
// It absorbs the reference's own error, which every cell of a scene shares
// (at the default 4096 spp its relative error on the image mean is about
// 1e-4 on the Cornell box), and the error of the image mean at the low spp
// of a few seeds (the verdict asks the whole interval to lie beyond it).
inline constexpr double kBiasTolerance = 0.005;

// What the `biased` column says besides 1 and 0.
inline constexpr const char* kBiasDeterministic = "deterministic";
inline constexpr const char* kBiasTooFewSeeds = "too few seeds";

struct BiasRow {
    std::string scene, sampler;
    int spp = 0, seeds = 0;
    std::optional<double> bias;  // mean relative bias over the seeds that measured it
    std::optional<double> ci95;  // half-width; nullopt below two seeds or when deterministic
    // "1" when the interval [bias − ci95, bias + ci95] lies wholly beyond
    // ±kBiasTolerance (so it excludes 0 and |bias| exceeds the tolerance),
    // "0" when it does not, kBiasDeterministic for a sampler whose image the
    // seed does not change (its error is the same fixed error at every seed,
    // not a bias over seeds), kBiasTooFewSeeds below two seeds.
    std::string biased;
};

// One row per (scene, sampler, spp), in the order the cells first name them.
std::vector<BiasRow> analyzeBias(const std::vector<CellRow>& cells);

// bias.csv: scene,sampler,spp,seeds,bias,ci95,biased.
std::string biasCsv(const std::vector<BiasRow>& rows);

// Student's t quantile for a two-sided 95% interval with `dof` ≥ 1 degrees of freedom.
double studentT975(int dof);

}  // namespace pathlab
