// The RGB parameters that materials and lights share (pbrt-v4 File Format,
// "Parameter lists"). A "texture" value is read by the parameters that take
// textures (world_texture_classes.cpp); elsewhere it is unsupported.
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

}  // namespace pathlab::pbrt
