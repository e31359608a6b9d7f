// How next-event estimation picks the one light it samples, from one uniform
// number and the receiver (p, n): the strategy is fixed for a render, chosen
// by a switch on a small enum rather than a virtual call per sample.
//
// - uniform: every light alike (pbrt-v4's UniformLightSampler);
// - power:   in proportion to emitted power, lights of infinite extent by
//            their irradiance at the scene's focus point (lights.h explains);
//            pathlab's default, whatever the scene format;
// - bvh:     a light BVH (light_bvh.h) over the lights with a position —
//            area, point and spot lights — with importance at the receiver;
//            distant lights and environments are chosen beside the tree,
//            each with the tree's own probability 1/(nInfinite + 1), as
//            pbrt-v4's BVHLightSampler (its default light sampler).
//
// Every strategy also gives the probability of a given light at a receiver,
// for multiple importance sampling when a BSDF-sampled ray hits an emitter.
#pragma once

#include <optional>
#include <vector>

#include "render/light_sampling/light_bvh.h"
#include "scene/light_selection.h"

namespace pathlab {

class LightChooser {
  public:
    LightChooser() = default;
    // powerWeights: the power strategy's weight of each light (none may be
    // negative; all zero: nothing to choose). bounds: each light's bounds for
    // the BVH, nothing for a light without a position (sampled beside it).
    LightChooser(LightSelection strategy, const std::vector<double>& powerWeights,
                 const std::vector<std::optional<LightBounds>>& bounds);

    LightSelection strategy() const { return strategy_; }
    size_t size() const { return count_; }
    // A light for the receiver at p with shading normal n (zero: unknown).
    std::optional<ChosenLight> choose(Vec3f p, Vec3f n, float u) const;
    // The probability that choose(p, n, ·) returns `light`.
    float pmf(Vec3f p, Vec3f n, size_t light) const;
    const LightBvh& bvh() const { return bvh_; }

  private:
    ChosenLight chooseByPower(float u) const;
    std::optional<ChosenLight> chooseByBvh(Vec3f p, Vec3f n, float u) const;
    float powerPmf(size_t light) const;
    float infiniteShare() const;  // probability of choosing beside the tree

    LightSelection strategy_ = LightSelection::Power;
    size_t count_ = 0;
    std::vector<float> cdf_;  // power
    LightBvh bvh_;
    std::vector<int> treeLight_;  // tree index → light
    std::vector<int> infinite_;   // lights beside the tree
    std::vector<bool> inTree_;    // by light
};

}  // namespace pathlab
