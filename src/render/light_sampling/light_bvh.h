// A bounding volume hierarchy over lights for choosing one in proportion to
// an estimate of what it contributes at the shading point (Conty Estevez &
// Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree
// Splitting"; pbrt-v4's BVHLightSampler, PBRT 4th ed., §12.6.3). Each inner
// node holds the LightBounds of its subtree; a choice walks down from the
// root, taking a child with probability proportional to its importance at the
// receiver, with ONE uniform number remapped into [0, 1) at each step — so the
// choice is one sampler dimension however deep the tree. The probability of a
// given light is the product of the branch probabilities on its path, which
// pmf() recomputes from the light's recorded path (the same arithmetic as the
// descent, so the same bits), for multiple importance sampling.
//
// Built top-down with a surface-area-orientation heuristic (pbrt-v4's
// EvaluateCost: phi · M_Ω · area, with M_Ω the solid-angle measure of the
// emission cones, eq. 12.31), bucketing lights by centroid along each axis.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "render/light_sampling/light_bounds.h"

namespace pathlab {

struct ChosenLight {
    int light = -1;  // index into the lights the tree was built from
    float pmf = 0;
};

class LightBvh {
  public:
    struct Node {
        LightBounds bounds;
        // Inner node: the second child (the first is the next node);
        // leaf: the light.
        int childOrLight = -1;
        bool leaf = false;
    };

    LightBvh() = default;
    // Lights with phi = 0 are left out: they are never chosen (pmf 0).
    explicit LightBvh(const std::vector<LightBounds>& lights);

    bool empty() const { return nodes_.empty(); }
    // A light for receiver p with shading normal n from u in [0, 1); nothing
    // when no light can contribute at p.
    std::optional<ChosenLight> choose(Vec3f p, Vec3f n, float u) const;
    // The probability that choose(p, n, ·) returns `light`.
    float pmf(Vec3f p, Vec3f n, int light) const;
    // Depth of the deepest leaf (the root is depth 0): for tests and figures.
    int depth() const { return maxDepth_; }
    // The nodes, depth first from the root: to inspect the tree.
    const std::vector<Node>& nodes() const { return nodes_; }

  private:
    // Where a light's leaf is: bit k of `trail` is the branch taken at depth k.
    struct Path {
        uint64_t trail = 0;
        int depth = -1;  // −1: the light is not in the tree
    };
    struct Item {
        int light;
        LightBounds bounds;
    };
    int build(std::vector<Item>& items, size_t begin, size_t end, uint64_t trail, int depth);
    size_t split(std::vector<Item>& items, size_t begin, size_t end, int depth) const;
    std::vector<Node> nodes_;
    std::vector<Path> paths_;  // by light
    int maxDepth_ = 0;
};

}  // namespace pathlab
