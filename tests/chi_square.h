// Pearson's chi-square goodness-of-fit test of a direction sampler against its
// density, as pbrt-v4 (src/pbrt/bsdfs_test.cpp) and Mitsuba (chi2.py) test
// theirs: bin the sphere in (cosθ, φ), histogram many samples, integrate the
// density over each bin numerically, pool bins with small expected counts, and
// reject when the p-value is below a Šidák-corrected significance level.
#pragma once

#include <boost/math/distributions/chi_squared.hpp>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"

namespace pathlab::testing {

struct ChiSquareResult {
    double pValue = 0;
    int degreesOfFreedom = 0;
    std::string detail;
};

// sample(i) returns a direction (or nothing when sampling failed — such samples
// count towards no bin, so the density must account for the failure mass);
// pdf(w) is the solid-angle density. Bins are uniform in cosθ ∈ [−1,1] and φ,
// so every bin has the same solid angle.
inline ChiSquareResult chiSquareTest(const std::function<std::optional<Vec3f>(int)>& sample,
                                     const std::function<double(Vec3f)>& pdf, int sampleCount,
                                     int cosBins = 16, int phiBins = 32, int sub = 40) {
    auto binOf = [&](Vec3f w) {
        const double c = std::clamp(double(w.z), -1.0, 1.0);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2 * M_PI;
        const int i = std::min(cosBins - 1, int((c + 1) / 2 * cosBins));
        const int j = std::min(phiBins - 1, int(phi / (2 * M_PI) * phiBins));
        return i * phiBins + j;
    };
    std::vector<double> observed(size_t(cosBins * phiBins), 0.0), expected(observed.size(), 0.0);
    for (int s = 0; s < sampleCount; ++s)
        if (auto w = sample(s)) observed[size_t(binOf(*w))] += 1;
    // Integrate the density over each bin with a sub×sub midpoint rule in (cosθ, φ),
    // where the solid-angle measure is dcosθ·dφ.
    for (int i = 0; i < cosBins; ++i)
        for (int j = 0; j < phiBins; ++j) {
            double sum = 0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const double c = -1 + (i + (a + 0.5) / sub) * 2.0 / cosBins;
                    const double phi = (j + (b + 0.5) / sub) * 2 * M_PI / phiBins;
                    const double s = std::sqrt(std::max(0.0, 1 - c * c));
                    sum += pdf(Vec3f(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c)));
                }
            const double binArea = (2.0 / cosBins) * (2 * M_PI / phiBins);
            expected[size_t(i * phiBins + j)] = sum / (sub * sub) * binArea * sampleCount;
        }
    // Pool bins expected to receive fewer than 5 samples.
    double chi2 = 0, pooledObs = 0, pooledExp = 0;
    int dof = -1;
    for (size_t k = 0; k < observed.size(); ++k) {
        if (expected[k] < 5) {
            pooledObs += observed[k];
            pooledExp += expected[k];
            continue;
        }
        const double d = observed[k] - expected[k];
        chi2 += d * d / expected[k];
        ++dof;
    }
    if (pooledExp > 5) {
        const double d = pooledObs - pooledExp;
        chi2 += d * d / pooledExp;
        ++dof;
    } else if (pooledObs > 10) {
        // Samples land where the density says almost none should.
        return {0.0, dof, "samples in bins of near-zero density: " + std::to_string(pooledObs)};
    }
    ChiSquareResult r;
    r.degreesOfFreedom = dof;
    if (dof < 1) return r;
    const boost::math::chi_squared dist(dof);
    r.pValue = 1 - boost::math::cdf(dist, chi2);
    r.detail = "chi2=" + std::to_string(chi2) + " dof=" + std::to_string(dof);
    return r;
}

// Šidák correction: the per-test significance for `tests` tests at overall level alpha.
inline double sidakSignificance(double alpha, int tests) {
    return 1 - std::pow(1 - alpha, 1.0 / tests);
}

}  // namespace pathlab::testing
