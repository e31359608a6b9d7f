// Materials (pbrt-v4 File Format, "Materials"; pbrt-v4's materials.cpp): the
// parameters of diffuse, conductor, dielectric, thindielectric,
// diffusetransmission, coateddiffuse, coatedconductor, mix and interface, and
// named materials, which may be
// used before they are defined (pbrt-v4 resolves them when the scene is
// complete). Textured parameters refer to named textures
// (world_texture_classes.cpp), evaluated at each hit by the renderer.
#include <cmath>

#include "scene/named_spectra.h"
#include "scene/pbrt/parser_state.h"

namespace pathlab::pbrt {
namespace {

Material greyDiffuse(const std::string& name) {
    Material m;
    m.name = name;
    m.type = MaterialType::Diffuse;
    m.albedo = Vec3f(0.5f);
    return m;
}

void markAllUsed(const ParamSet& ps) {
    for (const Param& p : ps.all()) p.used = true;
}

// A float parameter that may be given as a texture: the texture's index in
// `texture`, else the constant (or `fallback`).
struct FloatParam {
    float value = 0;
    int texture = -1;
};
FloatParam floatOrTexture(ImportState& st, const ParamSet& ps, const std::string& name,
                          FloatParam fallback) {
    if (const auto t = floatTextureParam(st, ps, name)) return {0, *t};
    if (!ps.find(name)) return fallback;
    return {ps.getFloat(name, fallback.value), -1};
}

// Plain materials evaluate a textured parameter at each hit; coated ones build
// their layered BSDF once per material, so a texture there is unsupported
// (its constant default under --lenient).
enum class TextureUse { PerHit, Unsupported };

// pbrt-v4's roughness parameters: "uroughness" and "vroughness", each
// defaulting to "roughness" (0), remapped to GGX alpha by RoughnessToAlpha
// (alpha = √roughness) when `remap` (the material's "remaproughness"). A
// textured one is remapped at each hit (Material::roughnessTexture).
struct GgxRoughness {
    float u = 0, v = 0;                // the constants' GGX alphas
    int textureU = -1, textureV = -1;  // textured ones
};
GgxRoughness ggxRoughness(ImportState& st, const ParamSet& ps, bool remap, TextureUse use,
                          const SourceLocation& where) {
    const FloatParam r = floatOrTexture(st, ps, "roughness", {});
    const FloatParam u = floatOrTexture(st, ps, "uroughness", r);
    const FloatParam v = floatOrTexture(st, ps, "vroughness", r);
    if (u.value < 0 || v.value < 0) throw errorAt(where, "roughness must not be negative");
    GgxRoughness g;
    g.u = remap ? std::sqrt(u.value) : u.value;
    g.v = remap ? std::sqrt(v.value) : v.value;
    if (use == TextureUse::PerHit)
        g.textureU = u.texture, g.textureV = v.texture;
    else if (u.texture >= 0 || v.texture >= 0)
        st.unsupported(where, "a textured roughness on a coated material", "roughness 0");
    return g;
}

bool remapsRoughness(const ParamSet& ps) {
    return ps.getBool("remaproughness", true);
}

// A coated material's constant float parameter (textures are not taken
// there yet: unsupported, the default under --lenient).
float constantFloat(ImportState& st, const ParamSet& ps, const std::string& name, float fallback) {
    const Param* p = ps.find(name);
    if (p && p->type == ParamType::Texture) {
        st.unsupported(p->where, "a texture for '" + name + "'", "its default");
        p->used = true;
        return fallback;
    }
    return ps.getFloat(name, fallback);
}

void setRoughness(Material& m, const GgxRoughness& g, bool remap) {
    m.roughness = g.u;
    m.roughnessTexture = g.textureU, m.roughnessVTexture = g.textureV;
    m.remapRoughness = remap;
    const bool textured = g.textureU >= 0 || g.textureV >= 0;
    m.roughnessV = g.v == g.u && !textured ? -1 : g.v;
}

// A spectrum parameter given by one of pbrt-v4's named metal spectra, else
// whatever rgbParam makes of it.
std::optional<Vec3f> metalParam(ImportState& st, const ParamSet& ps, const std::string& name) {
    const Param* p = ps.find(name);
    if (p && p->type == ParamType::Spectrum && p->strings.size() == 1) {
        if (auto rgb = namedMetalSpectrum(p->strings[0])) return rgb;
        st.unsupported(p->where,
                       "spectrum '" + p->strings[0] + "' for '" + name +
                           "' (named spectra: " + namedSpectraList() + ")",
                       "the parameter's default");
        return std::nullopt;
    }
    return rgbParam(st, ps, name);
}

// A dielectric's "eta": a float, or a named glass spectrum reduced to its
// index at the d line.
float dielectricEta(ImportState& st, const ParamSet& ps, const SourceLocation& where) {
    float eta = 1.5f;
    const Param* p = ps.find("eta");
    if (p && p->type == ParamType::Float && p->numbers.size() == 1) {
        eta = float(p->numbers[0]);
    } else if (p && p->type == ParamType::Spectrum && p->strings.size() == 1 &&
               namedGlassIor(p->strings[0])) {
        eta = *namedGlassIor(p->strings[0]);
    } else if (p) {
        st.unsupported(p->where, "this eta (a float or a named glass spectrum is)", "eta 1.5");
    }
    if (!(eta > 0) || !std::isfinite(eta)) throw errorAt(where, "eta must be positive");
    return eta;
}

// A conductor's parameters from `ps`; `remap` is the material's
// "remaproughness" (unprefixed also when `ps` holds coatedconductor's
// "conductor.*" parameters).
void conductor(ImportState& st, const ParamSet& ps, bool remap, TextureUse use,
               const SourceLocation& where, Material& m) {
    m.type = MaterialType::Conductor;
    setRoughness(m, ggxRoughness(st, ps, remap, use, where), remap);
    if (ps.find("reflectance")) {
        if (ps.find("eta") || ps.find("k"))
            throw errorAt(where, "conductor: give \"reflectance\" or \"eta\" and \"k\", not both");
        // pbrt-v4's alternative: eta 1 and the k that reflects r at normal
        // incidence, k = 2√r / √(1 − r), r clamped to [0, 0.9999].
        Vec3f r(0.5f);
        if (auto t = spectrumTextureParam(st, ps, "reflectance")) {
            if (use == TextureUse::PerHit)
                m.albedoTexture = *t;
            else
                st.unsupported(where, "a textured reflectance on a coated material",
                               "reflectance 0.5");
        } else if (auto rgb = rgbParam(st, ps, "reflectance")) {
            r = *rgb;
        }
        m.eta = Vec3f(1.0f);
        const auto k = [](float rc) {
            rc = std::clamp(rc, 0.0f, 0.9999f);
            return 2 * std::sqrt(rc) / std::sqrt(1 - rc);
        };
        m.k = {k(r.x), k(r.y), k(r.z)};
        return;
    }
    // pbrt-v4's default conductor is copper.
    m.eta = *namedMetalSpectrum("metal-Cu-eta");
    m.k = *namedMetalSpectrum("metal-Cu-k");
    if (auto eta = metalParam(st, ps, "eta")) m.eta = *eta;
    if (auto k = metalParam(st, ps, "k")) m.k = *k;
    if (!(m.eta.x >= 0 && m.eta.y >= 0 && m.eta.z >= 0 && m.k.x >= 0 && m.k.y >= 0 && m.k.z >= 0))
        throw errorAt(where, "conductor: eta and k must not be negative");
}

void diffuseTransmission(ImportState& st, const ParamSet& ps, Material& m) {
    m.type = MaterialType::DiffuseTransmission;
    Vec3f r(0.25f), t(0.25f);
    if (auto tex = spectrumTextureParam(st, ps, "reflectance"))
        m.albedoTexture = *tex;
    else if (auto rgb = rgbParam(st, ps, "reflectance"))
        r = *rgb;
    if (auto tex = spectrumTextureParam(st, ps, "transmittance"))
        m.transmittanceTexture = *tex;
    else if (auto rgb = rgbParam(st, ps, "transmittance"))
        t = *rgb;
    const float scale = ps.getFloat("scale", 1);
    m.albedoScale = scale;  // textured ones: at each hit
    // Clamped to [0, 1] as pbrt-v4's DiffuseTransmissionMaterial does.
    const auto clamped = [&](Vec3f c) {
        return Vec3f(std::clamp(scale * c.x, 0.0f, 1.0f), std::clamp(scale * c.y, 0.0f, 1.0f),
                     std::clamp(scale * c.z, 0.0f, 1.0f));
    };
    m.albedo = clamped(r);
    m.transmittance = clamped(t);
}

void mix(ImportState& st, const ParamSet& ps, const SourceLocation& where, Material& m) {
    m.type = MaterialType::Mix;
    const Param* names = ps.find("materials");
    if (!names || names->type != ParamType::String || names->strings.size() != 2)
        throw errorAt(where, "mix: needs \"string materials\" with two material names");
    // As in pbrt-v4, a mix's materials are named materials defined before it
    // (so no mix contains itself), and none is an interface.
    for (int i = 0; i < 2; ++i) {
        const std::string& part = names->strings[size_t(i)];
        const auto it = st.namedMaterials.find(part);
        if (it == st.namedMaterials.end() || st.pendingMaterials.count(part))
            throw errorAt(where, "mix: no material named '" + part + "' defined before it");
        if (st.result.scene.materials[size_t(it->second)].type == MaterialType::Interface)
            throw errorAt(where, "mix: '" + part + "' is an interface, which cannot be mixed");
        m.mix[i] = it->second;
    }
    const FloatParam amount = floatOrTexture(st, ps, "amount", {0.5f, -1});
    m.amount = amount.value, m.amountTexture = amount.texture;
    if (!std::isfinite(m.amount)) throw errorAt(where, "mix: amount must be a finite number");
}

// The coating and the medium under it of coateddiffuse and coatedconductor
// (pbrt-v4's defaults); `coat` holds the interface's own parameters (the
// prefixed "interface.*" of coatedconductor), with the material's own
// (unprefixed) "remaproughness".
Coating coating(ImportState& st, const ParamSet& ps, const ParamSet& coat,
                const SourceLocation& where) {
    Coating c;
    const GgxRoughness g =
        ggxRoughness(st, coat, remapsRoughness(ps), TextureUse::Unsupported, where);
    c.roughness = g.u;
    c.roughnessV = g.v == g.u ? -1 : g.v;
    c.eta = dielectricEta(st, coat, where);
    c.thickness = constantFloat(st, ps, "thickness", 0.01f);
    c.g = constantFloat(st, ps, "g", 0);
    if (auto albedo = rgbParam(st, ps, "albedo")) c.albedo = *albedo;
    c.maxDepth = ps.getInt("maxdepth", 10);
    c.nSamples = ps.getInt("nsamples", 1);
    if (!(c.thickness > 0) || !std::isfinite(c.thickness))
        throw errorAt(where, "coated material: thickness must be positive");
    if (!(c.g > -1 && c.g < 1)) throw errorAt(where, "coated material: g must lie in (-1, 1)");
    if (c.maxDepth < 1 || c.nSamples < 1)
        throw errorAt(where, "coated material: maxdepth and nsamples must be at least 1");
    if (!(c.albedo.x >= 0 && c.albedo.y >= 0 && c.albedo.z >= 0 && c.albedo.x <= 1 &&
          c.albedo.y <= 1 && c.albedo.z <= 1))
        throw errorAt(where, "coated material: albedo must lie in [0, 1]");
    return c;
}

void coatedConductor(ImportState& st, const ParamSet& ps, const SourceLocation& where,
                     Material& m) {
    const ParamSet coat = ps.withPrefix("interface."), metal = ps.withPrefix("conductor.");
    conductor(st, metal, remapsRoughness(ps), TextureUse::Unsupported, where, m);
    if (ps.find("reflectance")) {
        // pbrt-v4's coatedconductor takes "reflectance" unprefixed, in place
        // of conductor.eta and conductor.k: eta 1 and k = 2√r / √(1 − r).
        if (metal.find("eta") || metal.find("k"))
            throw errorAt(where,
                          "coatedconductor: give \"reflectance\" or \"conductor.eta\" "
                          "and \"conductor.k\", not both");
        Vec3f r(0.5f);
        if (auto rgb = rgbParam(st, ps, "reflectance")) r = *rgb;
        const auto k = [](float rc) {
            rc = std::clamp(rc, 0.0f, 0.9999f);
            return 2 * std::sqrt(rc) / std::sqrt(1 - rc);
        };
        m.eta = Vec3f(1.0f);
        m.k = {k(r.x), k(r.y), k(r.z)};
    }
    m.coating = coating(st, ps, coat, where);
    m.type = MaterialType::CoatedConductor;
    st.checkUnused(coat, "Material \"coatedconductor\" (prefixed \"interface.\")");
    st.checkUnused(metal, "Material \"coatedconductor\" (prefixed \"conductor.\")");
}

Material makeMaterial(ImportState& st, const std::string& type, const std::string& name,
                      const ParamSet& given, const SourceLocation& where) {
    const ParamSet ps = given.withDefaults(st.gs.attributes["material"]);
    ps.ignore("type");  // MakeNamedMaterial's
    Material m = greyDiffuse(name.empty() ? type + "@" + std::to_string(where.line) : name);
    if (type == "diffuse") {
        if (auto t = spectrumTextureParam(st, ps, "reflectance"))
            m.albedoTexture = *t;
        else if (auto r = rgbParam(st, ps, "reflectance"))
            m.albedo = *r;
    } else if (type == "dielectric" || type == "thindielectric") {
        m.type = type == "dielectric" ? MaterialType::Dielectric : MaterialType::ThinDielectric;
        m.albedo = Vec3f(1.0f);
        m.ior = dielectricEta(st, ps, where);
        if (type == "dielectric") {
            const bool remap = remapsRoughness(ps);
            setRoughness(m, ggxRoughness(st, ps, remap, TextureUse::PerHit, where), remap);
        } else {
            setRoughness(m, GgxRoughness{}, true);
        }
    } else if (type == "conductor") {
        conductor(st, ps, remapsRoughness(ps), TextureUse::PerHit, where, m);
    } else if (type == "diffusetransmission") {
        diffuseTransmission(st, ps, m);
    } else if (type == "mix") {
        mix(st, ps, where, m);
    } else if (type == "interface") {
        m.type = MaterialType::Interface;
    } else if (type == "coateddiffuse") {
        m.type = MaterialType::CoatedDiffuse;
        if (auto r = rgbParam(st, ps, "reflectance")) m.albedo = *r;
        m.coating = coating(st, ps, ps, where);
    } else if (type == "coatedconductor") {
        coatedConductor(st, ps, where, m);
    } else {
        st.unsupported(where, "material '" + type + "' (or these parameters of it)",
                       "diffuse grey");
        markAllUsed(ps);
    }
    // Every material but mix and interface takes a bump or normal map (the
    // others leave the parameters unused, an error as in pbrt-v4).
    if (m.type != MaterialType::Mix && m.type != MaterialType::Interface) materialMaps(st, ps, m);
    st.checkUnused(ps, "Material \"" + type + "\"");
    return m;
}

}  // namespace

int material(ImportState& st, const std::string& type, const std::string& name,
             const ParamSet& given, const SourceLocation& where) {
    st.result.scene.materials.push_back(makeMaterial(st, type, name, given, where));
    return int(st.result.scene.materials.size()) - 1;
}

int namedMaterialRef(ImportState& st, const std::string& name, const SourceLocation& where,
                     const std::string& user) {
    const auto it = st.namedMaterials.find(name);
    if (it != st.namedMaterials.end()) return it->second;
    // Not yet defined: a slot that MakeNamedMaterial fills later.
    st.result.scene.materials.push_back(greyDiffuse(name));
    const int index = int(st.result.scene.materials.size()) - 1;
    st.namedMaterials[name] = index;
    st.pendingMaterials.emplace(name, ImportState::PendingMaterial{where, user});
    return index;
}

void makeNamedMaterial(ImportState& st, const std::string& name, const std::string& type,
                       const ParamSet& ps, const SourceLocation& where) {
    const auto it = st.namedMaterials.find(name);
    if (it == st.namedMaterials.end()) {
        st.namedMaterials[name] = material(st, type, name, ps, where);
        return;
    }
    // pbrt-v4 rejects a redefinition too.
    if (!st.pendingMaterials.count(name))
        throw errorAt(where, "MakeNamedMaterial: material '" + name + "' is already defined");
    // Made while still pending, so that a mix cannot name the material it defines.
    Material m = makeMaterial(st, type, name, ps, where);
    st.pendingMaterials.erase(name);
    st.result.scene.materials[size_t(it->second)] = std::move(m);
}

void finishMaterials(ImportState& st) {
    for (const auto& [name, use] : st.pendingMaterials)
        throw errorAt(use.where, use.user + ": no material named '" + name + "'");
}

}  // namespace pathlab::pbrt
