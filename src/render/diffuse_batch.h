// The arithmetic of eight Lambertian path vertices at once: next-event
// estimation (towards one area light sampled by area here, or with light
// samples drawn by the caller) and the cosine-weighted bounce. Scalar, this is most of a vertex's
// time outside Embree, and its branches (which side of the surface, which wedge of the concentric
// disk, which side to nudge a ray origin to) follow random numbers and mispredict; here the eight
// lanes are structure-of-arrays, computed eight at a time with AVX2 or four at a time with SSE, and
// every branch is a select.
//
// Every value is bit-identical to the scalar path (sampleDirect with
// sampleByArea, Bsdf's Lambertian sample, Frame, offsetOrigin): the same IEEE
// operations in the same order, lane by lane — tested against them in
// tests/test_diffuse_batch.cpp. (No fused multiply-add: the build targets
// x86-64 without FMA, where GCC contracts nothing.)
//
// The colour a lane carries is a few channels whose arithmetic is the same
// per channel: RGB mode's three, or spectral mode's four wavelengths
// (render/colour/): Lambert's f and the bounce's weight are the reflectance's
// channels times colourless factors, and the light sample's estimate is f
// times the light's radiance in the same channels.
#pragma once

#include "core/math.h"
#include "render/lights.h"

namespace pathlab {

inline constexpr int kBatchLanes = 8;
// Colour channels per lane: 3 (RGB) or 4 (spectral::kSpectrumSamples).
inline constexpr int kMaxBatchChannels = 4;

// One vertex per lane: the hit, the ray that found it and the two 2D draws.
struct DiffuseBatchInput {
    float px[kBatchLanes], py[kBatchLanes], pz[kBatchLanes];  // hit point
    float nx[kBatchLanes], ny[kBatchLanes], nz[kBatchLanes];  // shading normal
    float gx[kBatchLanes], gy[kBatchLanes], gz[kBatchLanes];  // geometric normal
    float dx[kBatchLanes], dy[kBatchLanes], dz[kBatchLanes];  // incoming direction
    float albedo[kMaxBatchChannels][kBatchLanes];             // the reflectance, per channel
    float dirU[kBatchLanes], dirV[kBatchLanes];               // BSDF direction draw
    // With one area light sampled by area, the light point's draw; the kernel
    // samples the light itself.
    float lightU[kBatchLanes], lightV[kBatchLanes];
    // Otherwise the light sample the caller drew (LightSet::sample): direction,
    // distance (infinite for the environment), radiance, pdf, whether there
    // is one and whether it is a point, spot or distant light's (MIS weight 1).
    // The radiance is the sample's in the lane's colour channels; in spectral
    // mode it is given with the only light too (its RGB radiance at the
    // lane's wavelengths).
    float lightWx[kBatchLanes], lightWy[kBatchLanes], lightWz[kBatchLanes];
    float lightDistance[kBatchLanes];
    float lightRadiance[kMaxBatchChannels][kBatchLanes];
    float lightPdf[kBatchLanes];
    int lightValid[kBatchLanes];
    int lightDelta[kBatchLanes];
};

struct DiffuseBatchOutput {
    // Next-event estimation (sampleDirect): where shadow[k] is set, the
    // shadow ray is o + t·d from so to so + sd, t < shadowTMax, and `direct`
    // is the estimate when it is unblocked. Elsewhere no shadow ray is traced
    // and the estimate is zero.
    float sox[kBatchLanes], soy[kBatchLanes], soz[kBatchLanes];
    float sdx[kBatchLanes], sdy[kBatchLanes], sdz[kBatchLanes];
    float shadowTMax[kBatchLanes];
    float direct[kMaxBatchChannels][kBatchLanes];  // per colour channel
    int shadow[kBatchLanes];
    // The bounce, where bounce[k] is set (else the BSDF sample failed): the
    // world direction, its nudged origin, the throughput factor and the pdf.
    float ox[kBatchLanes], oy[kBatchLanes], oz[kBatchLanes];
    float wx[kBatchLanes], wy[kBatchLanes], wz[kBatchLanes];
    float weight[kMaxBatchChannels][kBatchLanes];  // per colour channel
    float pdf[kBatchLanes];
    int bounce[kBatchLanes];
};

// Which instructions shadeDiffuseBatch uses: the best the processor has
// (AVX2, eight lanes at once), or SSE (four) — the same bits either way.
enum class BatchIsa { Best, Sse };
bool batchUsesAvx2();

// Lanes 0 … lanes − 1 are shaded; lanes up to the next multiple of the
// vector width are computed too and may hold anything. `light`: the scene's
// only light, sampled here; null: the input carries each lane's light sample.
// `epsilon` is RenderScene's ray-origin offset. RGB: channels 0–2, the only
// light's radiance its own.
void shadeDiffuseBatch(const AreaLight* light, float epsilon, const DiffuseBatchInput& in,
                       int lanes, DiffuseBatchOutput& out, BatchIsa isa = BatchIsa::Best);
// Spectral mode: channels 0–3, the only light's radiance from the input
// (lightRadiance), as each lane's wavelengths see it.
void shadeDiffuseBatchSpectral(const AreaLight* light, float epsilon, const DiffuseBatchInput& in,
                               int lanes, DiffuseBatchOutput& out, BatchIsa isa = BatchIsa::Best);

}  // namespace pathlab
