// pbrt-v4's named spectra of metals and glasses, reduced once to the values
// pathlab's RGB renderer uses (scripts/named_spectra_rgb.py made the table:
// the source data and the method are described there and in
// docs/pbrt-format.md).
#pragma once

#include <optional>
#include <string>

#include "core/math.h"

namespace pathlab {

// "metal-Au-eta", "metal-Au-k", … (Ag, Al, Au, Cu, CuZn, MgO, TiO2): the
// spectrum projected to linear sRGB under D65.
std::optional<Vec3f> namedMetalSpectrum(const std::string& name);
// "glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5",
// "glass-F10", "glass-F11": the index at the d line, 587.56 nm.
std::optional<float> namedGlassIor(const std::string& name);
// The names above, for error messages.
const char* namedSpectraList();

}  // namespace pathlab
