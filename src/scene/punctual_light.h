// Lights with no area, reached only by next-event estimation (pbrt-v4's
// PointLight, SpotLight and DistantLight, PBRT 4th ed. §12.1, §12.4): a
// BSDF-sampled ray never hits them, so their light samples have weight 1.
#pragma once

#include <cmath>

#include "core/math.h"

namespace pathlab {

enum class PunctualLightType {
    Point,    // radiant intensity `intensity` in every direction from `position`
    Spot,     // a point light whose intensity falls off around `direction`
    Distant,  // radiance `radiance` arriving along `direction` from infinitely far
};

struct PunctualLight {
    PunctualLightType type = PunctualLightType::Point;
    Vec3f position{0.0f};
    // Spot: the unit axis the cone opens around (from → to). Distant: the unit
    // direction in which the light travels (from → to), so it arrives from
    // −direction.
    Vec3f direction{0, 0, 1};
    Vec3f intensity{0.0f};  // point, spot: I (RGB, per steradian)
    Vec3f radiance{0.0f};   // distant: L
    // Spot: full intensity within coneAngle − coneDeltaAngle of the axis, none
    // beyond coneAngle (degrees), pbrt-v4's smoothstep in cosθ between; set
    // through setSpotCone, which also sets the cosines the renderer uses.
    float coneAngle = 30, coneDeltaAngle = 5;
    float cosFalloffStart = 1, cosFalloffEnd = 1;
};

inline void setSpotCone(PunctualLight& l, float coneAngle, float coneDeltaAngle) {
    constexpr float kRadiansPerDegree = float(3.14159265358979323846 / 180);
    l.coneAngle = coneAngle;
    l.coneDeltaAngle = coneDeltaAngle;
    l.cosFalloffEnd = std::cos(coneAngle * kRadiansPerDegree);
    l.cosFalloffStart = std::cos((coneAngle - coneDeltaAngle) * kRadiansPerDegree);
}

}  // namespace pathlab
