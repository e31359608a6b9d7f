// Tabulated CIE data, generated at build time from Debian's colord-data
// (scripts/make_cie_tables.py reads /usr/share/colord; docs/spectral.md):
// the CIE 1931 2° standard observer's colour-matching functions and the CIE
// standard illuminants, as published in CIE 15:2004 ("Colorimetry", 3rd ed.),
// at 5 nm. Nothing here is typed in by hand.
#pragma once

namespace pathlab::spectral::cie_data {

// A spectrum sampled every `step` nm from `first`: values[i] at first + i·step.
struct TabulatedSpectrum {
    const char* name;
    double first, step;
    int count;
    const double* values;
};

// x̄, ȳ, z̄ at 360, 365, …, 830 nm.
inline constexpr double kCmfFirst = 360, kCmfStep = 5;
inline constexpr int kCmfCount = 95;
extern const double kCmfX[kCmfCount], kCmfY[kCmfCount], kCmfZ[kCmfCount];

// The standard illuminants under pbrt-v4's names ("stdillum-A", "stdillum-D65",
// "stdillum-F1" … "stdillum-F12", and colord's others), as published (not
// normalised: D65 is 100 at 560 nm in CIE 15 and 1 in colord's files).
extern const TabulatedSpectrum kIlluminants[];
extern const int kIlluminantCount;

// The CIE daylight basis S0, S1, S2 at 300, 305, …, 830 nm (CIE 15:2004 table
// T.2): a daylight illuminant of chromaticity (x, y) is S0 + M1 S1 + M2 S2.
inline constexpr double kDaylightFirst = 300, kDaylightStep = 5;
inline constexpr int kDaylightCount = 107;
extern const double kDaylightS0[kDaylightCount], kDaylightS1[kDaylightCount],
    kDaylightS2[kDaylightCount];

}  // namespace pathlab::spectral::cie_data
