// A dielectric interface as a layer of a layered BSDF (pbrt-v4's
// DielectricBxDF with its sample flags and transport mode): a walk inside the
// layers samples only transmission or only reflection, and a walk started
// from the light direction (importance transport) leaves out the 1/η′²
// radiance scaling of refraction (pbrt-v4 sec. 9.5.2).
#pragma once

#include <optional>

#include "render/bsdf.h"
#include "render/microfacet.h"

namespace pathlab {

enum class Transport { Radiance, Importance };
enum class Lobes { All, Reflection, Transmission };

struct DielectricInterface {
    float eta = 1.5f;  // inside over outside; the normal points outside
    GgxDistribution ggx{0.0f};

    bool isSpecular() const { return eta == 1 || ggx.effectivelySmooth(); }
    Vec3f f(Vec3f wo, Vec3f wi, Transport mode) const;
    float pdf(Vec3f wo, Vec3f wi, Transport mode, Lobes lobes = Lobes::All) const;
    // BsdfSample::specular marks a delta lobe; wi on wo's side: reflection.
    std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u, Transport mode,
                                     Lobes lobes = Lobes::All) const;
};

}  // namespace pathlab
