// pbrt-v4's coateddiffuse and coatedconductor materials as layered BSDFs
// (its CoatedDiffuseMaterial and CoatedConductorMaterial::GetBxDF).
#pragma once

#include <optional>

#include "render/layered/layered_bsdf.h"
#include "scene/scene.h"

namespace pathlab {

// The layered BSDF of a coated material; nothing for other materials.
std::optional<LayeredBsdf> coatedBsdf(const Material& m);

}  // namespace pathlab
