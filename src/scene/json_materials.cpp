// pathlab's JSON scene format: the "materials" section (docs/scene-format.md),
// as scene.h's Material, textured parameters naming textures of the
// "textures" section (json_textures.cpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "scene/json_node.h"
#include "scene/texture_loader.h"
#include "scene/textures/image_encoding.h"

namespace pathlab::jsonscene {
namespace {

struct Metal {
    const char* name;
    Vec3f eta, k;
};
// Complex indices of refraction at the sRGB primaries' wavelengths
// (approximately 650, 550, 450 nm), from the measured data pbrt ships.
constexpr Metal kMetals[] = {
    {"gold", {0.143f, 0.374f, 1.442f}, {3.983f, 2.385f, 1.603f}},
    {"silver", {0.155f, 0.117f, 0.138f}, {4.828f, 3.122f, 2.147f}},
    {"copper", {0.200f, 0.924f, 1.102f}, {3.912f, 2.452f, 2.142f}},
    {"aluminium", {1.657f, 0.880f, 0.521f}, {9.224f, 6.270f, 4.837f}},
};

// GGX alpha: "roughness", and "roughnessV" along v when anisotropic — or,
// with "remapRoughness": true, pbrt-v4's roughness r whose alpha is √r.
// Either may name a float texture (`b` given: not on coatings, whose layered
// BSDF is built once), evaluated at each hit; a textured "roughness" is
// also the one along v unless "roughnessV" is given, as pbrt-v4's
// "vroughness" defaults to "roughness".
void parseRoughness(const Node& n, Material& m, const Builder* b = nullptr) {
    const bool remap = n.has("remapRoughness") && n["remapRoughness"].boolean();
    m.remapRoughness = remap;
    for (const char* key : {"roughness", "roughnessV"}) {
        if (!n.has(key)) continue;
        const bool v = key[9] == 'V';
        if (const int tex = b ? textureParam(n[key], *b, true) : -1; tex >= 0) {
            (v ? m.roughnessVTexture : m.roughnessTexture) = tex;
            (v ? m.roughnessV : m.roughness) = 0;
            continue;
        }
        const float r = n[key].number();
        if (r < 0) n[key].fail("must not be negative");
        (v ? m.roughnessV : m.roughness) = remap ? std::sqrt(r) : r;
    }
    if (m.roughnessTexture >= 0 && !n.has("roughnessV")) {
        m.roughnessVTexture = m.roughnessTexture;
        m.roughnessV = 0;
    }
}

// A colour parameter that may name a spectrum texture: its texture index in
// `texture`, else the colour in `colour`.
void colourOrTexture(const Node& n, const Builder& b, Vec3f& colour, int& texture) {
    texture = textureParam(n, b, false);
    if (texture < 0) colour = n.colour();
}

// pbrt-v4's conductor given a reflectance r instead of an index: eta 1 and
// the k that reflects r at normal incidence, k = 2√r / √(1 − r), r clamped
// to [0, 0.9999].
Vec3f reflectanceK(Vec3f r) {
    const auto k = [](float rc) {
        rc = std::clamp(rc, 0.0f, 0.9999f);
        return 2 * std::sqrt(rc) / std::sqrt(1 - rc);
    };
    return {k(r.x), k(r.y), k(r.z)};
}

// A conductor's complex index: a named "metal", "eta" and "k", or a
// "reflectance" (a colour, or on a conductor a spectrum texture).
void parseConductorIndex(const Node& n, Material& m, const Builder* b = nullptr) {
    if (n.has("reflectance")) {
        if (n.has("metal") || n.has("eta") || n.has("k"))
            n.fail("give one of 'metal', 'eta' and 'k', or 'reflectance'");
        Vec3f r(0.5f);
        if (b)
            colourOrTexture(n["reflectance"], *b, r, m.albedoTexture);
        else
            r = n["reflectance"].colour();
        m.eta = Vec3f(1.0f), m.k = reflectanceK(r);
    } else if (n.has("metal")) {
        if (n.has("eta") || n.has("k")) n.fail("give either 'metal' or 'eta' and 'k', not both");
        const Node metal = n["metal"];
        const std::string s = metal.string();
        const Metal* found = nullptr;
        for (const Metal& x : kMetals)
            if (s == x.name) found = &x;
        if (!found) metal.fail("unknown metal '" + s + "' (gold, silver, copper, aluminium)");
        m.eta = found->eta, m.k = found->k;
    } else {
        m.eta = n["eta"].colour();
        m.k = n["k"].colour();
    }
}

// A whole number from lo to hi.
int countIn(const Node& n, int lo, int hi) {
    const float v = n.number();
    if (v != std::floor(v) || v < float(lo) || v > float(hi))
        n.fail("must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return int(v);
}

// The coating of coateddiffuse and coatedconductor (scene.h's Coating;
// pbrt-v4's parameters and defaults).
Coating parseCoating(const Node& n) {
    n.keys({"ior", "roughness", "roughnessV", "thickness", "albedo", "g", "maxDepth", "samples"});
    Coating c;
    if (n.has("ior")) c.eta = n["ior"].positive();
    Material alphas;
    alphas.roughness = 0;
    parseRoughness(n, alphas);
    c.roughness = alphas.roughness, c.roughnessV = alphas.roughnessV;
    if (n.has("thickness")) c.thickness = n["thickness"].positive();
    if (n.has("albedo")) {
        c.albedo = n["albedo"].colour();
        if (maxComponent(c.albedo) > 1) n["albedo"].fail("must be at most 1");
    }
    if (n.has("g")) {
        c.g = n["g"].number();
        if (!(c.g > -1 && c.g < 1)) n["g"].fail("must lie strictly between -1 and 1");
    }
    if (n.has("maxDepth")) c.maxDepth = countIn(n["maxDepth"], 1, 4096);
    if (n.has("samples")) c.nSamples = countIn(n["samples"], 1, 4096);
    return c;
}

// The keys of a material's bump and normal maps (render/bump_mapping.h).
constexpr std::string_view kMapKeys[] = {"normalMap", "bumpMap", "bumpScale", "displacement"};

}  // namespace

int loadImage(const Node& t, Builder& b, bool linear) {
    const std::string path = t.file().lexically_normal().string();
    const std::string key = linear ? path + "\nlinear" : path;
    auto it = b.textureIndex.find(key);
    if (it != b.textureIndex.end()) return it->second;
    try {
        b.scene.textures.push_back(loadTexture(path));
    } catch (const InputError& e) {
        t.fail(e.what());
    }
    if (linear) reencodeTexels(b.scene.textures.back(), ImageEncoding{ImageEncoding::Linear});
    return b.textureIndex.emplace(key, int(b.scene.textures.size()) - 1).first->second;
}

namespace {

// "normalMap": an image of tangent-space normals; or "bumpMap": an image of
// heights (its first channel, times "bumpScale", default 1), read linearly,
// looked up at the hit's (u, v) as pbrt-v4's imagemap (bilinear, repeating);
// or "displacement": heights as a number or a float texture of "textures"
// (pbrt-v4's "displacement").
void parseMaps(const Node& n, Material& m, Builder& b) {
    if (n.has("normalMap") && n.has("bumpMap"))
        n.fail("give either 'normalMap' or 'bumpMap', not both");
    if (n.has("displacement") && (n.has("normalMap") || n.has("bumpMap")))
        n.fail("give either 'displacement' or a map ('normalMap', 'bumpMap'), not both");
    if (n.has("bumpScale") && !n.has("bumpMap")) n["bumpScale"].fail("needs 'bumpMap'");
    if (n.has("normalMap")) m.normalMap = loadImage(n["normalMap"], b, true);
    if (n.has("displacement")) {
        m.displacementTexture = textureParam(n["displacement"], b, true);
        if (m.displacementTexture >= 0) return;
        ShadingTexture height;  // a constant, as pbrt-v4's GetFloatTextureOrNull
        height.isFloat = true;
        height.value = Vec3f(n["displacement"].number());
        b.scene.shadingTextures.push_back(height);
        m.displacementTexture = int(b.scene.shadingTextures.size()) - 1;
    }
    if (!n.has("bumpMap")) return;
    ShadingTexture heights;
    heights.kind = TextureKind::Image;
    heights.isFloat = true;
    heights.image = loadImage(n["bumpMap"], b, true);
    if (n.has("bumpScale")) heights.scale = n["bumpScale"].number();
    b.scene.shadingTextures.push_back(heights);
    m.displacementTexture = int(b.scene.shadingTextures.size()) - 1;
}

// A colour in [0, 1] (key of n), or a spectrum texture when `b` is given.
void fractionOrTexture(const Node& n, const char* key, const Builder* b, Vec3f& colour,
                       int& texture) {
    const Node c = n[key];
    if (b && (texture = textureParam(c, *b, false)) >= 0) return;
    colour = c.colour();
    if (maxComponent(colour) > 1) c.fail("must be at most 1");
}

void parseDiffuse(const Node& n, Material& m, Builder& b) {
    n.keys({"type", "albedo", "texture"}, kMapKeys);
    m.type = MaterialType::Diffuse;
    // The texture is the albedo (scene.h); both would leave one unused.
    if (n.has("albedo") && n.has("texture")) n.fail("give either 'albedo' or 'texture', not both");
    if (n.has("albedo")) colourOrTexture(n["albedo"], b, m.albedo, m.albedoTexture);
    if (n.has("texture")) {
        m.texture = loadImage(n["texture"], b, false);
        m.albedo = Vec3f(1.0f);
    }
}

void parseDielectric(const Node& n, const std::string& type, Material& m, const Builder& b) {
    if (type == "dielectric")
        n.keys({"type", "ior", "roughness", "roughnessV", "remapRoughness"}, kMapKeys);
    else
        n.keys({"type", "ior"}, kMapKeys);
    m.type = type == "dielectric" ? MaterialType::Dielectric : MaterialType::ThinDielectric;
    m.albedo = Vec3f(1.0f);
    m.roughness = 0;
    if (n.has("ior")) m.ior = n["ior"].positive();
    parseRoughness(n, m, &b);
}

void parseDiffuseTransmission(const Node& n, Material& m, const Builder& b) {
    n.keys({"type", "reflectance", "transmittance"}, kMapKeys);
    m.type = MaterialType::DiffuseTransmission;
    m.albedo = Vec3f(0.25f);
    if (n.has("reflectance")) fractionOrTexture(n, "reflectance", &b, m.albedo, m.albedoTexture);
    if (n.has("transmittance"))
        fractionOrTexture(n, "transmittance", &b, m.transmittance, m.transmittanceTexture);
}

void parseMix(const Node& n, Material& m, Builder& b) {
    n.keys({"type", "materials", "amount"});
    m.type = MaterialType::Mix;
    const Node parts = n["materials"];
    if (parts.size() != 2) parts.fail("expected two material names");
    // Resolved when every material is known (parseMaterials).
    for (int i = 0; i < 2; ++i) b.mixParts.push_back({parts.at(size_t(i)), i});
    if (!n.has("amount")) return;
    m.amountTexture = textureParam(n["amount"], b, true);
    if (m.amountTexture < 0) m.amount = n["amount"].number();
}

// coateddiffuse and coatedconductor: constant parameters only (their layered
// BSDF is built once per material, as for .pbrt files).
void parseCoated(const Node& n, const std::string& type, Material& m) {
    if (type == "coateddiffuse") {
        n.keys({"type", "reflectance", "coating"}, kMapKeys);
        m.type = MaterialType::CoatedDiffuse;
        m.albedo = Vec3f(0.5f);
        int none = -1;
        if (n.has("reflectance")) fractionOrTexture(n, "reflectance", nullptr, m.albedo, none);
    } else {
        n.keys({"type", "metal", "eta", "k", "reflectance", "roughness", "roughnessV",
                "remapRoughness", "coating"},
               kMapKeys);
        m.type = MaterialType::CoatedConductor;
        m.roughness = 0;
        parseConductorIndex(n, m);
        parseRoughness(n, m);
    }
    if (n.has("coating")) m.coating = parseCoating(n["coating"]);
}

Material parseMaterial(const Node& n, const std::string& name, Builder& b) {
    Material m;
    m.name = name;
    const std::string type = n["type"].string();
    if (type == "diffuse") {
        parseDiffuse(n, m, b);
    } else if (type == "mirror") {
        n.keys({"type", "albedo"}, kMapKeys);
        m.type = MaterialType::Mirror;
        m.albedo = n.has("albedo") ? n["albedo"].colour() : Vec3f(1.0f);
    } else if (type == "dielectric" || type == "thindielectric") {
        parseDielectric(n, type, m, b);
    } else if (type == "diffusetransmission") {
        parseDiffuseTransmission(n, m, b);
    } else if (type == "mix") {
        parseMix(n, m, b);
    } else if (type == "interface") {
        n.keys({"type"});
        m.type = MaterialType::Interface;
    } else if (type == "conductor") {
        n.keys({"type", "metal", "eta", "k", "reflectance", "roughness", "roughnessV",
                "remapRoughness"},
               kMapKeys);
        m.type = MaterialType::Conductor;
        parseConductorIndex(n, m, &b);
        parseRoughness(n, m, &b);
    } else if (type == "coateddiffuse" || type == "coatedconductor") {
        parseCoated(n, type, m);
    } else {
        n["type"].fail("unknown material type '" + type +
                       "' (diffuse, mirror, dielectric, conductor, thindielectric, "
                       "diffusetransmission, coateddiffuse, coatedconductor, mix, interface)");
    }
    if (m.type != MaterialType::Mix && m.type != MaterialType::Interface) parseMaps(n, m, b);
    return m;
}

// A mix material that contains itself (directly or through other mixes)
// chooses forever.
void rejectCyclicMixes(const std::vector<Material>& mats, const Node& where) {
    for (size_t i = 0; i < mats.size(); ++i) {
        if (mats[i].type != MaterialType::Mix) continue;
        std::vector<char> seen(mats.size(), 0);
        std::vector<int> stack{mats[i].mix[0], mats[i].mix[1]};
        while (!stack.empty()) {
            const int c = stack.back();
            stack.pop_back();
            if (c == int(i)) where.fail("mix material '" + mats[i].name + "' contains itself");
            if (seen[size_t(c)] || mats[size_t(c)].type != MaterialType::Mix) continue;
            seen[size_t(c)] = 1;
            stack.push_back(mats[size_t(c)].mix[0]);
            stack.push_back(mats[size_t(c)].mix[1]);
        }
    }
}

}  // namespace

void parseMaterials(const Node& mats, Builder& b) {
    struct MixName {
        int material, slot;
        Node name;
    };
    std::vector<MixName> mixNames;
    SceneDescription& s = b.scene;
    mats.requireObject();
    for (const auto& [name, value] : mats.json().items()) {
        const Node m = mats[name.c_str()];
        s.materials.push_back(parseMaterial(m, name, b));
        b.materialIndex[name] = int(s.materials.size()) - 1;
        for (const Builder::MixPart& part : b.mixParts)
            mixNames.push_back({int(s.materials.size()) - 1, part.slot, part.name});
        b.mixParts.clear();
    }
    for (const MixName& x : mixNames)
        s.materials[size_t(x.material)].mix[x.slot] = b.material(x.name);
    rejectCyclicMixes(s.materials, mats);
}

}  // namespace pathlab::jsonscene
