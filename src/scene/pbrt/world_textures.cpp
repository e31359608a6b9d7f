// Textures, and the RGB parameters that materials and lights share (pbrt-v4
// File Format, "Textures"). Textures are not supported yet: each is reported
// (substituted under --lenient by the defaults of the parameters that use it).
// Materials: materials.cpp; lights: world_lights.cpp.
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

}  // namespace pathlab::pbrt
