// Every pixel's running sums of a render, kept so that a later render of the
// same scene and settings with more samples continues from them instead of
// starting over: `pathlab view`'s progressive accumulation. The samples are
// summed in index order either way, so the continued render is bit-identical
// to one render of all its samples.
#pragma once

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/math.h"

namespace pathlab {

// A pixel's sums of samples and of their squares (filters of constant weight:
// the plain mean).
struct PlainSums {
    double sum[3] = {0, 0, 0}, sumSq[3] = {0, 0, 0};
    void add(Vec3f L) {
        for (int c = 0; c < 3; ++c) sum[c] += L[c], sumSq[c] += double(L[c]) * L[c];
    }
};

// A pixel's running sums of weighted samples (filters whose weights vary).
struct WeightedSums {
    double w = 0, w2 = 0, absW = 0;
    double wL[3] = {0, 0, 0}, w2L[3] = {0, 0, 0}, w2L2[3] = {0, 0, 0}, absWL[3] = {0, 0, 0};
    void add(double weight, Vec3f L) {
        const double ww = weight * weight, a = std::abs(weight);
        w += weight, w2 += ww, absW += a;
        for (int c = 0; c < 3; ++c) {
            wL[c] += weight * L[c], w2L[c] += ww * L[c], w2L2[c] += ww * L[c] * L[c];
            absWL[c] += a * L[c];
        }
    }
};

// One of the two vectors holds a sum per pixel of the image (row-major), the
// other is empty; both are empty before the first render (spp 0).
struct RunningSums {
    int first = 0;  // the first sample summed: 0 but for a sample range
    int spp = 0;    // samples summed per pixel, from `first` on
    std::vector<PlainSums> plain;
    std::vector<WeightedSums> weighted;
};

// Samples first … end − 1 of every pixel (RenderSettings::sampleRange).
struct SampleRange {
    int first = 0, end = 0;
    int count() const { return end - first; }
    bool operator==(const SampleRange&) const = default;
};

// Adds the sums of the next sample range to `into` (empty, or the sums of the
// samples just before it), field by field. Double addition is not
// associative: ranges added in one fixed order give the same bits every time,
// though not those of one render summing all samples in index order.
inline void addRunningSums(RunningSums& into, const RunningSums& next) {
    if (into.spp == 0) {
        into = next;
        return;
    }
    if (next.first != into.first + into.spp || next.plain.size() != into.plain.size() ||
        next.weighted.size() != into.weighted.size())
        throw std::logic_error("running sums of another image, or not the next sample range");
    for (size_t i = 0; i < into.plain.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            into.plain[i].sum[c] += next.plain[i].sum[c];
            into.plain[i].sumSq[c] += next.plain[i].sumSq[c];
        }
    for (size_t i = 0; i < into.weighted.size(); ++i) {
        WeightedSums& a = into.weighted[i];
        const WeightedSums& b = next.weighted[i];
        a.w += b.w, a.w2 += b.w2, a.absW += b.absW;
        for (int c = 0; c < 3; ++c) {
            a.wL[c] += b.wL[c], a.w2L[c] += b.w2L[c], a.w2L2[c] += b.w2L2[c];
            a.absWL[c] += b.absWL[c];
        }
    }
    into.spp += next.spp;
}

}  // namespace pathlab
