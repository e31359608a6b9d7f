// Helpers shared by the sampler tests: drawing point sets through the same
// calls the renderer makes.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "sampling/registry.h"

namespace pathlab::testing {

inline const std::vector<std::string>& allSamplerNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const SamplerInfo& s : samplerInfos()) v.push_back(s.name);
        return v;
    }();
    return names;
}

inline bool isRandomized(const std::string& name) {
    for (const SamplerInfo& s : samplerInfos())
        if (s.name == name) return s.randomized;
    return false;
}

// Points 0..n−1 of `pixel` in dimensions (i, j), for a sampler configured with
// n samples per pixel.
inline std::vector<Vec2f> drawPoints(const std::string& name, int n, int i, int j,
                                     uint64_t seed = 0, Vec2i pixel = {0, 0},
                                     Vec2i resolution = {1, 1}) {
    AnySampler sampler = makeSampler(name, SamplerConfig{n, seed, resolution});
    std::vector<Vec2f> pts(static_cast<size_t>(n));
    std::visit(
        [&](auto& s) {
            for (int k = 0; k < n; ++k) pts[k] = sampleDimensions(s, pixel, k, i, j);
        },
        sampler);
    return pts;
}

// Warnock 1972: the L2-star discrepancy of a 2D point set in closed form,
// T*² = 1/9 − (1/2N) Σ_i Π_k (1 − x_ik²) + (1/N²) Σ_i Σ_j Π_k (1 − max(x_ik, x_jk)).
inline double l2StarDiscrepancy(const std::vector<Vec2f>& pts) {
    const double n = double(pts.size());
    double a = 0, b = 0;
    for (const Vec2f& p : pts) a += (1 - double(p.x) * p.x) * (1 - double(p.y) * p.y);
    for (const Vec2f& p : pts)
        for (const Vec2f& q : pts)
            b += (1 - std::max<double>(p.x, q.x)) * (1 - std::max<double>(p.y, q.y));
    return std::sqrt(std::max(0.0, 1.0 / 9 - a / (2 * n) + b / (n * n)));
}

}  // namespace pathlab::testing
