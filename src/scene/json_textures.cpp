// pathlab's JSON scene format: the "textures" section (docs/scene-format.md),
// pbrt-v4's texture classes spelled in JSON. Each texture becomes nodes of
// SceneDescription::shadingTextures — the very graph the pbrt-v4 loader
// builds (scene/pbrt/world_texture_classes.cpp) and the renderer evaluates
// (scene/textures/shading_texture.h), with pbrt-v4's defaults — so a JSON
// scene and the equivalent .pbrt file render the same image.
#include <algorithm>
#include <cctype>
#include <string>

#include "scene/json_node.h"
#include "scene/pbrt/transform.h"
#include "scene/texture_loader.h"
#include "scene/textures/image_encoding.h"

namespace pathlab::jsonscene {
namespace {

int addNode(Builder& b, const ShadingTexture& node) {
    b.scene.shadingTextures.push_back(node);
    return int(b.scene.shadingTextures.size()) - 1;
}

// A constant, a number for a float texture, a colour (or one number) else.
Vec3f constantValue(const Node& n, bool isFloat) {
    return isFloat ? Vec3f(n.number()) : n.colour();
}

// Input `key` of texture t: the name of an earlier texture of the same kind,
// or a constant (`fallback` when absent), which becomes a node of its own as
// in the pbrt-v4 loader.
int input(const Node& t, const char* key, bool isFloat, Vec3f fallback, Builder& b) {
    ShadingTexture constant;
    constant.isFloat = isFloat;
    constant.value = fallback;
    if (t.has(key)) {
        const Node n = t[key];
        if (const int named = textureParam(n, b, isFloat); named >= 0) return named;
        constant.value = constantValue(n, isFloat);
    }
    return addNode(b, constant);
}

// The texture space of a spatial mapping: "transform" places it in the world
// as a shape's would (pbrt-v4: the CTM at the Texture directive); lookups
// take its inverse.
Affine worldToTexture(const Node& n) {
    const Affine xf = parseTransform(n);
    const float translation[3] = {xf.t.x, xf.t.y, xf.t.z};
    pbrt::Matrix4 m;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m.m[i][j] = xf.m[i][j];
        m.m[i][3] = translation[i];
    }
    const auto inverse = m.inverse();
    if (!inverse) n.fail("the transform is singular");
    return inverse->toAffine();
}

// "mapping": "uv" (the default), "spherical", "cylindrical" or "planar", or
// an object with "type" and that mapping's parameters (pbrt-v4's
// TextureMapping2D::Create and its defaults).
TextureMapping parseMapping(const Node& t) {
    TextureMapping m;
    if (!t.has("mapping")) return m;
    const Node n = t["mapping"];
    const bool object = n.json().is_object();
    const Node typeNode = object ? n["type"] : n;
    const std::string type = typeNode.string();
    const auto number = [&](const char* key, float fallback) {
        return object && n.has(key) ? n[key].number() : fallback;
    };
    if (type == "uv") {
        if (object) n.keys({"type", "uscale", "vscale", "udelta", "vdelta"});
        m.type = UvMapping::Uv;
        m.su = number("uscale", 1), m.sv = number("vscale", 1);
        m.du = number("udelta", 0), m.dv = number("vdelta", 0);
        return m;
    }
    if (type == "spherical" || type == "cylindrical") {
        if (object) n.keys({"type", "transform"});
        m.type = type == "spherical" ? UvMapping::Spherical : UvMapping::Cylindrical;
    } else if (type == "planar") {
        if (object) n.keys({"type", "v1", "v2", "udelta", "vdelta", "transform"});
        m.type = UvMapping::Planar;
        if (object && n.has("v1")) m.v1 = n["v1"].vec3();
        if (object && n.has("v2")) m.v2 = n["v2"].vec3();
        m.du = number("udelta", 0), m.dv = number("vdelta", 0);
    } else {
        typeNode.fail("unknown mapping '" + type + "' (uv, spherical, cylindrical or planar)");
    }
    if (object && n.has("transform")) m.worldToTexture = worldToTexture(n["transform"]);
    return m;
}

bool isPng(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".png";
}

// The image of an imagemap, read once per file and encoding: pbrt-v4's
// default encoding is sRGB for 8-bit files, linear for others (float files
// ignore it).
int imageFile(const Node& t, Builder& b) {
    const Node file = t["file"];
    const fs::path path = file.file().lexically_normal();
    std::string text = isPng(path) ? "sRGB" : "linear";
    if (t.has("encoding")) text = t["encoding"].string();
    const auto encoding = parseImageEncoding(text);
    if (!encoding)
        t["encoding"].fail("unknown encoding '" + text + "' (sRGB, linear or \"gamma G\")");
    // loadImage's keys: the sRGB decoding is the path alone.
    const std::string key = path.string() + (text == "sRGB" ? "" : "\n" + text);
    if (const auto it = b.textureIndex.find(key); it != b.textureIndex.end()) return it->second;
    Texture image;
    try {
        image = loadTexture(path.string());
    } catch (const InputError& e) {
        file.fail(e.what());
    }
    if (isPng(path)) reencodeTexels(image, *encoding);
    b.scene.textures.push_back(std::move(image));
    return b.textureIndex.emplace(key, int(b.scene.textures.size()) - 1).first->second;
}

void parseImageMap(const Node& t, ShadingTexture& node, Builder& b) {
    t.keys({"type", "float", "file", "encoding", "filter", "wrap", "scale", "invert", "mapping"});
    node.kind = TextureKind::Image;
    node.mapping = parseMapping(t);
    node.image = imageFile(t, b);
    if (t.has("filter")) {
        // pbrt-v4's trilinear and EWA filters are done as bilinear on the
        // finest level, as for .pbrt files (docs/pbrt-format.md).
        const std::string filter = t["filter"].string();
        if (filter == "point")
            node.pointFilter = true;
        else if (filter != "bilinear" && filter != "trilinear" && filter != "ewa")
            t["filter"].fail("unknown filter '" + filter + "' (point, bilinear, trilinear, ewa)");
    }
    if (t.has("wrap")) {
        const std::string wrap = t["wrap"].string();
        const std::optional<TextureWrap> named = textureWrapNamed(wrap);
        if (!named) t["wrap"].fail("unknown wrap '" + wrap + "' (repeat, black or clamp)");
        node.wrap = *named;
    }
    if (t.has("scale")) node.scale = t["scale"].number();
    if (t.has("invert")) node.invert = t["invert"].boolean();
}

ShadingTexture parseTexture(const Node& t, Builder& b) {
    ShadingTexture node;
    node.isFloat = t.has("float") && t["float"].boolean();
    const bool f = node.isFloat;
    const std::string type = t["type"].string();
    const Vec3f zero(0.0f), one(1.0f);
    if (type == "constant") {
        t.keys({"type", "float", "value"});
        node.value = t.has("value") ? constantValue(t["value"], f) : one;
    } else if (type == "scale") {
        t.keys({"type", "float", "tex", "scale"});
        node.kind = TextureKind::Scale;
        node.inputs[0] = input(t, "tex", f, one, b);
        node.inputs[1] = input(t, "scale", true, one, b);
    } else if (type == "mix") {
        t.keys({"type", "float", "tex1", "tex2", "amount"});
        node.kind = TextureKind::Mix;
        node.inputs[0] = input(t, "tex1", f, zero, b);
        node.inputs[1] = input(t, "tex2", f, one, b);
        node.inputs[2] = input(t, "amount", true, Vec3f(0.5f), b);
    } else if (type == "checkerboard") {
        t.keys({"type", "float", "tex1", "tex2", "mapping"});
        node.kind = TextureKind::Checkerboard;
        node.mapping = parseMapping(t);
        node.inputs[0] = input(t, "tex1", f, one, b);
        node.inputs[1] = input(t, "tex2", f, zero, b);
    } else if (type == "bilerp") {
        t.keys({"type", "float", "v00", "v01", "v10", "v11", "mapping"});
        node.kind = TextureKind::Bilerp;
        node.mapping = parseMapping(t);
        const char* corners[4] = {"v00", "v01", "v10", "v11"};
        for (int i = 0; i < 4; ++i)
            node.corners[i] = t.has(corners[i]) ? constantValue(t[corners[i]], f)
                                                : Vec3f(i % 2 == 0 ? 0.0f : 1.0f);
    } else if (type == "imagemap") {
        parseImageMap(t, node, b);
    } else {
        t["type"].fail("unknown texture type '" + type +
                       "' (constant, imagemap, checkerboard, scale, mix, bilerp)");
    }
    return node;
}

}  // namespace

