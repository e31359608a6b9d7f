// What the path integrator is asked to do: how deep paths go and when Russian
// roulette may end them. The renderer's and the study's settings take their
// default roulette depth from here.
#pragma once

#include "sampling/sampler.h"
#include "spectral/sampled_wavelengths.h"

namespace pathlab {

// Bounces before roulette may end a path. 2 is pbrt-v4's rule (depth > 1);
// Mitsuba 3's rr_depth = 5 is 4 here.
inline constexpr int kDefaultRouletteDepth = 2;

struct IntegratorSettings {
    int maxDepth = 8;
    bool russianRoulette = true;
    // Roulette may end a path only after its first `rouletteDepth` bounces: it
    // first decides when continuing from vertex `rouletteDepth` (0-based).
    int rouletteDepth = kDefaultRouletteDepth;
    // Trace a batch of a pixel's paths together, depth by depth
    // (estimateRadianceBatch): the same image, bit for bit, in less time. Off
    // only to compare the two.
    bool batchPaths = true;
    // The first dimension of path vertex 0's block (dims::firstBounce): 2, or
    // 4 when the camera's thin lens draws dimensions 2 and 3.
    int firstBounce = dims::kFirstBounce;
    // Spectral mode (render/colour/spectral_paths.h): each path carries four
    // wavelengths drawn from dimension wavelengthDimension, and firstBounce
    // is the dimension after it; `wavelengths` says how that one number
    // becomes the four (SampledWavelengths::sample).
    bool spectral = false;
    int wavelengthDimension = 0;
    spectral::WavelengthSampling wavelengths = spectral::WavelengthSampling::Visible;
};

}  // namespace pathlab
