// Next-event estimation towards a point, spot or distant light (pbrt-v4's
// PointLight::SampleLi, SpotLight::SampleLi, DistantLight::SampleLi): the
// direction is determined, so the sample draws no random number, and its
// "pdf" is the discrete probability of having chosen the light. Such a
// sample is a delta distribution that BSDF sampling can never produce, so its
// multiple-importance weight is 1 (Veach 1997, §9.2.4).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/math.h"
#include "scene/punctual_light.h"

namespace pathlab {

// pbrt-v4's SmoothStep(x, a, b): 0 below a, 1 above b, 3t² − 2t³ between.
inline float smoothStep(float x, float a, float b) {
    if (a == b) return x < a ? 0.0f : 1.0f;
    const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3 - 2 * t);
}

// The spot light's intensity towards unit direction w (away from the light).
inline Vec3f spotIntensity(const PunctualLight& l, Vec3f w) {
    return l.intensity * smoothStep(dot(w, l.direction), l.cosFalloffEnd, l.cosFalloffStart);
}

// Total emitted power, for choosing among lights in proportion to it (pbrt-v4's
// Phi, luminance of the RGB); a distant light has none (see lights.cpp).
inline double punctualPower(const PunctualLight& l) {
    switch (l.type) {
        case PunctualLightType::Point:
            return 4 * kPi * double(luminance(l.intensity));
        case PunctualLightType::Spot:
            return 2 * kPi * double(luminance(l.intensity)) *
                   ((1 - double(l.cosFalloffStart)) +
                    (double(l.cosFalloffStart) - double(l.cosFalloffEnd)) / 2);
        case PunctualLightType::Distant:
            return 0;
    }
    return 0;
}

// Luminance of the irradiance the light delivers at x onto a surface facing it,
// unoccluded.
inline double punctualIrradianceAt(const PunctualLight& l, Vec3f x) {
    if (l.type == PunctualLightType::Distant) return double(luminance(l.radiance));
    const Vec3f d = x - l.position;
    const float dist2 = std::max(dot(d, d), 1e-12f);
    const Vec3f I =
        l.type == PunctualLightType::Spot ? spotIntensity(l, d / std::sqrt(dist2)) : l.intensity;
    return double(luminance(I)) / dist2;
}

}  // namespace pathlab
