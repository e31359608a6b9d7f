// The display of a linear image: exposure, then a tone curve, then 8-bit PNG.
// Display only: the sums behind the image never see it.
#pragma once

#include <string>

#include "core/image.h"
#include "view/view_settings.h"

namespace pathlab::view {

// One linear value to a display value in [0, 1]: × 2^exposure, then
//   linear  clamped, written as is (no transfer function);
//   srgb    clamped, the sRGB transfer function (IEC 61966-2-1);
//   aces    Narkowicz's fit of the ACES filmic curve ("ACES Filmic Tone
//           Mapping Curve", 2015), then sRGB.
// NaN and negative values show as 0.
float toneMapValue(float linear, float scale, ToneMap toneMap);

// The image as an 8-bit RGB PNG file of its display values.
std::string encodeDisplayPng(const Image& image, float exposure, ToneMap toneMap);

}  // namespace pathlab::view
