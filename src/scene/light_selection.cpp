#include "scene/light_selection.h"

#include "core/error.h"

namespace pathlab {

std::optional<LightSelection> lightSelectionNamed(std::string_view name) {
    if (name == "uniform") return LightSelection::Uniform;
    if (name == "power") return LightSelection::Power;
    if (name == "bvh") return LightSelection::Bvh;
    return std::nullopt;
}

const char* lightSelectionName(LightSelection s) {
    switch (s) {
        case LightSelection::Uniform:
            return "uniform";
        case LightSelection::Power:
            return "power";
        case LightSelection::Bvh:
            return "bvh";
    }
    return "power";
}

const char* lightSelectionNames() {
    return "uniform, power, bvh";
}

LightSelection parseLightSelection(const std::string& name, const std::string& what) {
    if (name.empty()) return LightSelection::Power;
    if (const auto s = lightSelectionNamed(name)) return *s;
    throw InputError(what + " must be one of " + lightSelectionNames() + ", got '" + name + "'");
}

}  // namespace pathlab
