// Colour maps for error images.
#pragma once

#include <array>

namespace pathlab {

// The magma colour map at `value` in [0,1] (clamped), as sRGB-encoded values
// in [0,1]: perceptually uniform and readable in grey scale, the map FLIP's
// error images use.
std::array<float, 3> magmaSrgb(float value);

}  // namespace pathlab
