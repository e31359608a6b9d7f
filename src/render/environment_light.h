// An image environment map as a light (pbrt-v4's ImageInfiniteLight, PBRT 4th
// ed. §12.5.2): radiance looked up at the nearest texel of the equal-area
// octahedral map, directions sampled in proportion to the texels' luminance
// by a piecewise-constant 2D distribution over the map (pbrt-v4's
// PiecewiseConstant2D, shared with the pixel filters; every texel subtends
// the same solid angle 4π/N, so the density per steradian is the map's
// density / 4π) — or uniformly over the sphere when the image asks for it.
#pragma once

#include <optional>

#include "core/math.h"
#include "render/pixel_filter.h"  // PiecewiseConstant2D
#include "scene/environment_image.h"

namespace pathlab {

class EnvironmentLight {
  public:
    explicit EnvironmentLight(EnvironmentImage image);

    // Radiance arriving from world direction w (unit, pointing away from the
    // receiver, towards the sky).
    Vec3f radiance(Vec3f w) const;
    struct Sample {
        Vec3f wi;  // unit world direction towards the sky
        Vec3f radiance;
        float pdf;  // per unit solid angle
    };
    std::optional<Sample> sample(Vec2f u) const;
    float pdf(Vec3f w) const;
    // Luminance of the irradiance the map delivers, averaged over receiver
    // orientations: π times its mean luminance (for the choice among lights).
    double meanIrradiance() const { return meanIrradiance_; }

  private:
    Vec2f toSquare(Vec3f w) const;
    Vec3f texel(Vec2f uv) const;
    EnvironmentImage image_;
    PiecewiseConstant2D distribution_;
    double meanIrradiance_ = 0;
};

}  // namespace pathlab
