// The sampler interface: every random decision of the renderer is drawn here.
//
// Modelled on pbrt-v4's Sampler (src/pbrt/samplers.h): a small value type per
// strategy with the same four calls; the integrator is a template over it, so
// drawing a sample is an inlined call, never a virtual one. A sampler is
// copied per tile; anything large it needs that does not depend on the pixel
// (tables, textures) is shared and immutable, and per-pixel caches are the
// copy's own (stratified's strata tables, zsobol's digit trees).
//
// Determinism: a sampler's output is a pure function of (pixel, sample index,
// dimension, seed) — never of the order in which pixels are rendered — so an
// image is bit-identical whatever the thread count.
#pragma once

#include <concepts>
#include <cstdint>

#include "core/math.h"

namespace pathlab {

// The dimension layout, fixed for every sampler (see docs/rendering.md).
// startPixelSample(pixel, index, 0) is followed by getPixel2D() (dims 0,1); a
// camera with a thin lens then draws its lens position with get2D() (dims 2,3,
// as pbrt-v4's GetCameraSample draws pLens right after the pixel, less the
// time dimension pathlab has no use for). Then comes one block of
// kDimsPerBounce dimensions per path vertex, in this order:
//   +0      light choice (1D)           — which light next-event estimation samples
//   +1,+2   point on that light (2D)
//   +3      BSDF lobe choice (1D)       — e.g. reflect or refract at glass
//   +4,+5   BSDF direction (2D)
//   +6      Russian roulette (1D)
// The first block starts at kFirstBounce (2) without a lens and at
// kFirstBounce + kLensDimensions (4) with one: the renderer carries it at run
// time (IntegratorSettings::firstBounce), so a pinhole's layout, and every
// image rendered through one, is unchanged. A sampler whose native dimension
// count is smaller pads the rest (each sampler documents how). Samplers that
// key their tables on the lens-free layout (blue-noise's lookup terms,
// zsobol's tabulated low digits, `pathlab points`' 2D pairs) still give each
// dimension a pure function of (pixel, index, dimension, seed) with a lens; only
// their notion of which vertex a dimension belongs to is shifted by two.
namespace dims {
inline constexpr int kPixel = 0;
inline constexpr int kLens = 2;  // with a thin lens only
inline constexpr int kLensDimensions = 2;
inline constexpr int kFirstBounce = 2;
inline constexpr int kLightChoice = 0;
inline constexpr int kLightPoint = 1;
inline constexpr int kBsdfLobe = 3;
inline constexpr int kBsdfDirection = 4;
inline constexpr int kRoulette = 6;
inline constexpr int kDimsPerBounce = 7;
// The first dimension of vertex 0's block: after the lens when there is one.
constexpr int firstBounce(bool lens) {
    return kFirstBounce + (lens ? kLensDimensions : 0);
}
// First dimension of the block of path vertex `depth` (0 = the camera ray's
// hit), whose first block starts at `first` (firstBounce(lens)).
constexpr int bounceBase(int depth, int first = kFirstBounce) {
    return first + depth * kDimsPerBounce;
}
// The path depth a dimension belongs to (-1 for the pixel dimensions), in the
// lens-free layout.
constexpr int depthOfDimension(int dim) {
    return dim < kFirstBounce ? -1 : (dim - kFirstBounce) / kDimsPerBounce;
}
}  // namespace dims

// The lanes of one draw: the renderer traces a camera packet of this many
// consecutive samples of a pixel, and draws a path vertex's dimensions for up
// to this many paths at once.
inline constexpr int kCameraPacketSamples = 8;
// The draw order across samples: the renderer traces the paths of this many
// consecutive samples of a pixel together — their pixel dimensions first, a
// camera packet at a time, then depth by depth, the live paths in groups of
// kCameraPacketSamples — so that as paths end, the live ones still fill whole
// groups. Samplers that keep per-sample state keep it for this many samples;
// the cost model draws in this order.
inline constexpr int kBatchSamples = 64;
static_assert(kBatchSamples % kCameraPacketSamples == 0);

// What every sampler is constructed from.
struct SamplerConfig {
    int samplesPerPixel = 1;
    uint64_t seed = 0;
    Vec2i resolution{1, 1};
};

// The interface, as a concept (pbrt-v4 names, camelCase):
//   startPixelSample(pixel, index, dim) — start sample `index` of `pixel` at dimension `dim`
//   get1D(), get2D()                     — the next one or two dimensions, in [0,1)
//   getPixel2D()                         — dimensions 0 and 1: the position inside the pixel
//   samplesPerPixel()
template <typename S>
concept Sampler = std::copy_constructible<S> && requires(S s, Vec2i p, int i) {
    { s.samplesPerPixel() } -> std::convertible_to<int>;
    s.startPixelSample(p, i, i);
    { s.get1D() } -> std::same_as<float>;
    { s.get2D() } -> std::same_as<Vec2f>;
    { s.getPixel2D() } -> std::same_as<Vec2f>;
};

// The lane draws' indices as a full vector of kCameraPacketSamples unsigned
// lanes (those past count are 0), so that a loop over them is a SIMD loop.
inline void padLanes(const int* indices, int count, uint32_t* lanes) {
    for (int j = 0; j < kCameraPacketSamples; ++j) lanes[j] = 0;
    for (int j = 0; j < count; ++j) lanes[j] = static_cast<uint32_t>(indices[j]);
}

// Does S draw lanes itself (get1DLanes / get2DLanes)?
template <typename S>
concept DrawsLanes = Sampler<S> && requires(S s, Vec2i p, const int* i, float* x, Vec2f* xy) {
    s.get1DLanes(p, i, 0, 0, x);
    s.get2DLanes(p, i, 0, 0, xy);
};

// Lane draws without a sampler's own path: each lane positioned and drawn
// by itself (also the samplers' fallback where their lane path does not apply).
template <Sampler S>
void drawEachLane1D(S& s, Vec2i pixel, const int* indices, int count, int dim, float* out) {
    for (int j = 0; j < count; ++j) s.startPixelSample(pixel, indices[j], dim), out[j] = s.get1D();
}
template <Sampler S>
void drawEachLane2D(S& s, Vec2i pixel, const int* indices, int count, int dim, Vec2f* out) {
    for (int j = 0; j < count; ++j) s.startPixelSample(pixel, indices[j], dim), out[j] = s.get2D();
}

// Lane draws, for the batched integrator: dimension `dim` (1D), or `dim` and
// `dim` + 1 (2D), of samples indices[0 … count) of one pixel, count ≤
// kCameraPacketSamples. A sampler whose work for a dimension is shared by a
// pixel's samples (a scramble's seed, a permutation's hash) or runs side by
// side in SIMD lanes provides get1DLanes / get2DLanes; the others are
// repositioned sample by sample. Either way out[j] is, bit for bit, what
// startPixelSample(pixel, indices[j], dim) then get1D() / get2D() gives.
template <Sampler S>
void drawLanes1D(S& s, Vec2i pixel, const int* indices, int count, int dim, float* out) {
    if constexpr (DrawsLanes<S>) {
        s.get1DLanes(pixel, indices, count, dim, out);
    } else {
        drawEachLane1D(s, pixel, indices, count, dim, out);
    }
}
template <Sampler S>
void drawLanes2D(S& s, Vec2i pixel, const int* indices, int count, int dim, Vec2f* out) {
    if constexpr (DrawsLanes<S>) {
        s.get2DLanes(pixel, indices, count, dim, out);
    } else {
        drawEachLane2D(s, pixel, indices, count, dim, out);
    }
}

// Does S draw the pixel dimensions of several samples itself? Those whose
// getPixel2D is get2D at dimension 0 and that draw lanes say so.
template <typename S>
concept DrawsPixelLanes = Sampler<S> && requires(S s, Vec2i p, const int* i, Vec2f* xy) {
    s.getPixel2DLanes(p, i, 0, xy);
};

// The positions inside the pixel (dimensions 0 and 1) of samples
// indices[0 … count) of one pixel: out[j] is, bit for bit,
// startPixelSample(pixel, indices[j], dims::kPixel) then getPixel2D().
template <Sampler S>
void drawPixelLanes(S& s, Vec2i pixel, const int* indices, int count, Vec2f* out) {
    if constexpr (DrawsPixelLanes<S>) {
        s.getPixel2DLanes(pixel, indices, count, out);
    } else {
        for (int j = 0; j < count; ++j)
            s.startPixelSample(pixel, indices[j], dims::kPixel), out[j] = s.getPixel2D();
    }
}

// A path vertex's draws for the live paths of a batch (the paths' sample
// indices): the light choice (when `choice`), the light point and the BSDF
// direction of the vertex whose block starts at dimension `base`. A sampler
// with lane draws draws each dimension for all the paths at once; the others
// go path by path, so that each path is positioned once per vertex (the light
// choice and point are consecutive dimensions), not once per dimension.
template <Sampler S>
void drawVertexLanes(S& s, Vec2i pixel, const int* indices, int count, int base, bool choice,
                     float* uChoice, Vec2f* uLight, Vec2f* uDirection) {
    if constexpr (DrawsLanes<S>) {
        if (choice) drawLanes1D(s, pixel, indices, count, base + dims::kLightChoice, uChoice);
        drawLanes2D(s, pixel, indices, count, base + dims::kLightPoint, uLight);
        drawLanes2D(s, pixel, indices, count, base + dims::kBsdfDirection, uDirection);
    } else {
        for (int j = 0; j < count; ++j) {
            if (choice) {
                s.startPixelSample(pixel, indices[j], base + dims::kLightChoice);
                uChoice[j] = s.get1D();
            } else {
                s.startPixelSample(pixel, indices[j], base + dims::kLightPoint);
            }
            uLight[j] = s.get2D();
            s.startPixelSample(pixel, indices[j], base + dims::kBsdfDirection);
            uDirection[j] = s.get2D();
        }
    }
}

}  // namespace pathlab
