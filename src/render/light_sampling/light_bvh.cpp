#include "render/light_sampling/light_bvh.h"

#include <algorithm>
#include <array>

namespace pathlab {
namespace {

constexpr int kBuckets = 12;
// From this depth on, ranges are halved by count: with at most 2³² lights the
// deepest leaf is then at depth 64 or less, so a path fits a 64-bit trail.
constexpr int kBalancedFromDepth = 32;

// pbrt-v4's EvaluateCost (PBRT 4th ed., eq. 12.31): the power times the
// solid-angle measure M_Ω of the directions the group emits into, times the
// surface area of its box, times Kr, which penalises thin slabs cut across.
double splitCost(const LightBounds& b, const Box3f& whole, int dim) {
    if (b.phi == 0) return 0;
    const double cosO = b.normals.cosTheta;
    const double thetaO = std::acos(std::clamp(cosO, -1.0, 1.0));
    const double thetaE = std::acos(std::clamp(double(b.cosThetaE), -1.0, 1.0));
    const double thetaW = std::min(thetaO + thetaE, double(kPi));
    const double sinO = std::sqrt(std::max(0.0, 1 - cosO * cosO));
    const double mOmega =
        2 * kPi * (1 - cosO) +
        kPi / 2 * (2 * thetaW * sinO - std::cos(thetaO - 2 * thetaW) - 2 * thetaO * sinO + cosO);
    const Vec3f d = whole.diagonal();
    const double kr = double(maxComponent(d)) / double(d[dim]);
    return double(b.phi) * mOmega * kr * double(b.bounds.surfaceArea());
}

int bucketOf(Vec3f centre, const Box3f& centroids, int dim) {
    const float extent = centroids.hi[dim] - centroids.lo[dim];
    const int b = int(kBuckets * ((centre[dim] - centroids.lo[dim]) / extent));
    return std::clamp(b, 0, kBuckets - 1);
}

}  // namespace

LightBvh::LightBvh(const std::vector<LightBounds>& lights) : paths_(lights.size()) {
    std::vector<Item> items;
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].phi > 0) items.push_back({int(i), lights[i]});
    if (!items.empty()) build(items, 0, items.size(), 0, 0);
}

int LightBvh::build(std::vector<Item>& items, size_t begin, size_t end, uint64_t trail, int depth) {
    const int index = int(nodes_.size());
    maxDepth_ = std::max(maxDepth_, depth);
    if (end - begin == 1) {
        nodes_.push_back({items[begin].bounds, items[begin].light, true});
        paths_[size_t(items[begin].light)] = {trail, depth};
        return index;
    }
    LightBounds all;
    for (size_t i = begin; i < end; ++i) all = unionBounds(all, items[i].bounds);
    nodes_.push_back({all, -1, false});
    const size_t mid = split(items, begin, end, depth);
    build(items, begin, mid, trail, depth + 1);
    const int second = build(items, mid, end, trail | (uint64_t(1) << depth), depth + 1);
    nodes_[size_t(index)].childOrLight = second;
    return index;
}

// Where to cut items[begin, end): the bucket boundary of least splitCost over
// the three axes; the middle when no cut separates anything.
size_t LightBvh::split(std::vector<Item>& items, size_t begin, size_t end, int depth) const {
    const size_t middle = begin + (end - begin) / 2;
    if (depth >= kBalancedFromDepth) return middle;
    Box3f whole, centroids;
    for (size_t i = begin; i < end; ++i) {
        whole.extend(items[i].bounds.bounds);
        centroids.extend(items[i].bounds.bounds.centre());
    }
    double bestCost = std::numeric_limits<double>::infinity();
    int bestDim = -1, bestBucket = -1;
    for (int dim = 0; dim < 3; ++dim) {
        if (!(centroids.hi[dim] > centroids.lo[dim])) continue;
        std::array<LightBounds, kBuckets> bucket{};
        for (size_t i = begin; i < end; ++i) {
            LightBounds& b =
                bucket[size_t(bucketOf(items[i].bounds.bounds.centre(), centroids, dim))];
            b = unionBounds(b, items[i].bounds);
        }
        // Costs of the cut after bucket k, below and above it.
        std::array<LightBounds, kBuckets> above{};
        above[kBuckets - 1] = bucket[kBuckets - 1];
        for (int k = kBuckets - 2; k >= 0; --k)
            above[size_t(k)] = unionBounds(bucket[size_t(k)], above[size_t(k + 1)]);
        LightBounds below;
        for (int k = 0; k < kBuckets - 1; ++k) {
            below = unionBounds(below, bucket[size_t(k)]);
            const double cost =
                splitCost(below, whole, dim) + splitCost(above[size_t(k + 1)], whole, dim);
            if (cost > 0 && cost < bestCost) bestCost = cost, bestDim = dim, bestBucket = k;
        }
    }
    if (bestDim < 0) return middle;
    const auto first = items.begin() + std::ptrdiff_t(begin),
               last = items.begin() + std::ptrdiff_t(end);
    const auto cut = std::partition(first, last, [&](const Item& it) {
        return bucketOf(it.bounds.bounds.centre(), centroids, bestDim) <= bestBucket;
    });
    if (cut == first || cut == last) return middle;
    return size_t(cut - items.begin());
}

std::optional<ChosenLight> LightBvh::choose(Vec3f p, Vec3f n, float u) const {
    if (nodes_.empty()) return std::nullopt;
    int node = 0;
    float pmf = 1;
    while (!nodes_[size_t(node)].leaf) {
        const int c0 = node + 1, c1 = nodes_[size_t(node)].childOrLight;
        const float i0 = nodes_[size_t(c0)].bounds.importance(p, n);
        const float i1 = nodes_[size_t(c1)].bounds.importance(p, n);
        if (!(i0 + i1 > 0)) return std::nullopt;
        const float p0 = i0 / (i0 + i1), p1 = i1 / (i0 + i1);
        // The part of [0, 1) that picked the child, stretched back to [0, 1).
        if (u < p0) {
            pmf *= p0, u = std::min(u / p0, kOneMinusEpsilon), node = c0;
        } else {
            pmf *= p1, u = std::min((u - p0) / p1, kOneMinusEpsilon), node = c1;
        }
    }
    return ChosenLight{nodes_[size_t(node)].childOrLight, pmf};
}

float LightBvh::pmf(Vec3f p, Vec3f n, int light) const {
    const Path& path = paths_[size_t(light)];
    if (path.depth < 0) return 0;
    int node = 0;
    float pmf = 1;
    for (int k = 0; k < path.depth; ++k) {
        const int c0 = node + 1, c1 = nodes_[size_t(node)].childOrLight;
        const float i0 = nodes_[size_t(c0)].bounds.importance(p, n);
        const float i1 = nodes_[size_t(c1)].bounds.importance(p, n);
        if (!(i0 + i1 > 0)) return 0;
        const bool second = (path.trail >> k) & 1;
        pmf *= (second ? i1 : i0) / (i0 + i1);
        node = second ? c1 : c0;
    }
    return pmf;
}

}  // namespace pathlab
