// The table of sigmoid-polynomial coefficients over linear sRGB (Jakob &
// Hanika 2019, §4): for each colour, indexed by its largest component's
// channel l, that component z, and the other two relative to it, x = rgb[l+1]/z
// and y = rgb[l+2]/z (both in [0,1]), the coefficients the optimiser found.
// z is sampled on smoothstep(smoothstep(k/(n−1))), denser near black and
// near full brightness where the spectra change fastest (paper §4). A lookup
// interpolates the coefficients trilinearly.
//
// Each (l, x, y) column is solved by continuation along z, starting from a
// grey-ish colour at k = n/5 with the constant ½ spectrum and moving outwards
// both ways, each fit starting from its neighbour's solution (paper §4).
// Columns are independent, so the table is the same whatever the threads.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "spectral/rgb_spectrum.h"

namespace pathlab::spectral {

struct RgbToSpectrumTable {
    int resolution = 0;
    std::vector<float> zNodes;        // resolution values, increasing, 0 to 1
    std::vector<float> coefficients;  // [3][z][y][x][3], in nm (toNanometres)
    // The largest ΔE (CIE 1976) any table node was left with by the optimiser.
    float worstDeltaE = 0;

    SigmoidPolynomial lookup(Vec3f rgb) const;  // rgb in [0,1]³
    size_t index(int l, int zi, int yi, int xi) const {
        return (((size_t(l) * resolution + zi) * resolution + yi) * resolution + xi) * 3;
    }
};

// Runs the optimiser over a resolution³ × 3 grid (resolution ≥ 3).
RgbToSpectrumTable makeRgbToSpectrumTable(int resolution);

// Reads `file` if it holds a valid table of this resolution (its header,
// fingerprint of the CIE data and checksum all match), else makes one and
// writes it atomically; an unwritable cache is not an error.
std::shared_ptr<const RgbToSpectrumTable> loadOrCreateRgbToSpectrumTable(
    const std::filesystem::path& file, int resolution);

inline constexpr int kRgbToSpectrumResolution = 64;
// The process-wide table: cacheDirectory()/rgb-to-spectrum-srgb-64.bin.
const RgbToSpectrumTable& defaultRgbToSpectrumTable();

}  // namespace pathlab::spectral
