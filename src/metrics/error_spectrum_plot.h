// A small picture of an error spectrum, for `pathlab compare --error-spectrum
// OUT.png`: power on a log axis against frequency on a linear axis, drawn
// without a plotting library (the CSV is there for real figures).
#pragma once

#include "core/image.h"
#include "metrics/power_spectrum.h"

namespace pathlab {

// 480×320 pixels on white. x: 0 to 0.5 cycles per pixel (Nyquist), a dotted
// vertical line at kLowFrequencyLimit; y: log10 of the power over whole
// decades (a faint line at each) that hold rings 1..n/2; dashed grey: the
// total power, the level of white noise with the same variance; blue: the
// spectrum. The DC ring is not drawn.
Image errorSpectrumPlot(const RadialPowerSpectrum& spectrum);

}  // namespace pathlab
