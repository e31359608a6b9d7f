// Materials and textures (pbrt-v4 File Format, "Materials", "Textures"). This
// stage maps what pathlab's renderer already has with pbrt-v4's meaning —
// diffuse, smooth dielectric, conductor with RGB eta/k — and reports the rest
// as unsupported (substituted under --lenient). Lights: world_lights.cpp.
#include <cmath>

#include "scene/pbrt/parser_state.h"

namespace pathlab::pbrt {

std::optional<Vec3f> rgbParam(ImportState& st, const ParamSet& ps, const std::string& name) {
    const Param* p = ps.find(name);
    if (!p) return std::nullopt;
    if (p->type == ParamType::Rgb) {
        if (p->numbers.size() != 3)
            throw errorAt(p->where, "parameter '" + name + "' needs one RGB triple");
        return Vec3f(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
    }
    if (p->type == ParamType::Float && p->numbers.size() == 1) return Vec3f(float(p->numbers[0]));
    if (p->type == ParamType::Spectrum || p->type == ParamType::Blackbody ||
        p->type == ParamType::Texture) {
        st.unsupported(p->where,
                       std::string(paramTypeName(p->type)) + " values (parameter '" + name + "')",
                       "the parameter's default");
        return std::nullopt;
    }
    throw errorAt(p->where, "parameter '" + name + "' must be rgb or spectrum, not " +
                                paramTypeName(p->type));
}

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

// pbrt-v4's roughness parameters: "roughness" or u/v roughness, remapped to
// GGX alpha = sqrt(roughness) unless remaproughness is false
// (TrowbridgeReitzDistribution::RoughnessToAlpha).
float ggxAlpha(ImportState& st, const ParamSet& ps, const SourceLocation& where) {
    // A roughness texture has no value yet: its default stands in.
    const auto value = [&](const std::string& name, float fallback) {
        const Param* p = ps.find(name);
        if (p && p->type == ParamType::Texture) {
            st.unsupported(p->where, "a texture for '" + name + "'", "its default");
            return fallback;
        }
        return ps.getFloat(name, fallback);
    };
    const float r = value("roughness", 0);
    const float u = value("uroughness", r), v = value("vroughness", r);
    if (u != v) st.unsupported(where, "anisotropic roughness", "their mean, isotropic");
    const float rough = 0.5f * (u + v);
    if (rough < 0) throw errorAt(where, "roughness must not be negative");
    return ps.getBool("remaproughness", true) ? std::sqrt(rough) : rough;
}

}  // namespace

int material(ImportState& st, const std::string& type, const std::string& name,
             const ParamSet& given, const SourceLocation& where) {
    const ParamSet ps = given.withDefaults(st.gs.attributes["material"]);
    ps.ignore("type");  // MakeNamedMaterial's
    Material m = greyDiffuse(name.empty() ? type + "@" + std::to_string(where.line) : name);
    for (const char* bump : {"displacement", "normalmap"})
        if (ps.find(bump)) st.unsupported(where, std::string("material ") + bump, "no bump");
    if (type == "diffuse") {
        if (auto r = rgbParam(st, ps, "reflectance")) m.albedo = *r;
    } else if (type == "dielectric" && ggxAlpha(st, ps, where) == 0) {
        m.type = MaterialType::Dielectric;
        const Param* eta = ps.find("eta");
        if (eta && eta->type == ParamType::Float && eta->numbers.size() == 1) {
            m.ior = float(eta->numbers[0]);
        } else if (eta) {
            st.unsupported(eta->where, "a spectral eta", "eta 1.5");
        }
        if (!(m.ior > 0)) throw errorAt(where, "dielectric: eta must be positive");
        if (m.ior == 1) st.unsupported(where, "dielectric with eta 1 (a pass-through)", "glass");
    } else if (type == "conductor" && !ps.find("reflectance")) {
        m.type = MaterialType::Conductor;
        m.roughness = ggxAlpha(st, ps, where);
        // pbrt-v4's default conductor is copper (metal-Cu-eta / -k); the RGB
        // values stand in for those spectra until named spectra exist.
        m.eta = {0.2004f, 0.9240f, 1.1022f};
        m.k = {3.9129f, 2.4528f, 2.1421f};
        if (auto eta = rgbParam(st, ps, "eta")) m.eta = *eta;
        if (auto k = rgbParam(st, ps, "k")) m.k = *k;
    } else if (type == "interface" || type == "") {
        st.unsupported(where, "material '" + type + "'", "diffuse grey");
        markAllUsed(ps);
    } else {
        st.unsupported(where, "material '" + type + "' (or these parameters of it)",
                       "diffuse grey");
        markAllUsed(ps);
    }
    st.checkUnused(ps, "Material \"" + type + "\"");
    st.result.scene.materials.push_back(m);
    return int(st.result.scene.materials.size()) - 1;
}

void texture(ImportState& st, const std::string& name, const std::string& colorType,
             const std::string& type, const ParamSet& ps, const SourceLocation& where) {
    if (colorType != "spectrum" && colorType != "float" && colorType != "color")
        throw errorAt(where, "Texture '" + name +
                                 "': type must be \"spectrum\" or \"float\", got '" + colorType +
                                 "'");
    markAllUsed(ps);
    st.unsupported(where, "Texture '" + name + "' (" + type + ")",
                   "the default of every parameter that uses it");
}

}  // namespace pathlab::pbrt
