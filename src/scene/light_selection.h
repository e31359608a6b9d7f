// The strategies by which next-event estimation may choose the light it
// samples (render/light_sampling/light_chooser.h), by name: what a scene file
// (JSON "lightSampler") or the command line (--light-sampler) asks for.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace pathlab {

enum class LightSelection { Power, Uniform, Bvh };

// "uniform", "power" or "bvh"; nothing for any other name.
std::optional<LightSelection> lightSelectionNamed(std::string_view name);
const char* lightSelectionName(LightSelection s);
// The accepted names, for messages: "uniform, power, bvh".
const char* lightSelectionNames();
// lightSelectionNamed, "" meaning the default (power); throws InputError
// naming `what` (the option or key) for any other name.
LightSelection parseLightSelection(const std::string& name, const std::string& what);

}  // namespace pathlab