void parseTextures(const Node& textures, Builder& b) {
    textures.requireObject();
    for (const auto& [name, value] : textures.json().items()) {
        const ShadingTexture node = parseTexture(textures[name.c_str()], b);
        // Registered after its inputs: a texture cannot refer to itself.
        b.namedTextures[name] = {addNode(b, node), node.isFloat};
    }
}

int textureParam(const Node& n, const Builder& b, bool isFloat) {
    if (!n.json().is_string()) return -1;
    const std::string name = n.string();
    const auto it = b.namedTextures.find(name);
    if (it == b.namedTextures.end())
        n.fail("no texture named '" + name + "' in \"textures\" (before this use)");
    if (it->second.isFloat != isFloat)
        n.fail(std::string("needs a ") + (isFloat ? "float" : "spectrum") + " texture, but '" +
               name + "' is a " + (isFloat ? "spectrum" : "float") + " texture");
    return it->second.node;
}

int alphaParam(const Node& n, Builder& b) {
    if (const int tex = textureParam(n, b, true); tex >= 0) return tex;
    const float a = n.number();
    if (!(a >= 0 && a <= 1)) n.fail("must be in [0, 1] or name a float texture");
    if (a == 1) return -1;  // opaque: no test at all, as in the pbrt-v4 loader
    ShadingTexture constant;
    constant.isFloat = true;
    constant.value = Vec3f(a);
    return addNode(b, constant);
}

}  // namespace pathlab::jsonscene
