// The built-in studies behind `pathlab study --preset NAME`.
#pragma once

#include <string>
#include <vector>

#include "study/spec.h"

namespace pathlab {

// "seed": the presentation's study, sized to finish within ten minutes on two
//         cores (see docs/study.md for what was traded and why);
// "quick": a small study that finishes within a minute, for tests and trials;
// "full": the paper-sized study for bigger machines;
// "suite", "quick-suite": the verdict across scenes (study/suite_presets.h).
// Throws InputError for any other name.
StudySpec presetSpec(const std::string& name);

std::vector<std::string> presetNames();

}  // namespace pathlab
