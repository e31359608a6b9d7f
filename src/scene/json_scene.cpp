#include "scene/json_scene.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "scene/light_selection.h"
#include "scene/mesh_utils.h"
#include "scene/obj_loader.h"
#include "scene/texture_loader.h"
#include "scene/textures/image_encoding.h"

namespace pathlab {
namespace fs = std::filesystem;
namespace {

// Keeps the keys in file order, so materials are numbered as written.
using Json = nlohmann::ordered_json;

const char* typeName(const Json& j) {
    if (j.is_number()) return "a number";
    if (j.is_string()) return "a string";
    if (j.is_boolean()) return "a boolean";
    if (j.is_array()) return "an array";
    if (j.is_object()) return "an object";
    return "null";
}

struct Context {
    std::string source;
    fs::path baseDir;
};

// A JSON value with its position in the document ("meshes[2].material"), so
// every error names the key it is about.
class Node {
  public:
    Node(const Json& j, std::string path, const Context& ctx)
        : j_(j), path_(std::move(path)), ctx_(ctx) {}

    const Json& json() const { return j_; }
    const std::string& path() const { return path_; }

    [[noreturn]] void fail(const std::string& message) const {
        throw InputError(ctx_.source + ": " + (path_.empty() ? "" : path_ + ": ") + message);
    }

    void requireObject() const {
        if (!j_.is_object()) fail(std::string("expected an object, got ") + typeName(j_));
    }
    // Every key must be one of `allowed` or `more`.
    void keys(std::initializer_list<std::string_view> allowed,
              std::span<const std::string_view> more = {}) const {
        requireObject();
        for (const auto& [key, value] : j_.items()) {
            bool ok = false;
            for (std::string_view a : allowed) ok |= key == a;
            for (std::string_view a : more) ok |= key == a;
            if (ok) continue;
            std::string list;
            for (std::string_view a : allowed) {
                if (!list.empty()) list += ", ";
                list += a;
            }
            for (std::string_view a : more) list += ", " + std::string(a);
            fail("unknown key '" + key + "' (expected one of: " + list + ")");
        }
    }
    bool has(const char* key) const { return j_.is_object() && j_.contains(key); }
    Node operator[](const char* key) const {
        requireObject();
        if (!j_.contains(key)) fail(std::string("missing required key '") + key + "'");
        return Node(j_.at(key), join(key), ctx_);
    }
    size_t size() const {
        if (!j_.is_array()) fail(std::string("expected an array, got ") + typeName(j_));
        return j_.size();
    }
    Node at(size_t i) const { return Node(j_.at(i), path_ + "[" + std::to_string(i) + "]", ctx_); }

    float number() const {
        if (!j_.is_number()) fail(std::string("expected a number, got ") + typeName(j_));
        const float v = j_.get<float>();
        if (!std::isfinite(v)) fail("number out of range");
        return v;
    }
    float positive() const {
        const float v = number();
        if (!(v > 0)) fail("must be positive");
        return v;
    }
    // An image side: the same limit as `render --size`, so that a scene file
    // cannot ask for an image the renderer cannot hold.
    int imageSide() const {
        if (!j_.is_number_integer()) fail(std::string("expected an integer, got ") + typeName(j_));
        const auto v = j_.get<int64_t>();
        if (v < 1 || v > kMaxImageSide)
            fail("must be between 1 and " + std::to_string(kMaxImageSide) + ", got " +
                 std::to_string(v));
        return int(v);
    }
    bool boolean() const {
        if (!j_.is_boolean()) fail(std::string("expected true or false, got ") + typeName(j_));
        return j_.get<bool>();
    }
    std::string string() const {
        if (!j_.is_string()) fail(std::string("expected a string, got ") + typeName(j_));
        return j_.get<std::string>();
    }
    Vec3f vec3() const {
        if (!j_.is_array() || j_.size() != 3 || !j_[0].is_number() || !j_[1].is_number() ||
            !j_[2].is_number())
            fail(std::string("expected an array of 3 numbers, got ") + typeName(j_));
        const Vec3f v{at(0).number(), at(1).number(), at(2).number()};
        return v;
    }
    // An RGB triple, or one number for grey; never negative.
    Vec3f colour() const {
        Vec3f c;
        if (j_.is_number())
            c = Vec3f(number());
        else if (j_.is_array() && j_.size() == 3)
            c = vec3();
        else
            fail(std::string("expected an RGB colour [r, g, b] or one number, got ") +
                 typeName(j_));
        if (c.x < 0 || c.y < 0 || c.z < 0) fail("colour components must not be negative");
        return c;
    }
    fs::path file() const {
        const std::string s = string();
        if (s.empty()) fail("empty file name");
        const fs::path p = fs::path(s).is_absolute() ? fs::path(s) : ctx_.baseDir / s;
        std::error_code ec;
        const fs::file_status status = fs::status(p, ec);
        if (!fs::exists(status)) fail("file '" + p.string() + "' does not exist");
        if (!fs::is_regular_file(status)) fail("'" + p.string() + "' is not a regular file");
        return p;
    }

