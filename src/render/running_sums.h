// Every pixel's running sums of a render, kept so that a later render of the
// same scene and settings with more samples continues from them instead of
// starting over: `pathlab view`'s progressive accumulation. The samples are
// summed in index order either way, so the continued render is bit-identical
// to one render of all its samples.
#pragma once

#include <cmath>
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
    int spp = 0;  // samples summed per pixel
    std::vector<PlainSums> plain;
    std::vector<WeightedSums> weighted;
};

}  // namespace pathlab
