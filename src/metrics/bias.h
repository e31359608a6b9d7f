// Bias of a test image against a reference: the signed mean of TEST − REFERENCE
// over pixels, in total and per channel, and that relative to the reference's
// mean. MSE squares the error away; a sampler that is too bright everywhere
// (correlated dimensions, a fixed sample at the pixel centre) shows here with
// its sign, where MSE only shows "a bit more error".
#pragma once

#include <array>
#include <optional>

#include "core/image.h"

namespace pathlab {

struct Bias {
    double mean = 0;                   // mean of (t − r) over pixels and channels
    std::array<double, 3> channels{};  // mean of (t − r) over pixels, per channel
    double referenceMean = 0;          // mean of r over pixels and channels
    // mean / referenceMean; nullopt for a reference whose mean is not positive.
    std::optional<double> relative;
};

// Sums per row in double precision, rows added in order: the result does not
// depend on the number of threads. Throws InputError for images of different size.
Bias signedBias(const Image& reference, const Image& test);

}  // namespace pathlab
