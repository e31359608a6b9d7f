// The colour a path carries, as a swappable type. The path integrator
// (path_integrator.h) is written once against a *colour context*: a small
// object that turns the scene's RGB parameters — a material's reflectance, a
// light's emitted radiance — into the colour the path carries, and a BSDF's
// values into that colour. RgbContext is RGB mode: the colour is the linear
// RGB triple itself and every conversion is the identity, so the integrator
// instantiated with it is the RGB integrator, bit for bit. Spectral mode's
// context (spectral_context.h) carries the radiance at a path's four sampled
// wavelengths instead (pbrt-v4's SampledSpectrum).
//
// A context provides:
//   using Colour                             — Vec3f or spectral::SampledSpectrum
//   kChannels                                — its number of floats, each
//                                              computed alike (batched_paths.h)
//   Colour reflectance(Vec3f rgb)            — a bounded reflectance in [0, 1]
//   Colour emission(Vec3f rgb)               — emitted radiance (any rgb ≥ 0)
//   Colour f(const Bsdf&, Vec3f wo, Vec3f wi) — the BSDF's value (bsdf.h conventions)
//   Colour sampledF(const Bsdf&, Vec3f wo, const BsdfSample&) — f of a sample drawn
//                                               by Bsdf::sample (its direction and pdf
//                                               do not depend on the colour)
//   Colour layeredF(const LayeredBsdf&, Vec3f wo, Vec3f wi, WalkNumbers&) — a
//                                               layered BSDF's f from one walk
//   optional<LayeredSampleOf<Colour>> layeredSample(const LayeredBsdf&, Vec3f wo,
//                                               float uc, Vec2f u, WalkNumbers&)
//   Vec3f toRgb(const Colour&)               — the path's radiance as linear sRGB
#pragma once

#include <optional>

#include "core/math.h"
#include "render/bsdf.h"
#include "render/layered/layered_bsdf.h"

namespace pathlab {

struct RgbContext {
    using Colour = Vec3f;
    static constexpr bool kSpectral = false;
    static constexpr int kChannels = 3;
    Vec3f reflectance(Vec3f rgb) const { return rgb; }
    Vec3f emission(Vec3f rgb) const { return rgb; }
    Vec3f f(const Bsdf& bsdf, Vec3f wo, Vec3f wi) const { return bsdf.f(wo, wi); }
    Vec3f sampledF(const Bsdf&, Vec3f, const BsdfSample& s) const { return s.f; }
    Vec3f layeredF(const LayeredBsdf& l, Vec3f wo, Vec3f wi, WalkNumbers& r) const {
        return l.f(wo, wi, r);
    }
    std::optional<LayeredSampleOf<Vec3f>> layeredSample(const LayeredBsdf& l, Vec3f wo, float uc,
                                                        Vec2f u, WalkNumbers& r) const {
        const auto s = l.sample(wo, uc, u, r);
        if (!s) return std::nullopt;
        return LayeredSampleOf<Vec3f>{*s, s->f};
    }
    Vec3f toRgb(Vec3f L) const { return L; }
};

}  // namespace pathlab