  private:
    std::string join(const char* key) const { return path_.empty() ? key : path_ + "." + key; }
    const Json& j_;
    std::string path_;
    const Context& ctx_;
};

struct Builder {
    SceneDescription scene;
    std::map<std::string, int> materialIndex;
    std::map<std::string, int> textureIndex;  // by path, loaded once
    // The component names of the mix material parsed last, with their slot.
    struct MixPart {
        Node name;
        int slot;
    };
    std::vector<MixPart> mixParts;

    int material(const Node& n) {
        const std::string name = n.string();
        auto it = materialIndex.find(name);
        if (it == materialIndex.end()) n.fail("unknown material '" + name + "'");
        return it->second;
    }
};

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

// GGX alpha: "roughness", and "roughnessV" along v when anisotropic.
void parseRoughness(const Node& n, Material& m) {
    for (const char* key : {"roughness", "roughnessV"}) {
        if (!n.has(key)) continue;
        const float r = n[key].number();
        if (r < 0) n[key].fail("must not be negative");
        (key[9] == 'V' ? m.roughnessV : m.roughness) = r;
    }
}

// A conductor's complex index: a named "metal", or "eta" and "k".
void parseConductorIndex(const Node& n, Material& m) {
    if (n.has("metal")) {
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
constexpr std::string_view kMapKeys[] = {"normalMap", "bumpMap", "bumpScale"};

// An image named by node t, read once per file; `linear`: its code values
// taken as linear (a PNG's sRGB decoding undone), as maps need.
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

// "normalMap": an image of tangent-space normals; or "bumpMap": an image of
// heights (its first channel, times "bumpScale", default 1), read linearly,
// looked up at the hit's (u, v) as pbrt-v4's imagemap (bilinear, repeating).
void parseMaps(const Node& n, Material& m, Builder& b) {
    if (n.has("normalMap") && n.has("bumpMap"))
        n.fail("give either 'normalMap' or 'bumpMap', not both");
    if (n.has("bumpScale") && !n.has("bumpMap")) n["bumpScale"].fail("needs 'bumpMap'");
    if (n.has("normalMap")) m.normalMap = loadImage(n["normalMap"], b, true);
    if (!n.has("bumpMap")) return;
    ShadingTexture heights;
    heights.kind = TextureKind::Image;
    heights.isFloat = true;
    heights.image = loadImage(n["bumpMap"], b, true);
    if (n.has("bumpScale")) heights.scale = n["bumpScale"].number();
    b.scene.shadingTextures.push_back(heights);
    m.displacementTexture = int(b.scene.shadingTextures.size()) - 1;
}

Material parseMaterial(const Node& n, const std::string& name, Builder& b) {
    Material m;
    m.name = name;
    const std::string type = n["type"].string();
    if (type == "diffuse") {
        n.keys({"type", "albedo", "texture"}, kMapKeys);
        m.type = MaterialType::Diffuse;
        // The texture is the albedo (scene.h); both would leave one unused.
        if (n.has("albedo") && n.has("texture"))
            n.fail("give either 'albedo' or 'texture', not both");
        if (n.has("albedo")) m.albedo = n["albedo"].colour();
        if (n.has("texture")) {
            m.texture = loadImage(n["texture"], b, false);
            m.albedo = Vec3f(1.0f);
        }
    } else if (type == "mirror") {
        n.keys({"type", "albedo"}, kMapKeys);
        m.type = MaterialType::Mirror;
        m.albedo = n.has("albedo") ? n["albedo"].colour() : Vec3f(1.0f);
    } else if (type == "dielectric" || type == "thindielectric") {
        if (type == "dielectric")
            n.keys({"type", "ior", "roughness", "roughnessV"}, kMapKeys);
        else
            n.keys({"type", "ior"}, kMapKeys);
        m.type = type == "dielectric" ? MaterialType::Dielectric : MaterialType::ThinDielectric;
        m.albedo = Vec3f(1.0f);
        m.roughness = 0;
        if (n.has("ior")) m.ior = n["ior"].positive();
        parseRoughness(n, m);
    } else if (type == "diffusetransmission") {
        n.keys({"type", "reflectance", "transmittance"}, kMapKeys);
        m.type = MaterialType::DiffuseTransmission;
        const auto fraction = [&](const char* key) {
            const Vec3f c = n[key].colour();
            if (maxComponent(c) > 1) n[key].fail("must be at most 1");
            return c;
        };
        if (n.has("reflectance"))
            m.albedo = fraction("reflectance");
        else
            m.albedo = Vec3f(0.25f);
        if (n.has("transmittance")) m.transmittance = fraction("transmittance");
    } else if (type == "mix") {
        n.keys({"type", "materials", "amount"});
        m.type = MaterialType::Mix;
        const Node parts = n["materials"];
        if (parts.size() != 2) parts.fail("expected two material names");
        // Resolved when every material is known (resolveMixes).
        for (int i = 0; i < 2; ++i) b.mixParts.push_back({parts.at(size_t(i)), i});
        if (n.has("amount")) m.amount = n["amount"].number();
    } else if (type == "interface") {
        n.keys({"type"});
        m.type = MaterialType::Interface;
    } else if (type == "conductor") {
        n.keys({"type", "metal", "eta", "k", "roughness", "roughnessV"}, kMapKeys);
        m.type = MaterialType::Conductor;
        parseConductorIndex(n, m);
        parseRoughness(n, m);
    } else if (type == "coateddiffuse") {
        n.keys({"type", "reflectance", "coating"}, kMapKeys);
        m.type = MaterialType::CoatedDiffuse;
        m.albedo = Vec3f(0.5f);
        if (n.has("reflectance")) {
            m.albedo = n["reflectance"].colour();
            if (maxComponent(m.albedo) > 1) n["reflectance"].fail("must be at most 1");
        }
        if (n.has("coating")) m.coating = parseCoating(n["coating"]);
    } else if (type == "coatedconductor") {
        n.keys({"type", "metal", "eta", "k", "roughness", "roughnessV", "coating"}, kMapKeys);
        m.type = MaterialType::CoatedConductor;
        m.roughness = 0;
        parseConductorIndex(n, m);
        parseRoughness(n, m);
        if (n.has("coating")) m.coating = parseCoating(n["coating"]);
    } else {
        n["type"].fail("unknown material type '" + type +
                       "' (diffuse, mirror, dielectric, conductor, thindielectric, "
                       "diffusetransmission, coateddiffuse, coatedconductor, mix, interface)");
    }
    if (m.type != MaterialType::Mix && m.type != MaterialType::Interface) parseMaps(n, m, b);
    return m;
}

Affine parseTransform(const Node& n) {
    n.keys({"scale", "rotate", "translate"});
    // Applied in the order scale, rotate(s), translate.
    Affine xf;
    if (n.has("scale")) {
        const Node s = n["scale"];
        const Vec3f v = s.json().is_number() ? Vec3f(s.number()) : s.vec3();
        if (v.x == 0 || v.y == 0 || v.z == 0) s.fail("scale must not be zero");
        xf = Affine::scaling(v);
    }
    if (n.has("rotate")) {
        const Node r = n["rotate"];
        auto one = [](const Node& rot) {
            rot.keys({"axis", "degrees"});
            const Vec3f axis = rot["axis"].vec3();
            if (dot(axis, axis) == 0) rot["axis"].fail("axis must not be zero");
            return Affine::rotation(axis, rot["degrees"].number());
        };
        if (r.json().is_array())
            for (size_t i = 0; i < r.size(); ++i) xf = one(r.at(i)) * xf;
        else
            xf = one(r) * xf;
    }
    if (n.has("translate")) xf = Affine::translation(n["translate"].vec3()) * xf;
    return xf;
}

// A list of polygons with `corners` vertices each: [[[x,y,z], ...], ...].
void appendPolygons(const Node& list, int corners, Mesh& mesh) {
    for (size_t i = 0; i < list.size(); ++i) {
        const Node poly = list.at(i);
        if (poly.size() != size_t(corners))
            poly.fail("expected " + std::to_string(corners) + " vertices, got " +
                      std::to_string(poly.size()));
        Vec3f p[4];
        for (int c = 0; c < corners; ++c) p[c] = poly.at(c).vec3();
        if (corners == 4)
            appendQuad(mesh, p[0], p[1], p[2], p[3]);
        else
            appendTriangle(mesh, p[0], p[1], p[2]);
    }
}

void parseMesh(const Node& n, size_t index, Builder& b) {
    if (n.has("obj")) {
        n.keys({"obj", "material", "transform"});
        const size_t first = b.scene.meshes.size();
        const int forced = n.has("material") ? b.material(n["material"]) : -1;
        const Node obj = n["obj"];
        const std::string path = obj.file().string();  // fails with its own prefix
        try {
            appendObj(b.scene, path, forced);
        } catch (const InputError& e) {
            obj.fail(e.what());
        }
        // As for an OBJ given as the scene itself: a file with no faces (empty,
        // or not OBJ at all, whose lines tinyobjloader skips) is a mistake.
        size_t triangles = 0;
        for (size_t i = first; i < b.scene.meshes.size(); ++i)
            triangles += b.scene.meshes[i].triangleCount();
        if (triangles == 0) obj.fail("OBJ file '" + path + "' has no faces");
        if (n.has("transform")) {
            const Affine xf = parseTransform(n["transform"]);
            for (size_t i = first; i < b.scene.meshes.size(); ++i)
                transformMesh(b.scene.meshes[i], xf);
        }
        return;
    }
    n.keys({"name", "material", "quads", "triangles", "positions", "indices", "normals", "uvs",
            "emission", "twoSided", "transform"});
    Mesh mesh;
    mesh.name = n.has("name") ? n["name"].string() : "mesh" + std::to_string(index);
    mesh.material = b.material(n["material"]);
    const bool indexed = n.has("positions") || n.has("indices");
    if (indexed && (n.has("quads") || n.has("triangles")))
        n.fail("give either 'positions' and 'indices' or 'quads'/'triangles', not both");
    if (indexed) {
        const Node pos = n["positions"], idx = n["indices"];
        for (size_t i = 0; i < pos.size(); ++i) mesh.positions.push_back(pos.at(i).vec3());
        if (idx.size() % 3 != 0) idx.fail("the number of indices must be a multiple of 3");
        for (size_t i = 0; i < idx.size(); ++i) {
            const Node e = idx.at(i);
            if (!e.json().is_number_unsigned())
                e.fail(std::string("expected a non-negative integer, got ") + typeName(e.json()));
            const uint64_t v = e.json().get<uint64_t>();
            if (v >= mesh.positions.size())
                e.fail("index " + std::to_string(v) + " out of range (" +
                       std::to_string(mesh.positions.size()) + " positions)");
            mesh.indices.push_back(uint32_t(v));
        }
        if (n.has("normals")) {
            const Node nn = n["normals"];
            if (nn.size() != mesh.positions.size()) nn.fail("needs one normal per position");
            for (size_t i = 0; i < nn.size(); ++i) {
                const Vec3f v = nn.at(i).vec3();
                if (dot(v, v) == 0) nn.at(i).fail("normal must not be zero");
                mesh.normals.push_back(normalize(v));
            }
        }
        if (n.has("uvs")) {
            const Node uv = n["uvs"];
            if (uv.size() != mesh.positions.size()) uv.fail("needs one UV per position");
            for (size_t i = 0; i < uv.size(); ++i) {
                const Node e = uv.at(i);
                if (e.size() != 2) e.fail("expected [u, v]");
                mesh.uvs.push_back({e.at(0).number(), e.at(1).number()});
            }
        }
    } else {
        if (n.has("normals") || n.has("uvs"))
            n.fail("'normals' and 'uvs' need the indexed form ('positions' and 'indices')");
        if (!n.has("quads") && !n.has("triangles"))
            n.fail("needs 'quads', 'triangles', 'positions' and 'indices', or 'obj'");
        if (n.has("quads")) appendPolygons(n["quads"], 4, mesh);
        if (n.has("triangles")) appendPolygons(n["triangles"], 3, mesh);
    }
    if (n.has("emission")) mesh.emission = n["emission"].colour();
    if (n.has("twoSided")) mesh.twoSided = n["twoSided"].boolean();
    if (n.has("transform")) transformMesh(mesh, parseTransform(n["transform"]));
    b.scene.meshes.push_back(std::move(mesh));
}

// Lights reflect nothing unless given a material: they are emitters only.
int blackMaterial(Builder& b) {
    const std::string name = "(light)";
    auto it = b.materialIndex.find(name);
    if (it != b.materialIndex.end()) return it->second;
    Material m;
    m.name = name;
    m.albedo = Vec3f(0.0f);
    b.scene.materials.push_back(m);
    return b.materialIndex[name] = int(b.scene.materials.size()) - 1;
}

// An image environment map (docs/scene-format.md): pbrt-v4's equal-area
// octahedral layout, its +z world +z.
void parseEnvironmentMap(const Node& n, Builder& b) {
    n.keys({"file", "scale", "sampling"});
    const Node f = n["file"];
    const std::string path = f.file().lexically_normal().string();
    Image img;
    try {
        img = readImage(path);
    } catch (const InputError& e) {
        f.fail(e.what());
    }
    if (img.width != img.height)
        f.fail("'" + path + "' is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
               ", not square: not an equal-area octahedral map");
    for (float v : img.rgb)
        if (!std::isfinite(v) || v < 0)
            f.fail("'" + path + "' has a negative, NaN or infinite pixel");
    const float scale = n.has("scale") ? n["scale"].positive() : 1;
    EnvironmentImage env;
    if (n.has("sampling")) {
        const std::string how = n["sampling"].string();
        if (how != "luminance" && how != "uniform")
            n["sampling"].fail("must be \"luminance\" or \"uniform\", got '" + how + "'");
        env.uniformSampling = how == "uniform";
    }
    env.width = img.width;
    env.height = img.height;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) env.texels.push_back(img.at(x, y) * scale);
    b.scene.environmentMap = std::move(env);
}

// A point, spot or distant light (docs/scene-format.md), as pbrt-v4's.
void parsePunctualLight(const Node& n, const std::string& type, Builder& b) {
    PunctualLight l;
    const auto unit = [](const Node& d) {
        const Vec3f v = d.vec3();
        if (!(length(v) > 0)) d.fail("a direction must not be zero");
        return normalize(v);
    };
    if (type == "point") {
        n.keys({"name", "type", "position", "intensity"});
        l.type = PunctualLightType::Point;
        l.position = n["position"].vec3();
        l.intensity = n["intensity"].colour();
    } else if (type == "spot") {
        n.keys(
            {"name", "type", "position", "direction", "intensity", "coneAngle", "coneDeltaAngle"});
        l.type = PunctualLightType::Spot;
        l.position = n["position"].vec3();
        l.direction = unit(n["direction"]);
        l.intensity = n["intensity"].colour();
        const float cone = n.has("coneAngle") ? n["coneAngle"].number() : 30;
        const float delta = n.has("coneDeltaAngle") ? n["coneDeltaAngle"].number() : 5;
        if (!(cone > 0 && cone <= 180)) n["coneAngle"].fail("must be in (0, 180] degrees");
        if (!(delta >= 0 && delta <= cone))
            n[n.has("coneDeltaAngle") ? "coneDeltaAngle" : "coneAngle"].fail(
                "coneDeltaAngle must be in [0, coneAngle]");
        setSpotCone(l, cone, delta);
    } else {
        n.keys({"name", "type", "direction", "radiance"});
        l.type = PunctualLightType::Distant;
        l.direction = unit(n["direction"]);
        l.radiance = n["radiance"].colour();
    }
    b.scene.punctualLights.push_back(l);
}

void parseLight(const Node& n, size_t index, Builder& b) {
    const std::string lightType = n["type"].string();
    if (lightType == "point" || lightType == "spot" || lightType == "distant")
        return parsePunctualLight(n, lightType, b);
    n.keys({"name", "type", "vertices", "emission", "twoSided", "material"});
    Mesh mesh;
    mesh.name = n.has("name") ? n["name"].string() : "light" + std::to_string(index);
    const Node typeNode = n["type"];
    const std::string type = typeNode.string();
    int corners = 0;
    if (type == "quad")
        corners = 4;
    else if (type == "triangle")
        corners = 3;
    else
        typeNode.fail("unknown light type '" + type + "' (quad, triangle, point, spot, distant)");
    const Node v = n["vertices"];
    if (v.size() != size_t(corners))
        v.fail("a " + type + " light needs " + std::to_string(corners) + " vertices, got " +
               std::to_string(v.size()));
    Vec3f p[4];
    for (int c = 0; c < corners; ++c) p[c] = v.at(c).vec3();
    if (corners == 4)
        appendQuad(mesh, p[0], p[1], p[2], p[3]);
    else
        appendTriangle(mesh, p[0], p[1], p[2]);
    if (!(length(triangleNormalArea(p[0], p[1], p[2])) > 0) ||
        (corners == 4 && !(length(triangleNormalArea(p[0], p[2], p[3])) > 0)))
        v.fail("the light has zero area");
    mesh.emission = n["emission"].colour();
    if (isBlack(mesh.emission)) n["emission"].fail("a light's emission must not be black");
    if (n.has("twoSided")) mesh.twoSided = n["twoSided"].boolean();
    mesh.material = n.has("material") ? b.material(n["material"]) : blackMaterial(b);
    b.scene.meshes.push_back(std::move(mesh));
}

void parseSphere(const Node& n, Builder& b) {
    n.keys({"center", "radius", "material"});
    Sphere s;
    s.center = n["center"].vec3();
    s.radius = n["radius"].positive();
    s.material = b.material(n["material"]);
    b.scene.spheres.push_back(s);
}

Json parseText(const std::string& text, const std::string& source) {
    // nlohmann keeps the last of duplicate keys silently; a duplicate is almost
    // always a mistake, so the parser callback tracks each object's keys.
    std::vector<std::set<std::string>> open;
    std::string duplicate;
    auto callback = [&](int, Json::parse_event_t event, Json& parsed) {
        switch (event) {
            case Json::parse_event_t::object_start:
                open.emplace_back();
                break;
            case Json::parse_event_t::object_end:
                if (!open.empty()) open.pop_back();
                break;
            case Json::parse_event_t::key:
                if (!open.empty() && !open.back().insert(parsed.get<std::string>()).second &&
                    duplicate.empty())
                    duplicate = parsed.get<std::string>();
                break;
            default:
                break;
        }
        return true;
    };
    try {
        Json j = Json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
        if (!duplicate.empty()) throw InputError(source + ": duplicate key '" + duplicate + "'");
        return j;
    } catch (const Json::exception& e) {
        // A syntax error or a number too large for a double (out_of_range.406).
        // what() is "[json.exception.parse_error.101] parse error at line L, column C: ...".
        std::string why = e.what();
        if (const auto p = why.find("] "); p != std::string::npos) why = why.substr(p + 2);
        throw InputError(source + ": invalid JSON: " + why);
    }
}

}  // namespace

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

SceneDescription parseJsonScene(const std::string& text, const fs::path& baseDir,
                                const std::string& source) {
    const Json j = parseText(text, source);
    const Context ctx{source, baseDir};
    const Node root(j, "", ctx);
    root.keys({"name", "credit", "camera", "resolution", "environment", "environmentMap",
               "materials", "meshes", "lights", "spheres", "lightSampler"});
    Builder b;
    SceneDescription& s = b.scene;
    s.name = root.has("name") ? root["name"].string() : fs::path(source).stem().string();
    if (root.has("credit")) s.credit = root["credit"].string();

    const Node cam = root["camera"];
    cam.keys({"eye", "target", "up", "fovY"});
    s.camera.eye = cam["eye"].vec3();
    s.camera.target = cam["target"].vec3();
    if (cam.has("up")) s.camera.up = cam["up"].vec3();
    s.camera.fovY = cam["fovY"].number();
    if (!(s.camera.fovY > 0 && s.camera.fovY < 180))
        cam["fovY"].fail("must be in (0, 180) degrees");
    if (s.camera.eye.x == s.camera.target.x && s.camera.eye.y == s.camera.target.y &&
        s.camera.eye.z == s.camera.target.z)
        cam["target"].fail("camera target equals its eye");

    if (root.has("resolution")) {
        const Node r = root["resolution"];
        if (r.size() != 2) r.fail("expected [width, height]");
        s.resolution = {r.at(0).imageSide(), r.at(1).imageSide()};
    }
    if (root.has("environment")) s.environment = root["environment"].colour();
    if (root.has("environmentMap")) parseEnvironmentMap(root["environmentMap"], b);
    if (root.has("lightSampler")) {
        const Node ls = root["lightSampler"];
        s.defaults.lightSampler = ls.string();
        if (!lightSelectionNamed(s.defaults.lightSampler))
            ls.fail(std::string("expected one of ") + lightSelectionNames() + ", got '" +
                    s.defaults.lightSampler + "'");
    }

    if (root.has("materials")) {
        struct MixName {
            int material, slot;
            Node name;
        };
        std::vector<MixName> mixNames;
        const Node mats = root["materials"];
        mats.requireObject();
        for (const auto& [name, value] : mats.json().items()) {
            const Node m(value, mats.path() + "." + name, ctx);
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
    if (root.has("meshes")) {
        const Node meshes = root["meshes"];
        for (size_t i = 0; i < meshes.size(); ++i) parseMesh(meshes.at(i), i, b);
    }
    if (root.has("lights")) {
        const Node lights = root["lights"];
        for (size_t i = 0; i < lights.size(); ++i) parseLight(lights.at(i), i, b);
    }
    if (root.has("spheres")) {
        const Node spheres = root["spheres"];
        for (size_t i = 0; i < spheres.size(); ++i) parseSphere(spheres.at(i), b);
    }
    if (s.meshes.empty() && s.spheres.empty())
        throw InputError(source + ": the scene has no meshes, lights or spheres");
    return s;
}

SceneDescription loadJsonScene(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot open scene file '" + path + "'");
    std::ostringstream text;
    text << in.rdbuf();
    return parseJsonScene(text.str(), fs::path(path).parent_path(), path);
}

namespace {

// The shortest decimal that reads back as the same float, so written scenes
// say 0.725 rather than 0.7250000238418579.
double shortest(float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
}
Json toJson(Vec3f v) {
    return Json::array({shortest(v.x), shortest(v.y), shortest(v.z)});
}

Json coatingJson(const Coating& c) {
    Json o = {{"ior", shortest(c.eta)},
              {"roughness", shortest(c.roughness)},
              {"thickness", shortest(c.thickness)},
              {"albedo", toJson(c.albedo)},
              {"g", shortest(c.g)},
              {"maxDepth", c.maxDepth},
              {"samples", c.nSamples}};
    if (c.roughnessV >= 0) o["roughnessV"] = shortest(c.roughnessV);
    return o;
}

}  // namespace

std::string sceneToJson(const SceneDescription& s) {
    if (!s.environmentMap.empty())
        throw InputError("cannot write scene '" + s.name +
                         "': its environment map has no file to refer to");
    Json j;
    j["name"] = s.name;
    if (!s.credit.empty()) j["credit"] = s.credit;
    j["camera"] = {{"eye", toJson(s.camera.eye)},
                   {"target", toJson(s.camera.target)},
                   {"up", toJson(s.camera.up)},
                   {"fovY", shortest(s.camera.fovY)}};
    j["resolution"] = {s.resolution.x, s.resolution.y};
    j["environment"] = toJson(s.environment);
    if (!s.defaults.lightSampler.empty()) j["lightSampler"] = s.defaults.lightSampler;
    // Material names must be unique keys; repeated names get their index appended.
    std::vector<std::string> names;
    std::set<std::string> used;
    Json mats = Json::object();
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const Material& m = s.materials[i];
        std::string name = m.name.empty() ? "material" + std::to_string(i) : m.name;
        if (!used.insert(name).second) {
            name.append(1, '#').append(std::to_string(i));
            used.insert(name);
        }
        names.push_back(name);
        Json o;
        if (m.normalMap >= 0 || m.displacementTexture >= 0)
            throw InputError("cannot write material '" + m.name +
                             "': bump and normal maps have no file to refer to");
        switch (m.type) {
            case MaterialType::Diffuse:
                if (m.texture >= 0)
                    throw InputError("cannot write material '" + m.name +
                                     "': textures have no file to refer to");
                o = {{"type", "diffuse"}, {"albedo", toJson(m.albedo)}};
                break;
            case MaterialType::Mirror:
                o = {{"type", "mirror"}, {"albedo", toJson(m.albedo)}};
                break;
            case MaterialType::Dielectric:
                o = {{"type", "dielectric"}, {"ior", shortest(m.ior)}};
                if (m.roughness > 0) o["roughness"] = shortest(m.roughness);
                if (m.roughnessV >= 0) o["roughnessV"] = shortest(m.roughnessV);
                break;
            case MaterialType::Conductor:
                o = {{"type", "conductor"},
                     {"eta", toJson(m.eta)},
                     {"k", toJson(m.k)},
                     {"roughness", shortest(m.roughness)}};
                if (m.roughnessV >= 0) o["roughnessV"] = shortest(m.roughnessV);
                break;
            case MaterialType::ThinDielectric:
                o = {{"type", "thindielectric"}, {"ior", shortest(m.ior)}};
                break;
            case MaterialType::DiffuseTransmission:
                o = {{"type", "diffusetransmission"},
                     {"reflectance", toJson(m.albedo)},
                     {"transmittance", toJson(m.transmittance)}};
                break;
            case MaterialType::Mix:
                o = {{"type", "mix"}, {"amount", shortest(m.amount)}, {"materials", Json::array()}};
                break;
            case MaterialType::Interface:
                o = {{"type", "interface"}};
                break;
            case MaterialType::CoatedDiffuse:
                o = {{"type", "coateddiffuse"},
                     {"reflectance", toJson(m.albedo)},
                     {"coating", coatingJson(m.coating)}};
                break;
            case MaterialType::CoatedConductor:
                o = {{"type", "coatedconductor"},
                     {"eta", toJson(m.eta)},
                     {"k", toJson(m.k)},
                     {"roughness", shortest(m.roughness)},
                     {"coating", coatingJson(m.coating)}};
                if (m.roughnessV >= 0) o["roughnessV"] = shortest(m.roughnessV);
                break;
        }
        mats[name] = o;
    }
    // Mixes name their parts, whose names are all known now.
    for (size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].type == MaterialType::Mix)
            for (int part : s.materials[i].mix)
                mats[names[i]]["materials"].push_back(names.at(size_t(part)));
    j["materials"] = mats;
    Json meshes = Json::array();
    for (const Mesh& m : s.meshes) {
        Json o;
        o["name"] = m.name;
        o["material"] = names.at(size_t(m.material));
        Json pos = Json::array();
        for (const Vec3f& p : m.positions) pos.push_back(toJson(p));
        o["positions"] = pos;
        o["indices"] = m.indices;
        if (!m.normals.empty()) {
            Json nn = Json::array();
            for (const Vec3f& n : m.normals) nn.push_back(toJson(n));
            o["normals"] = nn;
        }
        if (!m.uvs.empty()) {
            Json uv = Json::array();
            for (const Vec2f& t : m.uvs) uv.push_back({shortest(t.x), shortest(t.y)});
            o["uvs"] = uv;
        }
        if (!isBlack(m.emission)) o["emission"] = toJson(m.emission);
        if (m.twoSided) o["twoSided"] = true;
        meshes.push_back(o);
    }
    j["meshes"] = meshes;
    if (!s.punctualLights.empty()) {
        Json lights = Json::array();
        for (const PunctualLight& l : s.punctualLights) {
            if (l.type == PunctualLightType::Point)
                lights.push_back({{"type", "point"},
                                  {"position", toJson(l.position)},
                                  {"intensity", toJson(l.intensity)}});
            else if (l.type == PunctualLightType::Spot)
                lights.push_back({{"type", "spot"},
                                  {"position", toJson(l.position)},
                                  {"direction", toJson(l.direction)},
                                  {"intensity", toJson(l.intensity)},
                                  {"coneAngle", shortest(l.coneAngle)},
                                  {"coneDeltaAngle", shortest(l.coneDeltaAngle)}});
            else
                lights.push_back({{"type", "distant"},
                                  {"direction", toJson(l.direction)},
                                  {"radiance", toJson(l.radiance)}});
        }
        j["lights"] = lights;
    }
    if (!s.spheres.empty()) {
        Json spheres = Json::array();
        for (const Sphere& sp : s.spheres)
            spheres.push_back({{"center", toJson(sp.center)},
                               {"radius", shortest(sp.radius)},
                               {"material", names.at(size_t(sp.material))}});
        j["spheres"] = spheres;
    }
    return j.dump(2) + "\n";
}

}  // namespace pathlab
