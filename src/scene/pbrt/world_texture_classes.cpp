// The Texture directive (pbrt-v4 File Format, "Textures"; pbrt-v4's
// textures.cpp): constant, scale, mix, checkerboard (2D), bilerp and imagemap,
// with the uv, spherical, cylindrical and planar mappings, as nodes of
// SceneDescription::shadingTextures; and the references to named textures
// that material parameters make.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iterator>

#include "core/error.h"
#include "scene/pbrt/parser_state.h"
#include "scene/texture_loader.h"
#include "scene/textures/image_encoding.h"

namespace pathlab::pbrt {
namespace {

int addNode(ImportState& st, const ShadingTexture& node) {
    st.result.scene.shadingTextures.push_back(node);
    return int(st.result.scene.shadingTextures.size()) - 1;
}

int constantNode(ImportState& st, Vec3f value, bool isFloat) {
    ShadingTexture node;
    node.kind = TextureKind::Constant;
    node.isFloat = isFloat;
    node.value = value;
    return addNode(st, node);
}

const char* kindName(bool isFloat) {
    return isFloat ? "float" : "spectrum";
}

// The texture a "texture NAME" parameter names, of the kind it needs.
int namedTexture(ImportState& st, const Param& p, bool isFloat) {
    if (p.strings.size() != 1)
        throw errorAt(p.where, "parameter '" + p.name + "' needs one texture name");
    const std::string& name = p.strings[0];
    const auto& mine = isFloat ? st.floatTextures : st.spectrumTextures;
    const auto& other = isFloat ? st.spectrumTextures : st.floatTextures;
    if (const auto it = mine.find(name); it != mine.end()) return it->second;
    if (other.count(name))
        throw errorAt(p.where, "parameter '" + p.name + "' needs a " + kindName(isFloat) +
                                   " texture, but '" + name + "' is a " + kindName(!isFloat) +
                                   " texture");
    throw errorAt(p.where, "parameter '" + p.name + "': no " + kindName(isFloat) +
                               " texture named '" + name + "' defined before it");
}

// A texture's input: a named texture, or a constant (`fallback` when absent).
int textureInput(ImportState& st, const ParamSet& ps, const std::string& name, bool isFloat,
                 Vec3f fallback) {
    const Param* p = ps.find(name);
    if (p && p->type == ParamType::Texture) return namedTexture(st, *p, isFloat);
    if (isFloat) return constantNode(st, Vec3f(ps.getFloat(name, fallback.x)), true);
    return constantNode(st, rgbParam(st, ps, name).value_or(fallback), false);
}

Vec3f constantValue(ImportState& st, const ParamSet& ps, const std::string& name, bool isFloat,
                    float fallback) {
    if (isFloat) return Vec3f(ps.getFloat(name, fallback));
    return rgbParam(st, ps, name).value_or(Vec3f(fallback));
}

// pbrt-v4's TextureMapping2D::Create; the spatial mappings read the point in
// the texture's own space (the inverse of the CTM at the directive).
TextureMapping readMapping(ImportState& st, const ParamSet& ps, const SourceLocation& where) {
    TextureMapping m;
    const std::optional<Matrix4> inverse = st.gs.ctm.inverse();
    if (!inverse || !st.gs.ctm.isAffine())
        throw errorAt(where, "Texture: the current transformation is singular or projective");
    m.worldToTexture = inverse->toAffine();
    const std::string type = ps.getString("mapping", "uv");
    if (type == "uv") {
        m.type = UvMapping::Uv;
        m.su = ps.getFloat("uscale", 1), m.sv = ps.getFloat("vscale", 1);
        m.du = ps.getFloat("udelta", 0), m.dv = ps.getFloat("vdelta", 0);
    } else if (type == "spherical") {
        m.type = UvMapping::Spherical;
    } else if (type == "cylindrical") {
        m.type = UvMapping::Cylindrical;
    } else if (type == "planar") {
        m.type = UvMapping::Planar;
        m.v1 = ps.getVector3("v1").value_or(Vec3f(1, 0, 0));
        m.v2 = ps.getVector3("v2").value_or(Vec3f(0, 1, 0));
        m.du = ps.getFloat("udelta", 0), m.dv = ps.getFloat("vdelta", 0);
    } else {
        throw errorAt(where, "Texture: unknown mapping '" + type +
                                 "' (uv, spherical, cylindrical or planar)");
    }
    return m;
}

bool isPng(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".png";
}

// The image of an imagemap, read once per file and encoding.
int textureImage(ImportState& st, const ParamSet& ps, const SourceLocation& where,
                 const std::string& includingDir) {
    const Param* file = ps.find("filename");
    if (!file || file->type != ParamType::String || file->strings.size() != 1)
        throw errorAt(where, "Texture \"imagemap\" needs a \"string filename\"");
    const std::string path = st.resolveFile(file->strings[0], includingDir, file->where);
    // pbrt-v4: 8-bit images default to sRGB, others to linear (float files
    // ignore the encoding).
    const std::string text = ps.getString("encoding", isPng(path) ? "sRGB" : "linear");
    const std::optional<ImageEncoding> encoding = parseImageEncoding(text);
    if (!encoding)
        throw errorAt(where,
                      "Texture: unknown encoding '" + text + "' (sRGB, linear or \"gamma G\")");
    const std::string key = path + "\n" + text;
    if (const auto it = st.textureImages.find(key); it != st.textureImages.end()) return it->second;
    Texture image;
    try {
        image = loadTexture(path);
    } catch (const InputError& e) {
        throw errorAt(file->where, e.what());
    }
    if (isPng(path)) reencodeTexels(image, *encoding);
    st.result.scene.textures.push_back(std::move(image));
    const int index = int(st.result.scene.textures.size()) - 1;
    st.textureImages[key] = index;
    return index;
}

void readImageMap(ImportState& st, const ParamSet& ps, const SourceLocation& where,
                  const std::string& includingDir, ShadingTexture& node) {
    node.kind = TextureKind::Image;
    node.mapping = readMapping(st, ps, where);
    node.image = textureImage(st, ps, where, includingDir);
    const std::string filter = ps.getString("filter", "bilinear");
    if (filter == "point") {
        node.pointFilter = true;
    } else if (filter == "trilinear" || filter == "ewa" || filter == "EWA") {
        st.note(where, "filter '" + filter + "' is done as bilinear on the finest level");
    } else if (filter != "bilinear") {
        throw errorAt(
            where, "Texture: unknown filter '" + filter + "' (point, bilinear, trilinear or ewa)");
    }
    ps.ignore("maxanisotropy");  // EWA's
    const std::string wrap = ps.getString("wrap", "repeat");
    const std::optional<TextureWrap> named = textureWrapNamed(wrap);
    if (!named)
        throw errorAt(where, "Texture: unknown wrap '" + wrap + "' (repeat, black or clamp)");
    node.wrap = *named;
    node.scale = ps.getFloat("scale", 1);
    node.invert = ps.getBool("invert", false);
}

void markAllUsed(const ParamSet& ps) {
    for (const Param& p : ps.all()) p.used = true;
}

}  // namespace

void texture(ImportState& st, const std::string& name, const std::string& colorType,
             const std::string& type, const ParamSet& given, const SourceLocation& where,
             const std::string& includingDir) {
    if (colorType != "spectrum" && colorType != "float" && colorType != "color")
        throw errorAt(where, "Texture '" + name +
                                 "': type must be \"spectrum\" or \"float\", got '" + colorType +
                                 "'");
    const bool isFloat = colorType == "float";
    auto& table = isFloat ? st.floatTextures : st.spectrumTextures;
    if (table.count(name)) throw errorAt(where, "Texture '" + name + "' is already defined");
    const ParamSet ps = given.withDefaults(st.gs.attributes["texture"]);
    ShadingTexture node;
    node.isFloat = isFloat;
    const Vec3f zero(0.0f), one(1.0f);
    if (type == "constant") {
        node.value = constantValue(st, ps, "value", isFloat, 1);
    } else if (type == "scale") {
        node.kind = TextureKind::Scale;
        node.inputs[0] = textureInput(st, ps, "tex", isFloat, one);
        node.inputs[1] = textureInput(st, ps, "scale", true, one);
    } else if (type == "mix") {
        node.kind = TextureKind::Mix;
        node.inputs[0] = textureInput(st, ps, "tex1", isFloat, zero);
        node.inputs[1] = textureInput(st, ps, "tex2", isFloat, one);
        node.inputs[2] = textureInput(st, ps, "amount", true, Vec3f(0.5f));
    } else if (type == "checkerboard") {
        node.kind = TextureKind::Checkerboard;
        if (ps.getInt("dimension", 2) != 2) {
            st.unsupported(where, "a 3D checkerboard", "a 2D one");
        }
        node.mapping = readMapping(st, ps, where);
        node.inputs[0] = textureInput(st, ps, "tex1", isFloat, one);
        node.inputs[1] = textureInput(st, ps, "tex2", isFloat, zero);
    } else if (type == "bilerp") {
        node.kind = TextureKind::Bilerp;
        node.mapping = readMapping(st, ps, where);
        const char* corners[4] = {"v00", "v01", "v10", "v11"};
        for (int i = 0; i < 4; ++i)
            node.corners[i] = constantValue(st, ps, corners[i], isFloat, i % 2 == 0 ? 0 : 1);
    } else if (type == "imagemap") {
        readImageMap(st, ps, where, includingDir, node);
    } else {
        static const char* const kOthers[] = {"directionmix", "dots",   "fbm", "wrinkled",
                                              "windy",        "marble", "ptex"};
        if (std::find(std::begin(kOthers), std::end(kOthers), type) == std::end(kOthers))
            throw errorAt(where, "Texture '" + name + "': unknown texture class '" + type + "'");
        st.unsupported(where, "Texture class '" + type + "'", "a constant 0.5");
        markAllUsed(ps);
        node.value = Vec3f(0.5f);
    }
    st.checkUnused(ps, "Texture \"" + type + "\"");
    table[name] = addNode(st, node);
}

std::optional<int> spectrumTextureParam(ImportState& st, const ParamSet& ps,
                                        const std::string& name) {
    const Param* p = ps.find(name);
    if (!p || p->type != ParamType::Texture) return std::nullopt;
    return namedTexture(st, *p, false);
}

std::optional<int> floatTextureParam(ImportState& st, const ParamSet& ps, const std::string& name) {
    const Param* p = ps.find(name);
    if (!p || p->type != ParamType::Texture) return std::nullopt;
    return namedTexture(st, *p, true);
}

}  // namespace pathlab::pbrt
