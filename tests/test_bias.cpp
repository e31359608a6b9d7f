// Bias as a result: the signed mean error of an image, and the study's
// verdict over seeds, against numbers worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "metrics/bias.h"
#include "study/bias_analysis.h"

namespace pathlab {
namespace {

TEST(Bias, SignedMeanPerChannelAndRelative) {
    // Reference pixels (1,2,3) and (3,2,1): mean 2. The test adds
    // (0.1, −0.2, 0.4) to the first pixel: per channel 0.05, −0.1, 0.2 over
    // two pixels, 0.05 over all six values, 0.025 of the reference's mean.
    Image ref(2, 1), test(2, 1);
    ref.set(0, 0, Vec3f(1, 2, 3));
    ref.set(1, 0, Vec3f(3, 2, 1));
    test.set(0, 0, Vec3f(1.1f, 1.8f, 3.4f));
    test.set(1, 0, Vec3f(3, 2, 1));
    const Bias b = signedBias(ref, test);
    EXPECT_NEAR(b.channels[0], 0.05, 1e-6);
    EXPECT_NEAR(b.channels[1], -0.1, 1e-6);
    EXPECT_NEAR(b.channels[2], 0.2, 1e-6);
    EXPECT_NEAR(b.mean, 0.05, 1e-6);
    EXPECT_DOUBLE_EQ(b.referenceMean, 2.0);
    ASSERT_TRUE(b.relative.has_value());
    EXPECT_NEAR(*b.relative, 0.025, 1e-6);
    // A black reference has no relative bias; sizes must agree.
    EXPECT_FALSE(signedBias(Image(2, 1), test).relative.has_value());
    EXPECT_THROW(signedBias(Image(1, 1), test), InputError);
}

TEST(Bias, StudentQuantilesAreTheTabulatedOnes) {
    // t(0.975) for 1, 3 and 30 degrees of freedom, from any statistics table.
    EXPECT_NEAR(studentT975(1), 12.7062, 1e-4);
    EXPECT_NEAR(studentT975(3), 3.1824, 1e-4);
    EXPECT_NEAR(studentT975(30), 2.0423, 1e-4);
}

CellRow cell(const std::string& sampler, int spp, int seed, std::optional<double> bias) {
    CellRow c;
    c.key = {"scene", sampler, spp, seed};
    c.bias = bias;
    return c;
}

std::vector<CellRow> seeds(const std::string& sampler, int spp, std::vector<double> values) {
    std::vector<CellRow> out;
    for (size_t i = 0; i < values.size(); ++i) out.push_back(cell(sampler, spp, int(i), values[i]));
    return out;
}

TEST(Bias, VerdictNeedsTheIntervalBeyondTheTolerance) {
    std::vector<CellRow> cells;
    // Mean 0.05, sample variance 2e-4/3: half-width t3·√(2e-4/3)/2 ≈ 0.0130.
    for (auto c : seeds("standard", 1, {0.05, 0.06, 0.04, 0.05})) cells.push_back(c);
    // Mean 0.004 excludes 0 (half-width ≈ 0.0013) but is within the tolerance.
    for (auto c : seeds("standard", 2, {0.003, 0.005, 0.004, 0.004})) cells.push_back(c);
    // Mean 0: no bias.
    for (auto c : seeds("standard", 4, {0.1, -0.1, 0.1, -0.1})) cells.push_back(c);
    const std::vector<BiasRow> rows = analyzeBias(cells);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].seeds, 4);
    EXPECT_NEAR(*rows[0].bias, 0.05, 1e-15);
    EXPECT_NEAR(*rows[0].ci95, studentT975(3) * std::sqrt(2e-4 / 3) / 2, 1e-12);
    EXPECT_EQ(rows[0].biased, "1");
    EXPECT_LT(*rows[1].ci95, *rows[1].bias);  // the interval excludes 0 …
    EXPECT_EQ(rows[1].biased, "0");           // … but not the tolerance
    EXPECT_EQ(rows[2].biased, "0");
    // The same verdict for a negative bias.
    EXPECT_EQ(analyzeBias(seeds("standard", 1, {-0.05, -0.06, -0.04, -0.05}))[0].biased, "1");
}

TEST(Bias, DeterministicSamplersAndTooFewSeedsGetWordsNotVerdicts) {
    // halton's image does not depend on the seed: a fixed error, not a bias.
    const auto halton = analyzeBias(seeds("halton", 1, {0.05, 0.05, 0.05}));
    EXPECT_EQ(halton[0].biased, kBiasDeterministic);
    EXPECT_FALSE(halton[0].ci95.has_value());
    // An external renderer's sampler whose seeds give the same image, likewise.
    EXPECT_EQ(analyzeBias(seeds("cycles:sobol", 1, {0.02, 0.02}))[0].biased, kBiasDeterministic);
    const auto one = analyzeBias(seeds("independent", 8, {0.3}));
    EXPECT_EQ(one[0].biased, kBiasTooFewSeeds);
    EXPECT_NEAR(*one[0].bias, 0.3, 1e-15);
    // Rows of an older study, without bias: no values, no verdict.
    EXPECT_EQ(analyzeBias({cell("independent", 1, 0, std::nullopt),
                           cell("independent", 1, 1, std::nullopt)})[0]
                  .biased,
              kBiasTooFewSeeds);
}

TEST(Bias, CsvHasTheDocumentedColumns) {
    const std::string csv = biasCsv(analyzeBias(seeds("halton", 2, {0.25, 0.25})));
    EXPECT_EQ(csv,
              "scene,sampler,spp,seeds,bias,ci95,biased\n"
              "scene,halton,2,2,0.25,,deterministic\n");
}

}  // namespace
}  // namespace pathlab
