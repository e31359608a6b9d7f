// What spectral mode renders so far: every material whose BSDF spectral_bsdf.cpp
// evaluates per wavelength, and every light (their RGB radiance is converted
// where the integrator receives it). The layered materials' random walks
// carry RGB only.
#include "core/error.h"
#include "render/colour/spectral_paths.h"

namespace pathlab {

void checkSpectralSupport(const SceneDescription& scene) {
    for (const Material& m : scene.materials) {
        if (m.type == MaterialType::CoatedDiffuse)
            throw InputError("spectral mode does not support the coateddiffuse material yet");
        if (m.type == MaterialType::CoatedConductor)
            throw InputError("spectral mode does not support the coatedconductor material yet");
    }
}

}  // namespace pathlab
