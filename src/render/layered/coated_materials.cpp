#include "render/layered/coated_materials.h"

namespace pathlab {

std::optional<LayeredBsdf> coatedBsdf(const Material& m) {
    if (m.type != MaterialType::CoatedDiffuse && m.type != MaterialType::CoatedConductor)
        return std::nullopt;
    const Coating& c = m.coating;
    DielectricInterface top;
    top.eta = c.eta;
    top.ggx = GgxDistribution(c.roughness, c.roughnessV >= 0 ? c.roughnessV : c.roughness);
    const LayerParameters layer{c.thickness, c.albedo, c.g, c.maxDepth, c.nSamples};
    if (m.type == MaterialType::CoatedDiffuse)
        return LayeredBsdf(top, Bsdf::diffuse(m.albedo), layer);
    // The conductor lies under the coating, not in vacuum: its index relative
    // to the coating's (pbrt-v4 divides eta and k by the coating's eta).
    const float alphaV = m.roughnessV >= 0 ? m.roughnessV : m.roughness;
    const Bsdf base = Bsdf::conductor(m.eta / c.eta, m.k / c.eta, m.roughness, alphaV);
    return LayeredBsdf(top, base, layer);
}

}  // namespace pathlab
