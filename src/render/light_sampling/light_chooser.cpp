#include "render/light_sampling/light_chooser.h"

#include <algorithm>

namespace pathlab {

LightChooser::LightChooser(LightSelection strategy, const std::vector<double>& powerWeights,
                           const std::vector<std::optional<LightBounds>>& bounds)
    : strategy_(strategy) {
    double total = 0;
    for (double w : powerWeights) total += w;
    if (!(total > 0)) return;
    count_ = powerWeights.size();
    double running = 0;
    for (double w : powerWeights) cdf_.push_back(float((running += w) / total));
    cdf_.back() = 1.0f;
    if (strategy_ != LightSelection::Bvh) return;
    std::vector<LightBounds> tree;
    inTree_.assign(count_, false);
    for (size_t i = 0; i < count_; ++i) {
        if (bounds[i]) {
            treeLight_.push_back(int(i));
            tree.push_back(*bounds[i]);
            inTree_[i] = bounds[i]->phi > 0;
        } else {
            infinite_.push_back(int(i));
        }
    }
    bvh_ = LightBvh(tree);
}

std::optional<ChosenLight> LightChooser::choose(Vec3f p, Vec3f n, float u) const {
    if (count_ == 0) return std::nullopt;
    switch (strategy_) {
        case LightSelection::Power:
            return chooseByPower(u);
        case LightSelection::Uniform:
            return ChosenLight{int(std::min(size_t(u * float(count_)), count_ - 1)),
                               1.0f / float(count_)};
        case LightSelection::Bvh:
            return chooseByBvh(p, n, u);
    }
    return std::nullopt;
}

float LightChooser::pmf(Vec3f p, Vec3f n, size_t light) const {
    if (count_ == 0) return 0;
    switch (strategy_) {
        case LightSelection::Power:
            return powerPmf(light);
        case LightSelection::Uniform:
            return 1.0f / float(count_);
        case LightSelection::Bvh:
            break;
    }
    if (!inTree_[light]) {
        if (std::find(infinite_.begin(), infinite_.end(), int(light)) == infinite_.end()) return 0;
        return infiniteShare() / float(infinite_.size());
    }
    const auto it = std::lower_bound(treeLight_.begin(), treeLight_.end(), int(light));
    return (1 - infiniteShare()) * bvh_.pmf(p, n, int(it - treeLight_.begin()));
}

ChosenLight LightChooser::chooseByPower(float u) const {
    const size_t i = std::min(size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()),
                              cdf_.size() - 1);
    return {int(i), powerPmf(i)};
}

float LightChooser::powerPmf(size_t i) const {
    return cdf_[i] - (i == 0 ? 0.0f : cdf_[i - 1]);
}

// pbrt-v4's BVHLightSampler: the tree counts as one more infinite light.
float LightChooser::infiniteShare() const {
    const size_t n = infinite_.size();
    return float(n) / float(n + (bvh_.empty() ? 0 : 1));
}

// The infinite lights take [0, pInfinite) of u, the tree the rest, each part
// stretched back to [0, 1) so the choice stays one dimension.
std::optional<ChosenLight> LightChooser::chooseByBvh(Vec3f p, Vec3f n, float u) const {
    const float pInfinite = infinite_.empty() ? 0.0f : infiniteShare();
    if (u < pInfinite) {
        const size_t k =
            std::min(size_t(u / pInfinite * float(infinite_.size())), infinite_.size() - 1);
        return ChosenLight{infinite_[k], pInfinite / float(infinite_.size())};
    }
    const float uTree = std::min((u - pInfinite) / (1 - pInfinite), kOneMinusEpsilon);
    const auto c = bvh_.choose(p, n, uTree);
    if (!c) return std::nullopt;
    return ChosenLight{treeLight_[size_t(c->light)], (1 - pInfinite) * c->pmf};
}

}  // namespace pathlab
