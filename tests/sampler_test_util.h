// Helpers shared by the sampler tests: drawing point sets through the same
// calls the renderer makes.
#pragma once

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

}  // namespace pathlab::testing
