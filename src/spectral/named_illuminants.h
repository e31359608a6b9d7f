// The CIE standard illuminants under pbrt-v4's names ("stdillum-A",
// "stdillum-D65", "stdillum-F1" … "stdillum-F12", and the other illuminants
// colord ships: B, C, D55, D93, E), normalised as pbrt-v4 normalises them: to
// luminance Y = 1 over the CIE 1931 observer. Data: CIE 15:2004 through
// Debian's colord-data (cie_data.h).
#pragma once

#include <string>
#include <string_view>

#include "spectral/piecewise_linear_spectrum.h"

namespace pathlab::spectral {

// The illuminant of that name, or nullptr.
const PiecewiseLinearSpectrum* namedIlluminant(std::string_view name);
// Every name, comma-separated, for error messages.
std::string namedIlluminantList();

}  // namespace pathlab::spectral
