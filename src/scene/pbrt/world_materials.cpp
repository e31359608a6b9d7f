// Textures and lights (pbrt-v4 File Format, "Textures", "Lights", "Area
// Lights"; materials are in materials.cpp). This stage maps what pathlab's
// renderer already has with pbrt-v4's meaning — diffuse area lights, a
// constant infinite light — and reports the rest as unsupported (substituted
// under --lenient).
#include <cmath>

#include "core/image.h"
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

void markAllUsed(const ParamSet& ps) {
    for (const Param& p : ps.all()) p.used = true;
}

}  // namespace

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

void areaLightSource(ImportState& st, const std::string& type, const ParamSet& given,
                     const SourceLocation& where) {
    if (type != "diffuse")
        throw errorAt(where, "unknown area light '" + type + "' (pbrt-v4 has \"diffuse\")");
    const ParamSet ps = given.withDefaults(st.gs.attributes["light"]);
    AreaLight light;
    light.where = where;
    // pbrt-v4: L defaults to the colour space's illuminant, which is RGB
    // (1, 1, 1), and an RGB L is normalised to its luminance's nits, which
    // leaves the RGB value itself.
    if (auto L = rgbParam(st, ps, "L")) light.radiance = *L;
    light.radiance *= ps.getFloat("scale", 1);
    light.twoSided = ps.getBool("twosided", false);
    if (ps.find("power")) st.unsupported(where, "area light power", "the radiance as given");
    if (ps.find("filename")) st.unsupported(where, "image area lights", "uniform emission");
    if (ps.find("alpha")) st.unsupported(where, "area light alpha", "an opaque light");
    st.checkUnused(ps, "AreaLightSource");
    if (light.radiance.x < 0 || light.radiance.y < 0 || light.radiance.z < 0)
        throw errorAt(where, "AreaLightSource: L must not be negative");
    st.gs.areaLight = light;
}

void lightSource(ImportState& st, const std::string& type, const ParamSet& given,
                 const SourceLocation& where) {
    const ParamSet ps = given.withDefaults(st.gs.attributes["light"]);
    if (type != "infinite") {
        st.unsupported(where, "LightSource '" + type + "'", "no light");
        markAllUsed(ps);
        return;
    }
    const float scale = ps.getFloat("scale", 1);
    const std::string file = ps.getString("filename", "");
    Vec3f L(1.0f);
    if (auto rgb = rgbParam(st, ps, "L")) L = *rgb;
    if (!file.empty()) {
        // An image map's importance sampling is not there yet. Its
        // equal-area octahedral texels all subtend the same solid angle, so
        // their mean is the map's mean radiance: the constant light that
        // stands in for it.
        st.unsupported(where, "image infinite lights", "a constant sky of the map's mean radiance");
        const Image img = readImage(st.resolveFile(file, st.mainDir, where));
        Vec3f sum(0.0f);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) sum += img.at(x, y);
        L = sum / float(std::max(1, img.width * img.height));
    }
    if (ps.find("illuminance"))
        st.unsupported(where, "infinite light illuminance", "the radiance as given");
    if (ps.find("portal")) st.unsupported(where, "infinite light portals", "no portal");
    st.checkUnused(ps, "LightSource \"infinite\"");
    st.result.scene.environment += L * scale;
}

}  // namespace pathlab::pbrt
